// Backward Euler with Newton's method: stiffness, Newton convergence, failures, pattern reuse.
#include "jellysim/ode/backward_euler.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "jellysim/ode/explicit_runge_kutta.hpp"
#include "test_problems.hpp"
#include "test_support.hpp"

namespace jellysim::ode::testing {
namespace {

TEST(BackwardEuler, NeedsAJacobian) {
  BackwardEuler integrator;
  const DampedOscillator system(1.0, 0.1);
  Vector y1;
  EXPECT_THROW(integrator.step(system, 0.0, 0.1, Vector::Ones(2), y1, nullptr), std::invalid_argument);
}

// A stiff spring at ω dt = 100, a hundred times the explicit stability limit ω dt ≈ 1.
TEST(BackwardEuler, StableOnAStiffSpringWhereForwardEulerExplodes) {
  const HarmonicOscillator system(100.0);
  const double dt = 1.0;
  BackwardEuler implicit;
  ExplicitRungeKutta explicit_euler(forward_euler_tableau());
  Vector y_implicit{{1.0, 0.0}}, y_explicit = y_implicit, next;
  double energy = system.energy(y_implicit);
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(implicit.step(system, i * dt, dt, y_implicit, next, nullptr).ok);
    y_implicit.swap(next);
    EXPECT_EQ(implicit.last_iterations(), 1) << "linear system: Newton is exact after one correction";
    EXPECT_LT(system.energy(y_implicit), energy);
    energy = system.energy(y_implicit);
    explicit_euler.step(system, i * dt, dt, y_explicit, next, nullptr);
    y_explicit.swap(next);
  }
  std::printf("  stiff spring, 5 steps at w dt = 100: backward Euler E = %.3e, forward Euler E = %.3e\n", energy,
              system.energy(y_explicit));
  const double e0 = system.energy(Vector{{1.0, 0.0}});
  EXPECT_LT(energy, 1e-15 * e0);
  EXPECT_GT(system.energy(y_explicit), 1e15 * e0);
}

TEST(BackwardEuler, NewtonConvergesQuadraticallyOnANonlinearProblem) {
  const Kepler system(0.5);
  BackwardEuler integrator;
  Vector y = system.initial_state(), next;
  int most = 0;
  for (int i = 0; i < 100; ++i) {
    ASSERT_TRUE(integrator.step(system, 0.01 * i, 0.01, y, next, nullptr).ok);
    y.swap(next);
    most = std::max(most, integrator.last_iterations());
  }
  std::printf("  Kepler e = 0.5, dt = 0.01: at most %d Newton iterations per step\n", most);
  EXPECT_LE(most, 3);
  EXPECT_EQ(integrator.pattern_analyses(), 1);  // one symbolic analysis reused by every factorisation
}

TEST(BackwardEuler, SimplifiedNewtonEvaluatesTheJacobianOncePerStep) {
  const Kepler system(0.5);
  BackwardEuler integrator({.simplified = true});
  const Vector y0 = system.initial_state();
  BackwardEuler full;
  const Vector reference = integrate_fixed(full, system, y0, 0.0, 1.0, 100);
  system.reset_counters();
  const Vector y = integrate_fixed(integrator, system, y0, 0.0, 1.0, 100);
  EXPECT_EQ(system.jacobian_evaluations(), 100);
  EXPECT_LT((y - reference).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(BackwardEuler, ReportsFailureWhenNewtonRunsOutOfIterations) {
  const Kepler system(0.5);
  BackwardEuler integrator({.max_iterations = 1});
  Vector y1;
  EXPECT_FALSE(integrator.step(system, 0.0, 0.05, system.initial_state(), y1, nullptr).ok);
}

TEST(BackwardEuler, ReportsFailureWhenTheIterationMatrixIsSingular) {
  const ScalarLinear system(1.0);  // I - dt J = 0 at dt = 1
  BackwardEuler integrator;
  Vector y1;
  EXPECT_FALSE(integrator.step(system, 0.0, 1.0, Vector::Ones(1), y1, nullptr).ok);
  EXPECT_TRUE(integrator.step(system, 0.0, 0.5, Vector::Ones(1), y1, nullptr).ok);
  EXPECT_NEAR(y1[0], 2.0, 1e-12);  // y1 = y / (1 - dt)
}

}  // namespace
}  // namespace jellysim::ode::testing
