// 3D immersed-boundary benchmarks (docs/three-d.md, "Part 2"), on the 48 × 96 × 48 quarter tank of
// the fluid's benchmarks (5 mm cells, water, walls on four sides, mirror planes at low x and z):
//  - BM_Ib3dTransfer/<threads>: spreading and interpolating ~3000 markers (a sphere of radius 15.5
//    cells, markers half a cell apart, its quarter) — one spread plus one interpolation.
//  - BM_Ib3dStep/<scheme>/<preconditioner>/<radius cells>/<threads>/<k>: one coupled step (Δt = 5 ms) of
//    a quarter sphere of markers joined to their neighbours (within 0.75 cells) by springs (500 N/m;
//    5 N/m for the explicit step, which is unstable with the stiff ones) and tethered (5 N/m) to
//    anchors that move up and down (2 mm at 2 Hz), the fluid's step included.
//    scheme 0 explicit, 1 semi-implicit; preconditioner 0 none, 1 self-mobility; the Krylov
//    tolerance 10^−k (relative to the increment; 6 is the default). Counters: markers,
//    GMRES iterations and projections per step, the split (transfer, fluid, Krylov; ms).
//  - BM_Ib3dUnprojectedPreconditioner/<radius cells>/<inner>: a study of a candidate preconditioner,
//    M = I − Δt² (2/3) J S K/(ρV) (the response without the projection: spread and interpolation
//    only), inverted exactly by an inner GMRES (to 1e-10), on the step's system for a random
//    right-hand side (inner 0: plain GMRES). Counters: outer iterations (projections) and inner ones
//    (spread–interpolation pairs).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "jellysim/ib3d/immersed_boundary_3d.hpp"
#include "jellysim/ode/gmres.hpp"

