// Grid-fluid benchmarks (docs/fluids.md):
//  - BM_PressureSolve/<solver>/<n>: one pressure solve to a 1e-6 relative max-norm residual from
//    a zero initial guess on an n × n all-wall (pure Neumann) cavity with a fixed smooth+rough
//    right-hand side. Reports cells and iterations; time/cell shows the growth with N.
//    _Fft/_Direct are exact (one pass); _FftR2rRows and _FftR2r2d are the transform solver's
//    other methods (FftPoissonMethod), _FftR2r2d the original one, for old vs new side by side.
//  - BM_FluidStep/<solver>/<n>: one full step of each fluid solver (multigrid, 1e-6) on a
//    periodic Taylor–Green vortex (ν = 1e-3), Eulerian at its stable Δt, semi-Lagrangian at CFL 1;
//    _PlainWarmStart: without the time-extrapolated pressure guess.
//  - BM_Advection/{fast,reference}/<n>, BM_ImplicitDiffusion/<n>: parts of that step.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "jellysim/studies/taylor_green.hpp"
#include "jellysim/fluid/fft_poisson.hpp"
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/fluid/semi_lagrangian.hpp"

namespace {

using namespace jellysim::fluid;

std::vector<double> benchmark_rhs(int n) {
  std::vector<double> b(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      b[static_cast<std::size_t>(j) * n + i] =
          std::cos(3.0 * (i + 0.5) / n) * std::sin(7.0 * (j + 0.5) / n) + ((i * 7 + j * 3) % 5 - 2);
  return b;
}

// set_up_first: one untimed solve first (the exact solvers factor or plan on their first solve
// and reuse that for every later solve on the same grid, as in a simulation).
void pressure_solve(benchmark::State& state, std::unique_ptr<PressureSolver> solver, bool set_up_first) {
  const int n = static_cast<int>(state.range(0));
  const PoissonOperator op(MacGrid(n, n, 1.0, 1.0), Boundaries::all(BoundaryType::no_slip));
  const std::vector<double> b = benchmark_rhs(n);
  std::vector<double> p(b.size());
  if (set_up_first) solver->solve(op, b, p);
  int iterations = 0;
  for (auto _ : state) {
    std::fill(p.begin(), p.end(), 0.0);
    iterations = solver->solve(op, b, p).iterations;
    benchmark::DoNotOptimize(p.data());
  }
  state.counters["cells"] = static_cast<double>(n) * n;
  state.counters["iterations"] = iterations;
  // Seconds per cell per solve (printed with an SI prefix, e.g. 104n = 104 ns).
  state.counters["time_per_cell"] = benchmark::Counter(static_cast<double>(n) * n,
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}

void pressure_solve(benchmark::State& state, const char* name, bool set_up_first = false) {
  const int n = static_cast<int>(state.range(0));
  PressureSolverSettings settings;
  settings.relative_tolerance = 1e-6;
  settings.max_iterations = 1000000;
  settings.sor_omega = jellysim::studies::optimal_sor_omega(n, n);
  pressure_solve(state, make_pressure_solver(name, settings), set_up_first);
}

void BM_PressureSolve_Multigrid(benchmark::State& state) { pressure_solve(state, "multigrid"); }
void BM_PressureSolve_Sor(benchmark::State& state) { pressure_solve(state, "sor"); }
void BM_PressureSolve_Direct(benchmark::State& state) { pressure_solve(state, "direct", true); }
// The transform solver as used ("fft": row DCT-II by a DFT + Thomas along y) and its two
// other methods, for old-vs-new in one process: FFTW r2r along the rows + Thomas, and the
// original 2D r2r transform (REDFT10/REDFT01 both ways).
void BM_PressureSolve_Fft(benchmark::State& state) { pressure_solve(state, "fft", true); }
void BM_PressureSolve_FftR2rRows(benchmark::State& state) {
  pressure_solve(state, std::make_unique<FftPoissonSolver>(FftPoissonMethod::r2r_rows_then_tridiagonal), true);
}
void BM_PressureSolve_FftR2r2d(benchmark::State& state) {
  pressure_solve(state, std::make_unique<FftPoissonSolver>(FftPoissonMethod::r2r_2d), true);
}

void fluid_step(benchmark::State& state, const char* name, bool extrapolate_pressure = true) {
  const int n = static_cast<int>(state.range(0));
  const TaylorGreen flow{6.283185307179586, 1.0, 1e-3};
  const MacGrid g(n, n, flow.length_m, flow.length_m);
  FluidSettings f;
  f.viscosity_m2_per_s = flow.viscosity_m2_per_s;
  f.density_kg_per_m3 = 1.0;
  f.boundaries = Boundaries::all(BoundaryType::periodic);
  f.pressure_solver = "multigrid";
  f.pressure.relative_tolerance = 1e-6;
  f.extrapolate_pressure_guess = extrapolate_pressure;
  auto solver = make_fluid_solver(name, g, f);
  solver->state().velocity = flow.sample(g, 0.0);
  solver->apply_boundaries();
  const double dt = std::string_view(name) == "eulerian" ? solver->stable_time_step() : g.dx() / flow.speed_m_per_s;
  for (int warm_up = 0; warm_up < 3; ++warm_up) solver->step(dt);  // pressure history filled
  StepReport report;
  for (auto _ : state) report = solver->step(dt);
  state.counters["cells"] = static_cast<double>(n) * n;
  state.counters["pressure_cycles"] = report.pressure.iterations;
  if (report.diffusion_iterations > 0) state.counters["diffusion_cg"] = report.diffusion_iterations;
}

// The parts of the semi-Lagrangian step on the same Taylor–Green field (periodic, ν = 1e-3,
// Δt = Δx/U): advection (row-wise fast path against the point-wise reference) and the implicit
// diffusion solve (tolerance 1e-8, the solver's default).
struct TaylorGreenField {
  TaylorGreen flow{6.283185307179586, 1.0, 1e-3};
  MacGrid grid;
  Boundaries sides = Boundaries::all(BoundaryType::periodic);
  Velocity velocity;
  double dt_s;
  explicit TaylorGreenField(int n)
      : grid(n, n, flow.length_m, flow.length_m), velocity(flow.sample(grid, 0.0)), dt_s(grid.dx() / flow.speed_m_per_s) {
    apply_velocity_boundaries(velocity, sides);
  }
};

template <void (*Advect)(const Velocity&, const Boundaries&, double, Velocity&)>
void BM_Advection(benchmark::State& state) {
  const TaylorGreenField f(static_cast<int>(state.range(0)));
  Velocity out(f.grid);
  for (auto _ : state) {
    Advect(f.velocity, f.sides, f.dt_s, out);
    benchmark::DoNotOptimize(out.u.raw().data());
  }
  state.counters["faces"] = static_cast<double>(f.grid.nx) * f.grid.ny * 2;
}

void BM_ImplicitDiffusion(benchmark::State& state) {
  const TaylorGreenField f(static_cast<int>(state.range(0)));
  ImplicitDiffusion diffusion(f.grid);
  Velocity v = f.velocity;
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    v = f.velocity;
    state.ResumeTiming();
    iterations = diffusion.solve(v, f.sides, f.flow.viscosity_m2_per_s * f.dt_s, 1e-8);
  }
  state.counters["cg_iterations"] = iterations;
}

void BM_FluidStep_Eulerian(benchmark::State& state) { fluid_step(state, "eulerian"); }
void BM_FluidStep_SemiLagrangian(benchmark::State& state) { fluid_step(state, "semi-lagrangian"); }
// The same with the previous pressure alone as the initial guess (FluidSettings::
// extrapolate_pressure_guess = false), i.e. without the time extrapolation that Taylor–Green's
// smoothly decaying pressure favours.
void BM_FluidStep_SemiLagrangian_PlainWarmStart(benchmark::State& state) {
  fluid_step(state, "semi-lagrangian", false);
}

}  // namespace

BENCHMARK(BM_PressureSolve_Multigrid)->RangeMultiplier(2)->Range(32, 1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PressureSolve_Sor)->RangeMultiplier(2)->Range(32, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PressureSolve_Fft)->Arg(60)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PressureSolve_FftR2rRows)->Arg(60)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PressureSolve_FftR2r2d)->Arg(60)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PressureSolve_Direct)->Arg(60)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FluidStep_Eulerian)->RangeMultiplier(2)->Range(64, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Advection<advect_velocity>)->Name("BM_Advection/fast")->RangeMultiplier(2)->Range(128, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Advection<advect_velocity_reference>)->Name("BM_Advection/reference")->RangeMultiplier(2)->Range(128, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ImplicitDiffusion)->RangeMultiplier(2)->Range(128, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidStep_SemiLagrangian)->RangeMultiplier(2)->Range(64, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidStep_SemiLagrangian_PlainWarmStart)->RangeMultiplier(2)->Range(64, 512)->Unit(benchmark::kMillisecond);
