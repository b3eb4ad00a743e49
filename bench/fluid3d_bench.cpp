// 3D fluid benchmarks (docs/three-d.md):
//  - BM_Fluid3dStep/<threads>: one step of the 3D solver (Koren convection, explicit viscosity, FFT
//    pressure) on the 48 × 96 × 48 quarter tank of issue 40's swimmer (cells of 5 mm, water, walls
//    on four sides, mirror planes at low x and low z) with a smooth flow of peak speed 0.1 m/s, at
//    its stable Δt. Counters: the
//    step's split (convection, viscosity, pressure, ms), the stable Δt (ms) and the simulated
//    seconds per wall-clock second that Δt allows (real-time factor of the fluid alone).
//  - BM_Fluid3dStepSemiLagrangian/<threads>: the same with MacCormack semi-Lagrangian advection
//    (its Δt: CFL 1); the "convection" counter is then the advection.
//  - BM_Fluid3dPressureSolve: one FFT pressure solve on that grid.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "jellysim/fluid3d/fluid_solver_3d.hpp"

namespace {

using namespace jellysim::fluid3d;

const Grid3d kTank({48, 96, 48}, {0.24, 0.48, 0.24});

// A smooth flow of peak speed U: Taylor–Green cells along each pair of axes, projected once.
std::unique_ptr<FluidSolver3d> tank_solver(int threads, double U, FluidMethod3d method) {
  FluidSettings3d s;
  s.threads = threads;
  s.method = method;
  s.boundaries = Boundaries3d::closed_box().quarter();
  auto solver = make_fluid_solver_3d(kTank, s);
  const double kx = 0.5 * std::numbers::pi / kTank.size(0), ky = 2.0 * std::numbers::pi / kTank.size(1),
               kz = 0.5 * std::numbers::pi / kTank.size(2);
  Velocity3d& vel = solver->mutable_state().velocity;
  set_component(kTank, s.boundaries, vel, 0, [&](double x, double y, double z) { return U * std::sin(kx * x) * std::cos(ky * y) * std::sin(kz * z); });
  set_component(kTank, s.boundaries, vel, 1, [&](double x, double y, double z) { return U * std::cos(kx * x) * std::sin(ky * y) * std::cos(kz * z); });
  set_component(kTank, s.boundaries, vel, 2, [&](double x, double y, double z) { return 0.5 * U * std::sin(kx * x) * std::sin(ky * y) * std::cos(kz * z); });
  solver->step(1e-4);  // projects the initial flow
  return solver;
}

void fluid_step(benchmark::State& state, FluidMethod3d method) {
  auto solver = tank_solver(static_cast<int>(state.range(0)), 0.1, method);
  double convection = 0.0, viscosity = 0.0, pressure = 0.0, dt = 0.0, total = 0.0;
  for (auto _ : state) {
    dt = solver->stable_time_step();
    solver->step(dt);
    const StepTimings3d t = solver->last_timings();
    convection += t.convection_s;
    viscosity += t.viscosity_s;
    pressure += t.pressure_s;
    total += t.total_s;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["convection_ms"] = 1e3 * convection / n;
  state.counters["viscosity_ms"] = 1e3 * viscosity / n;
  state.counters["pressure_ms"] = 1e3 * pressure / n;
  state.counters["dt_ms"] = 1e3 * dt;
  state.counters["realtime_factor"] = dt / (total / n);
  state.counters["cells"] = static_cast<double>(kTank.cell_count());
}
void BM_Fluid3dStep(benchmark::State& state) { fluid_step(state, FluidMethod3d::eulerian); }
void BM_Fluid3dStepSemiLagrangian(benchmark::State& state) { fluid_step(state, FluidMethod3d::semi_lagrangian); }
BENCHMARK(BM_Fluid3dStep)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fluid3dStepSemiLagrangian)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Fluid3dPressureSolve(benchmark::State& state) {
  auto solver = make_pressure_solver_3d("fft", kTank, Boundaries3d::closed_box());
  Field3d b(kTank.padded_size(), 0.0), p(kTank.padded_size(), 0.0);
  for (int k = 0; k < kTank.n(2); ++k)
    for (int j = 0; j < kTank.n(1); ++j)
      for (int i = 0; i < kTank.n(0); ++i) b[kTank.index(i, j, k)] = std::cos(0.3 * i) * std::sin(0.7 * j) + ((i + 3 * j + 5 * k) % 5 - 2);
  for (auto _ : state) {
    solver->solve(b, p);
    benchmark::DoNotOptimize(p.data());
  }
}
BENCHMARK(BM_Fluid3dPressureSolve)->Unit(benchmark::kMillisecond);

}  // namespace