namespace {

using namespace jellysim::ib3d;
using jellysim::fluid3d::Boundaries3d;
using jellysim::fluid3d::Grid3d;

const Grid3d kTank({48, 96, 48}, {0.24, 0.48, 0.24});
constexpr double kCellM = 0.005;

std::vector<Vec3> quarter_sphere(double radius_cells) {
  return sphere_surface_markers({0.0, 0.24, 0.0}, radius_cells * kCellM, 0.5 * kCellM, true);
}

std::unique_ptr<jellysim::fluid3d::FluidSolver3d> tank(int threads) {
  jellysim::fluid3d::FluidSettings3d s;
  s.threads = threads;
  s.boundaries = Boundaries3d::closed_box().quarter();
  return jellysim::fluid3d::make_fluid_solver_3d(kTank, s);
}

void BM_Ib3dTransfer(benchmark::State& state) {
  jellysim::WorkerPool pool(static_cast<int>(state.range(0)));
  Transfer3d t(kTank, Boundaries3d::closed_box().quarter(), jellysim::coupling::Kernel::peskin4, &pool);
  const auto x = quarter_sphere(15.5);
  std::vector<Vec3> f(x.size(), Vec3{0.01, -0.02, 0.005}), u(x.size());
  jellysim::fluid3d::Velocity3d acc(kTank), vel(kTank);
  for (auto& q : vel.c)
    for (std::size_t i = 0; i < q.size(); ++i) q[i] = std::sin(0.001 * static_cast<double>(i));
  for (auto _ : state) {
    t.spread(x, f, 1000.0, acc);
    t.interpolate(vel, x, u);
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["markers"] = static_cast<double>(x.size());
}
BENCHMARK(BM_Ib3dTransfer)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Ib3dStep(benchmark::State& state) {
  const auto x = quarter_sphere(static_cast<double>(state.range(2)));
  Markers3d markers(x);
  Tethers3d tethers(x, std::vector<double>(x.size(), 5.0));
  const bool explicit_step = state.range(0) == 0;
  SpringNet3d net(neighbour_springs(x, 0.75 * kCellM, explicit_step ? 5.0 : 500.0), &tethers);
  auto fluid = tank(static_cast<int>(state.range(3)));
  CouplingSettings3d cs;
  cs.scheme = explicit_step ? Scheme3d::explicit_euler : Scheme3d::semi_implicit;
  cs.preconditioner = state.range(1) == 0 ? Preconditioner3d::none : Preconditioner3d::self_mobility;
  cs.krylov_tolerance = std::pow(10.0, -static_cast<double>(state.range(4)));
  cs.threads = static_cast<int>(state.range(3));
  ImmersedBoundary3d ib(*fluid, markers, net, cs);
  const double dt = 0.005;
  double iterations = 0.0, projections = 0.0, transfer = 0.0, fluid_s = 0.0, krylov = 0.0;
  for (auto _ : state) {
    const double lift = 0.002 * std::sin(2.0 * std::numbers::pi * 2.0 * (ib.time_s() + dt));
    for (std::size_t m = 0; m < x.size(); ++m) tethers.anchors()[m][1] = x[m][1] + lift;
    const CoupledStepReport3d r = ib.step(dt);
    iterations += r.krylov_iterations;
    projections += r.projections;
    transfer += r.transfer_s;
    fluid_s += r.fluid_s;
    krylov += r.krylov_s;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["markers"] = static_cast<double>(x.size());
  state.counters["gmres_iterations"] = iterations / n;
  state.counters["projections"] = projections / n;
  state.counters["transfer_ms"] = 1e3 * transfer / n;
  state.counters["fluid_ms"] = 1e3 * fluid_s / n;
  state.counters["krylov_ms"] = 1e3 * krylov / n;
}
// Semi-implicit, both preconditioners, marker counts from ~200 to ~3200 (sphere radius 4 to 16
// cells), one thread; then the explicit step and two threads at ~3000 markers.
BENCHMARK(BM_Ib3dStep)
    ->ArgsProduct({{1}, {0, 1}, {4, 8, 12, 16}, {1}, {6}})
    ->Args({0, 0, 16, 1, 6})
    ->Args({0, 0, 16, 2, 6})
    ->Args({1, 0, 16, 2, 6})
    ->Args({1, 0, 16, 1, 4})
    ->Args({1, 0, 16, 1, 3})
    ->Iterations(8)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_Ib3dUnprojectedPreconditioner(benchmark::State& state) {
  const auto x = quarter_sphere(static_cast<double>(state.range(0)));
  Markers3d markers(x);
  Tethers3d tethers(x, std::vector<double>(x.size(), 5.0));
  SpringNet3d net(neighbour_springs(x, 0.75 * kCellM, 500.0), &tethers);
  auto fluid = tank(1);
  ImmersedBoundary3d ib(*fluid, markers, net);
  const bool inner = state.range(1) != 0;
  const double dt2 = 0.005 * 0.005, rho = 1000.0;
  std::vector<Vec3> w, kw(x.size()), u(x.size());
  auto k_times = [&](const Eigen::VectorXd& v) {
    unflatten(v, w);
    net.jacobian_times(0.0, x, w, kw);
    return flatten(kw);
  };
  jellysim::fluid3d::Velocity3d acc(kTank);
  const jellysim::ode::LinearOperator unprojected = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    unflatten(k_times(v), w);
    for (auto& q : acc.c) std::fill(q.begin(), q.end(), 0.0);
    ib.transfer().spread(x, w, rho, acc);
    ib.transfer().interpolate(acc, x, u);
    out = v - dt2 * (2.0 / 3.0) * flatten(u);
  };
  int inner_iterations = 0, outer_iterations = 0;
  Eigen::VectorXd response;
  const jellysim::ode::LinearOperator preconditioned = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(in.size());
    if (inner) inner_iterations += jellysim::ode::gmres(unprojected, in, z, 1e-10, 500, 500).iterations;
    else z = in;
    ib.apply_response(k_times(z), response);
    out = z - dt2 * response;
  };
  Eigen::VectorXd b(3 * static_cast<Eigen::Index>(x.size()));
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::sin(1.7 * static_cast<double>(i) + 0.3 * std::cos(0.11 * static_cast<double>(i)));
  for (auto _ : state) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(b.size());
    outer_iterations = jellysim::ode::gmres(preconditioned, b, y, 1e-6, 300, 300).iterations;
  }
  state.counters["markers"] = static_cast<double>(x.size());
  state.counters["outer_iterations"] = outer_iterations;
  state.counters["inner_iterations"] = inner_iterations;
}
BENCHMARK(BM_Ib3dUnprojectedPreconditioner)
    ->ArgsProduct({{8, 16}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
