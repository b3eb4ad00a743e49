// Particle-fluid benchmarks (docs/sph.md):
//  - BM_SphAccelerations/threads: one SPH force evaluation (density + pressure + viscosity, mirrored
//    walls) of the mosquito-larva fluid (625 particles, h = 0.05), with 1 or 2 threads.
//  - BM_SphAccelerationsLarge/threads: the same for 10,000 particles (shows the O(n) cell grid).
//  - BM_MosquitoLarva/threads: simulating 1 s of the mosquito-larva scene (κ_p = 40, Dormand–Prince,
//    tolerances 1e-4 + 1e-3 |y|) including collisions.
#include "sph/bodies.hpp"
#include "sph/fluid.hpp"
#include "sph/initial_conditions.hpp"
#include "sph/scene.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

namespace {

using namespace jellysim;

sph::SphParameters larva_fluid() { return {0.05, 2000.0, 40.0, 8.9e-3}; }

void run_accelerations(benchmark::State& state, double side, double spacing) {
  const std::vector<sph::Wall> walls = sph::box_walls({0.0, 0.0}, {side, side});
  std::vector<Vec2> x = sph::triangular_lattice({0.0, 0.0}, {side, side}, spacing), v;
  sph::thermalise(x, v, 0.1 * spacing, 1.0, 7);
  const std::vector<double> m(x.size(), 3.0);
  sph::SphFluid fluid(larva_fluid(), walls, static_cast<int>(state.range(0)));
  std::vector<Vec2> a;
  for (auto _ : state) {
    fluid.compute_accelerations(x, v, m, a);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["particles"] = static_cast<double>(x.size());
  state.counters["evals_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SphAccelerations(benchmark::State& state) { run_accelerations(state, 1.0, 0.043); }
BENCHMARK(BM_SphAccelerations)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_SphAccelerationsLarge(benchmark::State& state) { run_accelerations(state, 4.0, 0.043); }
BENCHMARK(BM_SphAccelerationsLarge)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

sph::Scene larva_scene(int threads) {
  sph::Scene s;
  s.sph = larva_fluid();
  s.walls = sph::box_walls({0.0, 0.0}, {1.0, 1.0});
  sph::LarvaSpec spec;
  spec.wave_cells = 0.1;
  sph::Larva larva = sph::make_larva(spec);
  s.body = larva.body;
  s.outline = larva.outline;
  s.muscles = larva.muscles;
  s.position = sph::triangular_lattice_with_count({0.0, 0.0}, {1.0, 1.0}, 625, [](Vec2 p) {
    return std::abs(p.x - 0.5) < 0.2125 && std::abs(p.y - 0.5) < 0.0375;  // the larva plus h/4
  });
  const sph::MassSearch m = sph::find_particle_mass(s.position, 1.0 - 0.02, s.sph, s.walls, 1e-6);
  s.velocity.assign(s.position.size(), Vec2{});
  s.mass.assign(s.position.size(), m.mass_kg);
  s.fluid_count = s.position.size();
  s.collision = {1e-6, 0.005};
  s.threads = threads;
  return s;
}

/// Dormand–Prince with the experiment's tolerances (1e-4 + 1e-3 |y|) over `duration` seconds.
sph::RunSettings larva_settings(double duration) {
  sph::RunSettings rs;
  rs.time.integrator = "dopri5";
  rs.time.adaptive = true;
  rs.time.dt = 1e-3;
  rs.time.tolerances.atol = 1e-4;
  rs.time.tolerances.rtol = 1e-3;
  rs.time.duration = duration;
  rs.time.frame_interval = duration;
  return rs;
}

std::string keep_going(double, const sph::Scene&, const sph::CoupledSystem&) { return {}; }

void BM_MosquitoLarva(benchmark::State& state) {
  const sph::RunSettings rs = larva_settings(1.0);
  std::int64_t steps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sph::Scene s = larva_scene(static_cast<int>(state.range(0)));
    state.ResumeTiming();
    const sph::RunResult r = sph::run(s, rs, keep_going);
    steps = r.statistics.steps;
    benchmark::DoNotOptimize(s.position.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_MosquitoLarva)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// One thread against two on a developed larva state (docs/sph.md, "Two cores"), in one process.
// The state is the scene after 3 s, computed once (the same for any thread count; results are
// bit-identical for 1 and 2 threads, only the time differs).
sph::Scene developed_scene(int threads) {
  static const sph::Scene developed = [] {
    sph::Scene s = larva_scene(1);
    sph::run(s, larva_settings(3.0), keep_going);
    return s;
  }();
  sph::Scene s = developed;
  s.threads = threads;
  return s;
}

/// One evaluation of the whole right-hand side y' = f(t, y): SPH forces in the parallel region,
/// muscles and springs, packing.
void BM_SphLarvaDerivative(benchmark::State& state) {
  sph::Scene scene = developed_scene(static_cast<int>(state.range(0)));
  const sph::CoupledSystem system(scene);
  const ode::Vector y = system.pack_state();
  ode::Vector dydt(y.size());
  for (auto _ : state) {
    system.derivative(1.0, y, dydt);
    benchmark::DoNotOptimize(dydt.data());
  }
  state.counters["evals_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SphLarvaDerivative)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

/// 1 s of the scene with Dormand–Prince and the collision pass, continued from the developed state.
void BM_SphLarvaRun(benchmark::State& state) {
  const sph::RunSettings rs = larva_settings(1.0);
  std::int64_t steps = 0, evaluations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sph::Scene s = developed_scene(static_cast<int>(state.range(0)));
    state.ResumeTiming();
    const sph::RunResult r = sph::run(s, rs, keep_going);
    steps = r.statistics.steps;
    evaluations = r.statistics.function_evaluations;
    benchmark::DoNotOptimize(s.position.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK(BM_SphLarvaRun)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

}  // namespace
