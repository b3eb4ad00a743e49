// The Butcher tableaux and the generic explicit Runge–Kutta stepper: tableau consistency, the
// embedded error estimates, and FSAL reuse of the last stage.
#include <gtest/gtest.h>

#include <cstdio>

#include "jellysim/ode/butcher_tableau.hpp"
#include "jellysim/ode/explicit_runge_kutta.hpp"
#include "test_problems.hpp"
#include "test_support.hpp"

namespace jellysim::ode::testing {
namespace {

TEST(ButcherTableau, AllShippedTableauxAreConsistent) {
  for (const ButcherTableau& tableau :
       {forward_euler_tableau(), predictor_corrector_tableau(), rk2_tableau(), rk4_tableau(), dopri5_tableau()}) {
    EXPECT_NO_THROW(validate(tableau)) << tableau.name;
  }
}

TEST(ButcherTableau, MalformedTableauxAreRejected) {
  ButcherTableau bad_row_sum = rk4_tableau();
  bad_row_sum.a[2][1] = 0.4;
  EXPECT_THROW(ExplicitRungeKutta{bad_row_sum}, std::invalid_argument);
  ButcherTableau bad_fsal = dopri5_tableau();
  bad_fsal.a[6][2] = 0.45;
  bad_fsal.a[6][3] += 500.0 / 1113.0 - 0.45;  // rows still sum to c, but the last row is no longer b
  EXPECT_THROW(validate(bad_fsal), std::invalid_argument);
  ButcherTableau bad_weights = rk2_tableau();
  bad_weights.b_hat = {0.9, 0.0};
  EXPECT_THROW(validate(bad_weights), std::invalid_argument);
}

/// Slope of log|local error estimate| against log dt for one step of the Kepler problem.
double estimate_slope(const ButcherTableau& tableau) {
  ExplicitRungeKutta integrator(tableau);
  const Kepler system(0.5);
  const Vector y0 = system.initial_state();
  std::vector<double> dts, estimates;
  Vector y1, error;
  for (double dt = 0.04; dt > 0.004; dt /= 2) {
    EXPECT_TRUE(integrator.step(system, 0.0, dt, y0, y1, &error).has_error);
    dts.push_back(dt);
    estimates.push_back(error.norm());
  }
  return fitted_slope(dts, estimates);
}

TEST(EmbeddedPair, LocalErrorEstimatesScaleWithTheEmbeddedOrderPlusOne) {
  const double rk2 = estimate_slope(rk2_tableau()), dopri5 = estimate_slope(dopri5_tableau());
  std::printf("  local error estimate slopes: rk2 %.3f (expect 2), dopri5 %.3f (expect 5)\n", rk2, dopri5);
  EXPECT_NEAR(rk2, 2.0, 0.2);
  EXPECT_NEAR(dopri5, 5.0, 0.2);
}

TEST(EmbeddedPair, Rk2EstimateIsHeunMinusForwardEuler) {
  const Kepler system(0.5);
  const Vector y0 = system.initial_state();
  const double dt = 0.01;
  ExplicitRungeKutta rk2(rk2_tableau()), euler(forward_euler_tableau());
  Vector heun, forward, error;
  ASSERT_TRUE(rk2.step(system, 0.0, dt, y0, heun, &error).has_error);
  euler.step(system, 0.0, dt, y0, forward, nullptr);
  EXPECT_LT((error - (heun - forward)).norm(), 1e-14);
}

TEST(EmbeddedPair, MethodsWithoutAPairReportNoError) {
  ExplicitRungeKutta rk4(rk4_tableau());
  const Kepler system(0.5);
  Vector y1, error;
  EXPECT_FALSE(rk4.step(system, 0.0, 0.01, system.initial_state(), y1, &error).has_error);
}

TEST(Fsal, Dopri5UsesSixEvaluationsPerStepAfterTheFirst) {
  const Kepler system(0.5);
  ExplicitRungeKutta dopri5(dopri5_tableau());
  integrate_fixed(dopri5, system, system.initial_state(), 0.0, 1.0, 100);
  EXPECT_EQ(system.evaluations(), 7 + 6 * 99);
}

TEST(Fsal, CacheMissesWhenTheStateChangesOrAfterReset) {
  const Kepler system(0.5);
  ExplicitRungeKutta dopri5(dopri5_tableau());
  const double dt = 0.01;
  Vector y = system.initial_state(), y1;
  dopri5.step(system, 0.0, dt, y, y1, nullptr);
  system.reset_counters();
  Vector nudged = y1;
  nudged[0] += 1e-15;
  dopri5.step(system, dt, dt, nudged, y, nullptr);
  EXPECT_EQ(system.evaluations(), 7);  // different y: the last stage does not apply
  system.reset_counters();
  dopri5.step(system, 2 * dt, dt, y, y1, nullptr);
  EXPECT_EQ(system.evaluations(), 6);  // continues from exactly the last end point
  dopri5.reset();
  system.reset_counters();
  dopri5.step(system, 3 * dt, dt, y1, y, nullptr);
  EXPECT_EQ(system.evaluations(), 7);
}

}  // namespace
}  // namespace jellysim::ode::testing
