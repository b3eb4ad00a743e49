// Backward Euler for SPH (thesis eq. 2.33) by a Jacobian-free Newton–Krylov solve: one step solves
// the implicit equation, a fluid at rest stays at rest with steps beyond the explicit limit, and
// the Newton–Krylov settings are validated.
#include "jellysim/ode/newton_krylov.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace jellysim::sph {
namespace {

/// A thermalised patch of fluid in a small box with mirrored walls and gravity (about 60 particles).
Scene small_fluid(int threads) {
  Scene s;
  s.sph = {0.05, 2000.0, 40.0, 8.9e-3};
  s.walls = box_walls({0.0, 0.0}, {0.35, 0.3});
  s.position = triangular_lattice({0.0, 0.0}, {0.35, 0.3}, 0.043);
  thermalise(s.position, s.velocity, 0.004, 20.0, 3);  // velocities ~ 0.08 m/s
  s.mass.assign(s.position.size(), 3.3);
  s.fluid_count = s.position.size();
  s.particle_gravity = {0.0, -9.81};
  s.threads = threads;
  return s;
}

TEST(SphBackwardEuler, OneStepSolvesTheImplicitEquation) {
  Scene s = small_fluid(1);
  CoupledSystem system(s);
  const ode::Vector y = system.pack_state();
  const double t = 0.0, dt = 5e-3;
  ode::NewtonKrylovSettings newton;
  newton.atol = newton.rtol = 1e-10;
  ode::JacobianFreeBackwardEuler be(newton);
  ode::Vector y1;
  ASSERT_TRUE(be.step(system, t, dt, y, y1, nullptr).ok);
  EXPECT_GE(be.last_newton_iterations(), 1);
  EXPECT_GT(be.last_gmres_iterations(), 0);
  // G(y1) = y1 − y − Δt f(t + Δt, y1) must vanish to the Newton tolerance.
  ode::Vector f1;
  system.derivative(t + dt, y1, f1);
  const ode::Vector residual = y1 - y - dt * f1;
  EXPECT_LE(ode::error_norm(residual, y, y1, 1e-10, 1e-10), 1.0) << "max |G| = " << residual.cwiseAbs().maxCoeff();
  // ... and the solution is not the explicit Euler step.
  ode::Vector f0;
  system.derivative(t, y, f0);
  const ode::Vector explicit_step = y + dt * f0;
  EXPECT_GT((y1 - explicit_step).cwiseAbs().maxCoeff(), 1e3 * residual.cwiseAbs().maxCoeff());
}

TEST(SphBackwardEuler, RelaxedFluidStaysAtRestWithStepsBeyondTheExplicitLimit) {
  Scene s;
  s.sph = {0.05, 2000.0, 40.0, 8.9e-3};
  const double a = 0.043, width = 8 * a, height = (6 * std::sqrt(3.0) / 2.0 + 1.0) * a;  // the lattice fits
  s.walls = box_walls({0.0, 0.0}, {width, height});
  s.position = triangular_lattice({0.0, 0.0}, {width, height}, a);
  const MassSearch m = find_particle_mass(s.position, width * height, s.sph, s.walls, 1e-8);
  s.velocity.assign(s.position.size(), Vec2{});
  s.mass.assign(s.position.size(), m.mass_kg);
  s.fluid_count = s.position.size();
  relax(s.position, s.mass, s.sph, s.walls, 3000);
  const std::vector<Vec2> start = s.position;
  // Fixed steps of 0.02 s: h / c = 0.05 / √40 ≈ 0.008 s, beyond which explicit methods go unstable.
  RunSettings rs;
  rs.time.integrator = "backward-euler";
  rs.time.adaptive = false;
  rs.time.dt = 0.02;
  rs.time.duration = 1.0;
  rs.time.frame_interval = 0.1;
  std::vector<double> speed;  // fastest particle per frame
  const RunResult r = run(s, rs, [&](double, const Scene& sc, const CoupledSystem&) {
    double fastest = 0.0;
    for (Vec2 v : sc.velocity) fastest = std::max(fastest, norm(v));
    speed.push_back(fastest);
    return std::string();
  });
  ASSERT_FALSE(r.failed) << r.failure;
  EXPECT_EQ(r.statistics.steps, 50);
  EXPECT_LT(*std::max_element(speed.begin(), speed.end()), 1e-3 * std::sqrt(40.0)) << "spurious flow";
  EXPECT_LT(speed.back(), 2e-4) << "flow does not die out";
  double moved = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) moved = std::max(moved, norm(s.position[i] - start[i]));
  EXPECT_LT(moved, 0.05 * a);

}

TEST(SphBackwardEuler, RunsAdaptivelyAndMatchesAnExplicitReference) {
  // Short adaptive run (step doubling) against Dormand–Prince with tight tolerances: both solve
  // the same ODE, so they agree to about the backward-Euler tolerance.
  Scene implicit = small_fluid(2), reference = small_fluid(1);
  RunSettings rs;
  rs.time.adaptive = true;
  rs.time.dt = 1e-3;
  rs.time.duration = 0.05;
  rs.time.frame_interval = 0.05;
  rs.time.tolerances.atol = 1e-6;
  rs.time.tolerances.rtol = 1e-6;
  rs.time.integrator = "backward-euler";
  const auto ignore = [](double, const Scene&, const CoupledSystem&) { return std::string(); };
  const RunResult r = run(implicit, rs, ignore);
  ASSERT_FALSE(r.failed) << r.failure;
  rs.time.integrator = "dopri5";
  rs.time.tolerances.atol = rs.time.tolerances.rtol = 1e-10;
  ASSERT_FALSE(run(reference, rs, ignore).failed);
  double diff = 0.0;
  for (std::size_t i = 0; i < implicit.position.size(); ++i) {
    diff = std::max(diff, norm(implicit.position[i] - reference.position[i]));
  }
  EXPECT_LT(diff, 1e-4);
  EXPECT_GT(r.statistics.function_evaluations, 3 * r.statistics.steps);  // Newton–Krylov work
}

TEST(SphBackwardEuler, RejectsInvalidSettings) {
  ode::NewtonKrylovSettings s;
  s.max_newton_iterations = 0;
  EXPECT_THROW(ode::JacobianFreeBackwardEuler{s}, std::invalid_argument);
  s = {};
  s.gmres_tolerance = 1.0;
  EXPECT_THROW(ode::JacobianFreeBackwardEuler{s}, std::invalid_argument);
  EXPECT_EQ(ode::make_jacobian_free_integrator("backward-euler")->name(), "backward-euler");
  EXPECT_EQ(ode::make_jacobian_free_integrator("rk4")->name(), "rk4");
  EXPECT_THROW(ode::make_jacobian_free_integrator("euler"), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::sph
