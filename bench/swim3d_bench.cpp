// The 3D swimmer's speed (issue 40 part 5; docs/three-d.md "Speed"):
//  - BM_Swim3dStep/<cells across the bell>/<threads>: coupled steps of the built-in bell (the slice's
//    4 cm bell as a shell, edges half a cell) from rest, in a tank four bell diameters wide, deep
//    and tall solved on its quarter: at 24 cells across, the 48 × 96 × 48 quarter tank
//    (96 × 96 × 96 whole). One iteration is one coupled step (one frame per step). Counters: ms per step and its split
//    (transfer, fluid, Krylov), GMRES iterations per step, simulated seconds per wall second
//    (real_time_factor; the target is ≥ 0.1), markers, solved cells, the fluid's estimated
//    memory (MB). The first steps start from rest: the stroke's middle takes ~10 % more GMRES
//    iterations (`examples/swim_3d` over whole cycles gives the figure averaged over the stroke).
#include <benchmark/benchmark.h>

#include "jellysim/swim3d/swimmer_3d.hpp"

namespace {

using namespace jellysim::swim3d;

Swim3dSpec bench_spec(int across, int threads) {
  Swim3dSpec s;
  const double D = s.bell.slice.diameter_m;
  s.tank_size_m = {4 * D, 4 * D, 4 * D};
  s.cells = {4 * across, 4 * across, 4 * across};
  s.aperture_height_m = 1.25 * D;
  s.bell.target_edge_m = 0.5 * D / across;  // Peskin's rule: markers half a cell apart
  s.frames_per_cycle = 100000;  // a frame per coupled step
  s.threads = threads;
  return s;
}

void BM_Swim3dStep(benchmark::State& state) {
  const Swim3dSpec spec = bench_spec(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Swimmer3d swimmer(spec);
  for (auto _ : state) benchmark::DoNotOptimize(swimmer.advance_frame().centroid);
  const Swim3dTimings& t = swimmer.timings();
  const double n = t.steps;
  const auto g = solved_grid(spec);
  state.counters["steps"] = n;
  state.counters["ms_per_step"] = 1e3 * t.total_s / n;
  state.counters["transfer_ms"] = 1e3 * t.transfer_s / n;
  state.counters["fluid_ms"] = 1e3 * t.fluid_s / n;
  state.counters["krylov_ms"] = 1e3 * t.krylov_s / n;
  state.counters["gmres_iterations"] = t.krylov_iterations / n;
  state.counters["real_time_factor"] = swimmer.time_s() / t.total_s;
  state.counters["markers"] = static_cast<double>(swimmer.markers().size());
  state.counters["cells"] = static_cast<double>(g.cell_count());
  state.counters["memory_MB"] =
      static_cast<double>(jellysim::fluid3d::estimated_memory_bytes_3d(g, fluid_settings(spec))) / 1e6;
}
// 8, 16 and 24 cells across the bell (the last the target), one and two threads.
BENCHMARK(BM_Swim3dStep)
    ->ArgsProduct({{8, 16}, {1, 2}})
    ->Iterations(40)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Swim3dStep)->ArgsProduct({{24}, {1, 2}})->Iterations(15)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
