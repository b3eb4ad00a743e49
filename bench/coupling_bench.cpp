// Immersed-boundary jellyfish benchmarks (docs/jellyfish.md, docs/benchmarks.md):
//  - BM_Swim/<scene>_<scheme>: one contraction cycle (1/0.7 s) of a jellyfish scene ("builtin": the
//    resolved built-in scene, 96 × 128 cells, solved on its east half; "thesis": Fig. 8.21's 60 × 60
//    tank, scenes/jellyfish-thesis.toml; "fine": scenes/jellyfish-fine.toml's 160 × 160 tank),
//    explicit or semi-implicit coupling, no outputs. The explicit scheme runs at the largest step
//    coupling-stability found stable for it.
//  - BM_MarkerSpaceSolve/<cells>/<preconditioner>/<half>: one cycle of the fine scene's 40 cm tank
//    at cells × cells (60, 160, 320), plain GMRES (0, the coupling before the marker-space solve) or
//    the mobility preconditioner (1), on the whole tank (0) or its east half (1).
//  - BM_MobilityAssemble/<half>: one build of the dense mobility for the built-in scene's markers at
//    rest (what the marker-space solve does every step): the whole tank (0), or the east half's rows
//    on the half tank (1, as the default run does).
//  - BM_Geometry/<geometry>: one cycle of the built-in scene on its east half, planar or
//    axisymmetric (the ring bell, issue 22), with the scene's adaptive step (the faster ring bell
//    takes more steps: CFL) and at a fixed 2.5 ms step (the same steps: the cost of one).
//  - BM_HooverMiller/<scheme>: IB2d's Hoover–Miller bell (experiment hoover-miller, Re 150, IB2d's
//    N = 256: 96 × 320 cells, periodic), as the experiment runs it: the semi-implicit coupling for one
//    1 s cycle; and the explicit coupling at IB2d's own step (Δt = 1e-5 s, its input2d) for 0.01 s,
//    on the cheaper Eulerian fluid step: an explicit immersed boundary in our C++ at IB2d's step, a
//    lower bound on IB2d's own cost (IB2d itself, run under Octave, is in docs/ib2d.md).
// Counters: wall seconds per simulated second (wall_per_sim_s; < 0.1 means ten times faster than
// real time), steps per simulated second and Krylov (GMRES) iterations per step.
#include <benchmark/benchmark.h>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//coupling/mobility.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace {

using namespace jellysim;

/// The built-in scene, optionally with a scene file of the repository laid over it, for one cycle.
config::Config one_cycle(const char* overlay) {
  config::Config c = scene::builtin_jellyfish_scene();
  if (overlay) c.merge(config::Config::parse(experiments::embedded_text(overlay), overlay));
  c.set("tank.tracers_per_side=0");
  c.set("duration=" + io::format_double(1.0 / 0.7));
  c.set("output.frame_interval=0.1");
  return c;
}

void report(benchmark::State& state, const jellyfish::SwimSettings& s) {
  double wall = 0.0, simulated = 0.0, steps = 0.0, krylov = 0.0;
  for (auto _ : state) {
    const experiments::SwimRecording rec = experiments::run_swim(s, {}, nullptr, {});
    if (!rec.stats.failure.empty()) state.SkipWithError(rec.stats.failure.c_str());
    wall += rec.stats.wall_seconds;
    simulated += rec.stats.simulated_seconds;
    steps += static_cast<double>(rec.stats.steps);
    krylov += static_cast<double>(rec.stats.krylov_iterations);
    benchmark::DoNotOptimize(rec.metrics.data());
  }
  state.counters["wall_per_sim_s"] = simulated > 0 ? wall / simulated : 0.0;
  state.counters["steps_per_sim_s"] = simulated > 0 ? steps / simulated : 0.0;
  state.counters["krylov_per_step"] = steps > 0 ? krylov / steps : 0.0;
}

void BM_Swim(benchmark::State& state, const char* overlay, bool semi_implicit) {
  config::Config c = one_cycle(overlay);
  c.set(std::string("coupling.scheme=") + (semi_implicit ? "semi-implicit" : "explicit"));
  if (!semi_implicit) c.set("coupling.max_dt=0.0025");
  report(state, scene::read_swim_settings(c));
}

