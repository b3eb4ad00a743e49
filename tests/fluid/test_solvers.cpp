// Both fluid solvers against exact and published solutions and conservation properties.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/fluid/eulerian_solver.hpp"
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/reference_data.hpp"

namespace jellysim::fluid {
namespace {

TEST(Poiseuille, InflowOutflowChannelDevelopsTheParabolicProfile) {
  const double H = 1.0, L = 4.0, U = 1.0;
  const MacGrid g(64, 16, L, H);
  FluidSettings f;
  f.viscosity_m2_per_s = 0.1;
  f.density_kg_per_m3 = 1.0;
  f.boundaries = {{BoundaryType::inflow, {U, 0.0}}, {BoundaryType::outflow, {}},
                  {BoundaryType::no_slip, {}}, {BoundaryType::no_slip, {}}};
  f.safety_factor = 0.9;
  EulerianSolver solver(g, f);
  while (solver.time_s() < 20.0) solver.step(solver.stable_time_step());
  // Fully developed: u(y) = 6 U y (H − y) / H² (mean U, centre 1.5 U), v = 0.
  double worst = 0.0;
  for (double x : {2.5, 3.5})
    for (int j = 0; j < g.ny; ++j) {
      const double y = (j + 0.5) * g.dy();
      const double exact = 6.0 * U * y * (H - y) / (H * H);
      worst = std::max(worst, std::abs(solver.state().velocity.u.sample({x, y}) - exact));
    }
  std::printf("  Poiseuille: max |u - parabola| = %.4f (centre speed 1.5)\n", worst);
  EXPECT_LT(worst, 0.01 * 1.5);
  EXPECT_LT(std::abs(solver.state().velocity.v.sample({3.5, 0.5})), 1e-3);
}

FlowState random_periodic_flow(const MacGrid& g, std::string_view solver_name) {
  FluidSettings f;
  f.boundaries = Boundaries::all(BoundaryType::periodic);
  auto solver = make_fluid_solver(solver_name, g, f);
  Velocity& vel = solver->state().velocity;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const Vec2 xu = vel.u.position(i, j), xv = vel.v.position(i, j);
      const double kx = 2.0 * M_PI / g.width_m, ky = 2.0 * M_PI / g.height_m;
      vel.u(i, j) = 0.3 + 0.5 * std::sin(ky * xu.y) + 0.2 * std::cos(kx * xu.x) * std::sin(ky * xu.y);
      vel.v(i, j) = -0.1 + 0.4 * std::cos(kx * xv.x - ky * xv.y);
    }
  solver->apply_boundaries();
  return solver->state();
}

TEST(PeriodicBoundaries, ConserveTotalMomentum) {
  const MacGrid g(24, 20, 1.2, 1.0);
  for (const char* name : {"eulerian", "semi-lagrangian"}) {
    FluidSettings f;
    f.viscosity_m2_per_s = 1e-3;
    f.density_kg_per_m3 = 1.0;
    f.boundaries = Boundaries::all(BoundaryType::periodic);
    f.pressure.relative_tolerance = 1e-12;
    auto solver = make_fluid_solver(name, g, f);
    solver->state().velocity = random_periodic_flow(g, name).velocity;
    solver->apply_boundaries();
    // Project once so that the momentum is measured on a divergence-free field.
    solver->step(1e-6);
    const Vec2 m0 = total_momentum(solver->state().velocity, true, true);
    for (int k = 0; k < 20; ++k) solver->step(std::min(0.01, solver->stable_time_step()));
    const Vec2 m1 = total_momentum(solver->state().velocity, true, true);
    const double scale = std::abs(m0.x) + std::abs(m0.y);
    std::printf("  %s: momentum drift %.2e relative\n", name, norm(m1 - m0) / scale);
    if (std::string_view(name) == "eulerian")
      EXPECT_LT(norm(m1 - m0), 1e-12 * scale);  // flux form: exact up to rounding
    else
      EXPECT_LT(norm(m1 - m0), 1e-2 * scale);  // interpolation is not conservative
  }
}

TEST(BodyAcceleration, UniformForceAcceleratesAPeriodicFluidExactly) {
  const MacGrid g(16, 16, 1.0, 1.0);
  for (const char* name : {"eulerian", "semi-lagrangian"}) {
    FluidSettings f;
    f.viscosity_m2_per_s = 1e-2;
    f.boundaries = Boundaries::all(BoundaryType::periodic);
    auto solver = make_fluid_solver(name, g, f);
    solver->body_acceleration().u.fill(0.5);
    solver->body_acceleration().v.fill(-0.25);
    for (int k = 0; k < 10; ++k) solver->step(0.01);
    EXPECT_NEAR(solver->state().velocity.u(3, 7), 0.05, 1e-12) << name;
    EXPECT_NEAR(solver->state().velocity.v(9, 2), -0.025, 1e-12) << name;
  }
}

TEST(FreeSlipWalls, AllowTangentialFlowAndNoNormalFlow) {
  const MacGrid g(16, 16, 1.0, 1.0);
  for (const char* name : {"eulerian", "semi-lagrangian"}) {
    // A uniform stream along free-slip walls is an exact steady solution.
    FluidSettings f;
    f.viscosity_m2_per_s = 1e-2;
    f.boundaries = {{BoundaryType::periodic, {}}, {BoundaryType::periodic, {}},
                    {BoundaryType::free_slip, {}}, {BoundaryType::free_slip, {}}};
    auto solver = make_fluid_solver(name, g, f);
    solver->state().velocity.u.fill(1.0);
    solver->apply_boundaries();
    for (int k = 0; k < 20; ++k) solver->step(0.02);
    for (int i = 0; i < g.nx; ++i) {
      EXPECT_NEAR(solver->state().velocity.u.sample({(i + 0.5) / 16.0, 0.0}), 1.0, 1e-10) << name;
      EXPECT_EQ(solver->state().velocity.v(i, 0), 0.0);
      EXPECT_EQ(solver->state().velocity.v(i, g.ny), 0.0);
    }
    // A vortex in a free-slip box keeps sliding along the walls but never crosses them.
    f.boundaries = Boundaries::all(BoundaryType::free_slip);
    auto box = make_fluid_solver(name, g, f);
    TaylorGreen tg{2.0, 1.0, 1e-2};  // cells of size 1 × 1: walls on the cell lines
    box->state().velocity = tg.sample(g, 0.0);
    box->apply_boundaries();
    for (int k = 0; k < 20; ++k) box->step(0.01);
    const Velocity& vel = box->state().velocity;
    double wall_tangential = 0.0;
    for (int j = 0; j < g.ny; ++j) {
      EXPECT_EQ(vel.u(0, j), 0.0);
      EXPECT_EQ(vel.u(g.nx, j), 0.0);
      wall_tangential = std::max(wall_tangential, std::abs(vel.v.sample({0.0, (j + 0.5) / 16.0})));
    }
    EXPECT_GT(wall_tangential, 0.5) << name;
  }
}

TEST(EulerianTimeStep, CflViolatingStepIsRefusedWithAMessage) {
  const MacGrid g(16, 16, 1.0, 1.0);
  FluidSettings f;
  f.viscosity_m2_per_s = 1e-3;
  f.boundaries = Boundaries::lid_driven_cavity(1.0);
  f.time_step_policy = TimeStepPolicy::refuse;
  EulerianSolver solver(g, f);
  solver.step(0.01);
  const double limit = solver.stable_time_step();
  try {
    solver.step(10.0 * limit);
    FAIL() << "expected a refusal";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("CFL"), std::string::npos);
  }
}

TEST(EulerianTimeStep, CflViolatingStepIsReducedWithAMessageAndStaysBounded) {
  const MacGrid g(16, 16, 1.0, 1.0);
  FluidSettings f;
  f.viscosity_m2_per_s = 1e-3;
  f.boundaries = Boundaries::lid_driven_cavity(1.0);
  f.time_step_policy = TimeStepPolicy::reduce;
  EulerianSolver solver(g, f);
  const StepReport r = solver.step(1.0);  // ~16 × the CFL limit
  EXPECT_GT(r.substeps, 1);
  EXPECT_FALSE(r.message.empty());
  EXPECT_NEAR(solver.time_s(), 1.0, 1e-12);
  EXPECT_LT(solver.state().velocity.u.max_abs_interior(), 1.5);
}

}  // namespace
}  // namespace jellysim::fluid
