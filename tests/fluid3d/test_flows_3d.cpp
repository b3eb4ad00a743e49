// The 3D fluid against exact solutions: the Taylor–Green vortex and the Arnold–Beltrami–Childress
// (ABC) flow decaying in a periodic box (orders over two grids), laminar flow in a square duct
// against its Fourier series, the lid-driven cube at Re 100 (coarse), and bitwise equality of 1 and
// 2 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <string>

#include "jellysim/fluid3d/fluid_solver_3d.hpp"

namespace jellysim::fluid3d {
namespace {

constexpr double kPi = std::numbers::pi;
using VelocityFunction = std::function<Vec3(double x, double y, double z, double t)>;

// Steps to t_end with the stable step (the last one shortened to land on t_end).
void advance_to(FluidSolver3d& solver, double t_end) {
  while (solver.state().time_s < t_end * (1.0 - 1e-12))
    solver.step(std::min(solver.stable_time_step(), t_end - solver.state().time_s));
}

void set_velocity(const Grid3d& g, const Boundaries3d& b, Velocity3d& vel, const VelocityFunction& f) {
  for (int c = 0; c < 3; ++c)
    set_component(g, b, vel, c, [&](double x, double y, double z) { return f(x, y, z, 0.0)[static_cast<std::size_t>(c)]; });
}

// Root-mean-square over the faces of |u_h − u_exact(t)|.
double rms_error(const Grid3d& g, const Velocity3d& vel, const VelocityFunction& exact, double t) {
  double sum = 0.0;
  std::size_t count = 0;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < g.n(2); ++k)
      for (int j = 0; j < g.n(1); ++j)
        for (int i = 0; i < g.n(0); ++i) {
          const Vec3 x = g.position(c, i, j, k);
          const double e = vel.c[static_cast<std::size_t>(c)][g.index(i, j, k)] - exact(x[0], x[1], x[2], t)[static_cast<std::size_t>(c)];
          sum += e * e;
          ++count;
        }
  return std::sqrt(sum / static_cast<double>(count));
}

// The RMS velocity error at t_end of a periodic 2π box with n³ cells started from exact(t = 0).
double periodic_decay_error(int n, double nu, double t_end, const VelocityFunction& exact, FluidSettings3d s = {}) {
  const Grid3d g({n, n, n}, {2.0 * kPi, 2.0 * kPi, 2.0 * kPi});
  s.boundaries = Boundaries3d::periodic_box();
  s.viscosity_m2_per_s = nu;
  s.density_kg_per_m3 = 1.0;
  auto solver = make_fluid_solver_3d(g, s);
  set_velocity(g, s.boundaries, solver->mutable_state().velocity, exact);
  advance_to(*solver, t_end);
  return rms_error(g, solver->state().velocity, exact, t_end);
}

// u = sin x cos y, v = −cos x sin y, w = 0, decaying as e^{−2νt}.
Vec3 taylor_green(double x, double y, double, double t, double nu) {
  const double a = std::exp(-2.0 * nu * t);
  return {a * std::sin(x) * std::cos(y), -a * std::cos(x) * std::sin(y), 0.0};
}

// ABC flow (A = B = C = 1): ∇×u = u, so (u·∇)u = ∇|u|²/2 is absorbed by the pressure and the flow
// decays as e^{−νt}; all three components depend on all three coordinates.
Vec3 abc_flow(double x, double y, double z, double t, double nu) {
  const double a = std::exp(-nu * t);
  return {a * (std::sin(z) + std::cos(y)), a * (std::sin(x) + std::cos(z)), a * (std::sin(y) + std::cos(x))};
}

constexpr double kNu = 0.1;

struct DecayOrder {
  double e16, e32, order;
};

// The RMS errors at t_end on 16³ and 32³ and the observed order log2(e16/e32).
DecayOrder measured_decay_order(const char* name, double t_end, const VelocityFunction& exact) {
  const double e16 = periodic_decay_error(16, kNu, t_end, exact), e32 = periodic_decay_error(32, kNu, t_end, exact);
  const DecayOrder d{e16, e32, std::log2(e16 / e32)};
  std::printf("  %s, t = %.1f: RMS error 16^3 %.3e, 32^3 %.3e, order %.3f\n", name, t_end, d.e16, d.e32, d.order);
  return d;
}

TEST(TaylorGreen3d, DecaysAtSecondOrderInAPeriodicBox) {
  const DecayOrder d = measured_decay_order("Taylor-Green", 1.0, [](double x, double y, double z, double t) {
    return taylor_green(x, y, z, t, kNu);
  });
  EXPECT_NEAR(d.e16, 1.80e-3, 0.03e-3);  // measured 1.803e-3
  EXPECT_NEAR(d.e32, 2.00e-4, 0.03e-4);  // measured 2.004e-4
  EXPECT_GE(d.order, 1.8);
  EXPECT_NEAR(d.order, 3.17, 0.03);  // measured 3.169 (Koren's third-order face values, Δt ∝ Δx² here)
}

TEST(Beltrami3d, AbcFlowDecaysAtSecondOrderInAPeriodicBox) {
  const DecayOrder d = measured_decay_order("ABC flow", 0.5, [](double x, double y, double z, double t) {
    return abc_flow(x, y, z, t, kNu);
  });
  EXPECT_NEAR(d.e32, 2.40e-3, 0.03e-3);  // measured 2.401e-3
  EXPECT_GE(d.order, 1.8);
  EXPECT_NEAR(d.order, 2.49, 0.03);  // measured 2.491
}

// ½ Σ|u|² h³ of the ABC flow on a periodic grid: each squared sine and cosine sums to n/2 over whole
// periods and the cross terms to 0, so the discrete energy is the exact ½·3·(2π)³ = 12π³ m⁵/s².
TEST(KineticEnergy3d, OfTheAbcFlowIsTheExactIntegral) {
  const Grid3d g({8, 12, 10}, {2.0 * kPi, 2.0 * kPi, 2.0 * kPi});
  const Boundaries3d b = Boundaries3d::periodic_box();
  Velocity3d vel(g);
  set_velocity(g, b, vel, [](double x, double y, double z, double t) { return abc_flow(x, y, z, t, kNu); });
  EXPECT_NEAR(kinetic_energy_3d(g, b, vel), 12.0 * kPi * kPi * kPi, 1e-12 * 12.0 * kPi * kPi * kPi);
}

// The semi-Lagrangian step (CFL 0.5) on 12³ and 24³: linear sampling is first order (Δt ∝ Δx from
// the CFL number), MacCormack's correction second order here, where the viscous limit sets
// Δt ∝ Δx² (the splitting's O(Δt) error is then O(Δx²) too).
TEST(SemiLagrangian3d, TaylorGreenDecaysWithLinearAndMacCormackAdvection) {
  const VelocityFunction exact = [](double x, double y, double z, double t) { return taylor_green(x, y, z, t, kNu); };
  std::vector<double> orders, errors;
  for (fluid::AdvectionScheme scheme : {fluid::AdvectionScheme::linear, fluid::AdvectionScheme::maccormack}) {
    FluidSettings3d s;
    s.method = FluidMethod3d::semi_lagrangian;
    s.advection = scheme;
    s.cfl = 0.5;
    const double e12 = periodic_decay_error(12, kNu, 1.0, exact, s), e24 = periodic_decay_error(24, kNu, 1.0, exact, s);
    orders.push_back(std::log2(e12 / e24));
    errors.push_back(e24);
    std::printf("  semi-Lagrangian %s, Taylor-Green t = 1: 12^3 %.3e, 24^3 %.3e, order %.3f\n",
                std::string(fluid::to_string(scheme)).c_str(), e12, e24, orders.back());
  }
  EXPECT_NEAR(orders[0], 0.89, 0.03);       // linear: measured 0.892
  EXPECT_NEAR(errors[0], 3.17e-2, 0.05e-2);  // measured 3.170e-2
  EXPECT_NEAR(orders[1], 1.85, 0.03);       // MacCormack: measured 1.847
  EXPECT_NEAR(errors[1], 3.86e-3, 0.05e-3);  // measured 3.855e-3
}

// The third grid (64³, about 10 s in Release): Release pass only (the name holds "Slow").
TEST(SlowBeltrami3d, AbcFlowOrderHoldsOn64Cubed) {
  const VelocityFunction exact = [](double x, double y, double z, double t) { return abc_flow(x, y, z, t, kNu); };
  const double e32 = periodic_decay_error(32, kNu, 0.5, exact), e64 = periodic_decay_error(64, kNu, 0.5, exact);
  const double order = std::log2(e32 / e64);
  std::printf("  ABC flow, t = 0.5: RMS error 32^3 %.3e, 64^3 %.3e, order %.3f\n", e32, e64, order);
  EXPECT_NEAR(e64, 3.44e-4, 0.05e-4);  // measured 3.443e-4
  EXPECT_GE(order, 1.8);
  EXPECT_NEAR(order, 2.80, 0.03);  // measured 2.802 (2.49 from 16³ to 32³)
}

// Fully developed flow in a square duct of side 2a driven by the acceleration G along x (White,
// Viscous Fluid Flow, eq. 3-48, with −dp/dx/μ = G/ν; y', z' from the duct's axis):
// u = (16 a² G/(ν π³)) Σ_{n odd} (−1)^{(n−1)/2} [1 − cosh(nπz'/2a)/cosh(nπ/2)] cos(nπy'/2a) / n³.
double duct_velocity(double y, double z, double a, double G, double nu) {
  double sum = 0.0;
  for (int n = 1; n < 200; n += 2) {
    const double sign = ((n - 1) / 2) % 2 == 0 ? 1.0 : -1.0;
    const double ratio = std::cosh(n * kPi * z / (2.0 * a)) / std::cosh(n * kPi / 2.0);
    sum += sign * (1.0 - ratio) * std::cos(n * kPi * y / (2.0 * a)) / (n * n * n);
  }
  return 16.0 * a * a * G / (nu * kPi * kPi * kPi) * sum;
}

// Max |u − series| / max u in a unit duct with n × n cells across and 4 along the (periodic) axis
// `axis`, the flow along it; the two cross-stream axes in cyclic order after it.
double duct_error(int n, int axis) {
  const double side = 1.0, a = 0.5, G = 1.0, nu = 1.0;
  Index3 cells{n, n, n};
  Vec3 size{side, side, side};
  cells[static_cast<std::size_t>(axis)] = 4;
  size[static_cast<std::size_t>(axis)] = 4.0 * side / n;
  const Grid3d g(cells, size);
  FluidSettings3d s;
  s.boundaries = Boundaries3d::duct(axis);
  s.viscosity_m2_per_s = nu;
  s.density_kg_per_m3 = 1.0;
  auto solver = make_fluid_solver_3d(g, s);
  Velocity3d& vel = solver->mutable_state().velocity;
  const int p = (axis + 1) % 3, q = (axis + 2) % 3;
  const auto series = [&](double x, double y, double z) {
    const Vec3 r{x, y, z};
    return duct_velocity(r[static_cast<std::size_t>(p)] - a, r[static_cast<std::size_t>(q)] - a, a, G, nu);
  };
  set_component(g, s.boundaries, vel, axis, series);
  for (double& f : solver->body_acceleration().c[static_cast<std::size_t>(axis)]) f = G;
  advance_to(*solver, 0.4);  // the slowest mode decays as e^{−2π²νt/side²}: e^{−7.9}
  double worst = 0.0, peak = 0.0;
  for_each_interior_cell(g, [&](std::size_t I, int i, int j, int k) {
    const Vec3 x = g.position(axis, i, j, k);
    const double exact = series(x[0], x[1], x[2]);
    worst = std::max(worst, std::abs(vel.c[static_cast<std::size_t>(axis)][I] - exact));
    peak = std::max(peak, exact);
  });
  return worst / peak;
}

TEST(SquareDuct3d, PressureDrivenFlowMatchesTheFourierSeries) {
  const double e8 = duct_error(8, 0), e16 = duct_error(16, 0);
  std::printf("  square duct: max |u - series| / u_max: 8^2 %.3e, 16^2 %.3e, order %.3f\n", e8, e16, std::log2(e8 / e16));
  EXPECT_NEAR(e16, 6.30e-3, 0.05e-3);  // measured 6.298e-3
  EXPECT_NEAR(std::log2(e8 / e16), 1.93, 0.03);  // measured 1.931
  // The same duct along y and along z: the same error (the discretisation treats the axes alike).
  for (int axis : {1, 2}) {
    const double e = duct_error(16, axis);
    std::printf("  duct along axis %d, 16^2: %.6e\n", axis, e);
    EXPECT_NEAR(e, e16, 1e-12);
  }
}

// A closed box driven by a body force symmetric about the vertical mid-planes x = ½ and z = ½ (a jet
// up the axis, a swirl-free inflow toward it), and its quarter x, z ∈ [½, 1] with mirror planes at
// its low x and z sides: after 30 steps the quarter holds the full box's velocities.
Velocity3d run_symmetric_jet(const Grid3d& g, const Boundaries3d& b, double x0, double z0) {
  FluidSettings3d s;
  s.boundaries = b;
  s.viscosity_m2_per_s = 0.01;
  s.density_kg_per_m3 = 1.0;
  auto solver = make_fluid_solver_3d(g, s);
  const auto bump = [&](double x, double z) { return std::exp(-((x - x0) * (x - x0) + (z - z0) * (z - z0)) / 0.04); };
  Velocity3d& a = solver->body_acceleration();
  set_component(g, b, a, 0, [&](double x, double, double z) { return -(x - x0) * bump(x, z); });
  set_component(g, b, a, 1, [&](double x, double y, double z) { return bump(x, z) * std::sin(kPi * y / 0.75); });
  set_component(g, b, a, 2, [&](double x, double, double z) { return -(z - z0) * bump(x, z); });
  for (int step = 0; step < 30; ++step) solver->step(0.005);
  return solver->state().velocity;
}

TEST(QuarterTank3d, MirrorPlanesReproduceTheSymmetricFullBox) {
  const Grid3d full({16, 12, 16}, {1.0, 0.75, 1.0}), quarter({8, 12, 8}, {0.5, 0.75, 0.5});
  const Velocity3d v_full = run_symmetric_jet(full, Boundaries3d::closed_box(), 0.5, 0.5);
  const Velocity3d v_quarter = run_symmetric_jet(quarter, Boundaries3d::closed_box().quarter(), 0.0, 0.0);
  double diff = 0.0, peak = 0.0;
  for (int c = 0; c < 3; ++c)
    for_each_interior_cell(quarter, [&](std::size_t I, int i, int j, int k) {
      const double q = v_quarter.c[static_cast<std::size_t>(c)][I];
      diff = std::max(diff, std::abs(q - v_full.c[static_cast<std::size_t>(c)][full.index(i + 8, j, k + 8)]));
      peak = std::max(peak, std::abs(q));
    });
  std::printf("  quarter tank: max |u_quarter - u_full| = %.2e m/s (peak %.3f m/s)\n", diff, peak);
  EXPECT_GT(peak, 0.05);
  EXPECT_LT(diff, 1e-15);  // measured 2.8e-17: round-off
}

// A random flow in the lid-driven cube, five steps on 1 and on 2 threads: the same bits (both
// methods).
TEST(Fluid3dThreads, OneAndTwoThreadsGiveTheSameBits) {
  const Grid3d g({12, 16, 14}, {1.0, 1.0, 1.0});
  std::vector<Velocity3d> results;
  for (int run = 0; run < 4; ++run) {
    const int threads = 1 + run % 2;
    FluidSettings3d s;
    s.method = run < 2 ? FluidMethod3d::eulerian : FluidMethod3d::semi_lagrangian;
    s.boundaries = Boundaries3d::lid_driven_cavity(1.0);
    s.viscosity_m2_per_s = 0.01;
    s.threads = threads;
    auto solver = make_fluid_solver_3d(g, s);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> uniform(-0.5, 0.5);
    for (int c = 0; c < 3; ++c)
      set_component(g, s.boundaries, solver->mutable_state().velocity, c, [&](double, double, double) { return uniform(rng); });
    for (int step = 0; step < 5; ++step) solver->step(solver->stable_time_step());
    results.push_back(solver->state().velocity);
  }
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(results[0].c[c], results[1].c[c]);
    EXPECT_EQ(results[2].c[c], results[3].c[c]);
  }
}

}  // namespace
}  // namespace jellysim::fluid3d