BENCHMARK_CAPTURE(BM_Swim, builtin_semi_implicit, nullptr, true)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Swim, thesis_explicit, "scenes/jellyfish-thesis.toml", false)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Swim, thesis_semi_implicit, "scenes/jellyfish-thesis.toml", true)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Swim, fine_semi_implicit, "scenes/jellyfish-fine.toml", true)->Unit(benchmark::kSecond)->Iterations(1);

void BM_Geometry(benchmark::State& state, const char* geometry, bool fixed_step) {
  config::Config c = one_cycle(nullptr);
  c.set(std::string("tank.geometry=\"") + geometry + "\"");
  if (fixed_step) c.set("coupling.max_dt=0.0025");  // below both CFL limits: the same steps
  report(state, scene::read_swim_settings(c));
}

BENCHMARK_CAPTURE(BM_Geometry, planar_half_tank, "planar", false)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Geometry, axisymmetric, "axisymmetric", false)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Geometry, planar_half_tank_fixed_step, "planar", true)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Geometry, axisymmetric_fixed_step, "axisymmetric", true)->Unit(benchmark::kSecond)->Iterations(1);

void BM_HooverMiller(benchmark::State& state, bool semi_implicit) {
  config::Config c = experiments::default_config(experiments::find_experiment("hoover-miller"));
  c.set("duration=" + std::string(semi_implicit ? "1.0" : "0.01"));
  c.set("output.frame_interval=0.01");
  if (!semi_implicit) {
    c.set("coupling.scheme=explicit");
    c.set("coupling.max_dt=1e-5");
    c.set("coupling.min_dt=1e-7");
    c.set("tank.solver=eulerian");  // our cheapest fluid step: the bound stays a lower one
  }
  report(state, scene::read_swim_settings(c));
}

BENCHMARK_CAPTURE(BM_HooverMiller, semi_implicit, true)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_HooverMiller, explicit_ib2d_step, false)->Unit(benchmark::kSecond)->Iterations(1);

void BM_MarkerSpaceSolve(benchmark::State& state) {
  config::Config c = one_cycle("scenes/jellyfish-fine.toml");
  const std::string cells = std::to_string(state.range(0));
  c.set("tank.cells=[" + cells + ", " + cells + "]");
  c.set(std::string("coupling.preconditioner=") + (state.range(1) ? "mobility" : "none"));
  c.set(std::string("tank.half_tank=") + (state.range(2) ? "true" : "false"));
  report(state, scene::read_swim_settings(c));
}

BENCHMARK(BM_MarkerSpaceSolve)
    ->ArgNames({"cells", "mobility", "half"})
    ->ArgsProduct({{60, 160, 320}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

void BM_MobilityAssemble(benchmark::State& state) {
  const jellyfish::SwimSettings s = scene::read_swim_settings(one_cycle(nullptr));
  const jellyfish::SwimSimulation sim(s);
  const std::vector<Vec2>& x = sim.body().points.position;
  const bool half = state.range(0) != 0;
  coupling::TransferGeometry g;
  const double w = s.tank.width_m, h = s.tank.height_m;
  g.grid = half ? fluid::MacGrid(s.tank.cells_x / 2, s.tank.cells_y, 0.5 * w, h, Vec2{0.5 * w, 0.0})
                : fluid::MacGrid(s.tank.cells_x, s.tank.cells_y, w, h);
  g.sides = s.tank.boundaries.homogeneous();
  g.west_mirror = half;
  const coupling::MobilityMatrix mobility(g);
  std::vector<int> rows;  // on the half tank: the points on or east of the axis
  for (std::size_t p = 0; p < x.size(); ++p)
    if (!half || x[p].x >= 0.5 * w - 1e-12) rows.push_back(static_cast<int>(p));
  Eigen::MatrixXd r;
  for (auto _ : state) {
    mobility.assemble(x, {}, s.tank.density_kg_per_m3, rows, r);
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["rows"] = static_cast<double>(r.rows());
  state.counters["columns"] = static_cast<double>(r.cols());
}
BENCHMARK(BM_MobilityAssemble)->ArgName("half")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
