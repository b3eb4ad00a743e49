// The adaptive step-size controller (thesis §2.4.6): tolerance met against exact solutions, step
// counting, rejections and failures, landing on output times, and its advantage over a fixed step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "jellysim/ode/integrator.hpp"
#include "test_problems.hpp"
#include "test_support.hpp"

namespace jellysim::ode::testing {
namespace {

AdaptiveSettings with_tolerance(double tol) {
  AdaptiveSettings settings;
  settings.atol = tol;
  settings.rtol = tol;
  return settings;
}

TEST(ErrorNorm, IsTheWeightedRms) {
  const Vector error{{1.0, 2.0}}, y{{0.0, 10.0}}, y_new{{0.0, -20.0}};
  // scales: 1 + 0.1 * 0 = 1 and 1 + 0.1 * 20 = 3
  EXPECT_NEAR(error_norm(error, y, y_new, 1.0, 0.1), std::sqrt((1.0 + 4.0 / 9.0) / 2.0), 1e-15);
  EXPECT_EQ(error_norm(Vector(), Vector(), Vector(), 1.0, 1.0), 0.0);
}

TEST(AdaptiveStepper, UsesStepDoublingOnlyWithoutAnEmbeddedPair) {
  for (const std::string& name : integrator_names()) {
    auto integrator = make_integrator(name);
    const AdaptiveStepper stepper(*integrator, {});
    EXPECT_EQ(stepper.uses_step_doubling(), name != "dopri5" && name != "rk2") << name;
  }
}

TEST(AdaptiveStepper, RejectsInvalidSettings) {
  auto integrator = make_integrator("dopri5");
  AdaptiveSettings settings;
  settings.safety = 0.0;
  EXPECT_THROW(AdaptiveStepper(*integrator, settings), std::invalid_argument);
}

// dopri5 and rk2 through their embedded pairs, rk4 through step doubling.
class MeetsTolerance : public ::testing::TestWithParam<std::string> {};

TEST_P(MeetsTolerance, OnANonlinearProblemWithAKnownSolution) {
  const RationalDecay system;
  for (const double tol : {1e-4, 1e-6, 1e-8}) {
    auto integrator = make_integrator(GetParam());
    const AdaptiveRun run =
        integrate_adaptive(*integrator, system, Vector::Ones(1), 0.0, 2.0, with_tolerance(tol), 0.01);
    const double error = std::abs(run.y[0] - RationalDecay::exact(2.0));
    std::printf("  %-8s tol %.0e: error %.2e = %.2f tol, %lld accepted, %lld rejected\n", GetParam().c_str(), tol,
                error, error / tol, static_cast<long long>(run.stats.accepted),
                static_cast<long long>(run.stats.rejected));
    EXPECT_LT(error, 5.0 * tol);
    EXPECT_GT(error, 0.02 * tol) << "far more accurate than asked: the controller wastes steps";
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, MeetsTolerance, ::testing::Values("dopri5", "rk2", "rk4"),
                         [](const auto& info) { return gtest_name(info.param); });

TEST(AdaptiveStepper, CountsStepsAndEvaluationsOnAnEccentricOrbit) {
  const Kepler system(0.9);
  auto dopri5 = make_integrator("dopri5");
  const AdaptiveRun run =
      integrate_adaptive(*dopri5, system, system.initial_state(), 0.0, Kepler::period(), with_tolerance(1e-8), 0.01);
  EXPECT_GT(run.stats.rejected, 0);
  // FSAL: 7 evaluations for the first attempt, 6 for every later one, rejected ones included.
  EXPECT_EQ(system.evaluations(), 1 + 6 * (run.stats.accepted + run.stats.rejected));
}

/// Fewest fixed steps (on a grid of ratio 1.1) whose error at t = period is at most `target`.
std::int64_t fixed_step_evaluations_for(const std::string& method, const Kepler& system, double target) {
  for (double steps = 100; steps < 1e6; steps *= 1.1) {
    auto integrator = make_integrator(method);
    system.reset_counters();
    const Vector y =
        integrate_fixed(*integrator, system, system.initial_state(), 0.0, Kepler::period(), static_cast<int>(steps));
    if ((y - system.initial_state()).lpNorm<Eigen::Infinity>() <= target) return system.evaluations();
  }
  return 0;
}

// Fast perihelion passage, slow aphelion: the step the orbit needs varies by two orders of magnitude.
class BeatsFixedStep : public ::testing::TestWithParam<std::string> {};

TEST_P(BeatsFixedStep, OnAnEccentricOrbitAtEqualAccuracy) {
  const Kepler system(0.9);
  auto integrator = make_integrator(GetParam());
  const AdaptiveRun run = integrate_adaptive(*integrator, system, system.initial_state(), 0.0, Kepler::period(),
                                             with_tolerance(1e-8), 0.01);
  const std::int64_t adaptive = system.evaluations();
  const double error = (run.y - system.initial_state()).lpNorm<Eigen::Infinity>();
  const std::int64_t fixed = fixed_step_evaluations_for(GetParam(), system, error);
  std::printf("  %-8s Kepler e = 0.9, error %.2e: adaptive %lld evaluations, fixed step %lld (%.1fx)\n",
              GetParam().c_str(), error, static_cast<long long>(adaptive), static_cast<long long>(fixed),
              static_cast<double>(fixed) / static_cast<double>(adaptive));
  EXPECT_GT(fixed, 3 * adaptive);
}

INSTANTIATE_TEST_SUITE_P(Methods, BeatsFixedStep, ::testing::Values("dopri5", "rk4"),
                         [](const auto& info) { return gtest_name(info.param); });

TEST(AdaptiveStepper, LandsOnTheLimitWithoutShrinkingTheNextStep) {
  const RationalDecay system;
  auto dopri5 = make_integrator("dopri5");
  AdaptiveStepper stepper(*dopri5, with_tolerance(1e-6));
  double t = 0.0, taken = 0.0;
  Vector y = Vector::Ones(1);
  const double next = stepper.step(system, t, y, 0.1, 1e-9, taken);
  EXPECT_EQ(taken, 1e-9);
  EXPECT_EQ(t, 1e-9);
  EXPECT_GE(next, 0.1);
}

TEST(AdaptiveStepper, AFailedStepShrinksByMinFactor) {
  const ScalarLinear system(1.0);  // backward Euler's iteration matrix is singular at dt = 1
  auto backward_euler = make_integrator("backward-euler");
  AdaptiveStepper stepper(*backward_euler, with_tolerance(1.0));
  double t = 0.0, taken = 0.0;
  Vector y = Vector::Ones(1);
  stepper.step(system, t, y, 1.0, 10.0, taken);
  EXPECT_EQ(stepper.statistics().rejected, 1);
  EXPECT_EQ(stepper.statistics().accepted, 1);
  EXPECT_EQ(taken, AdaptiveSettings{}.min_factor);
}

TEST(AdaptiveStepper, NonFiniteErrorsAreRejectedUntilTheStepUnderflows) {
  const BreaksDownAt system(0.5);
  auto dopri5 = make_integrator("dopri5");
  AdaptiveStepper stepper(*dopri5, with_tolerance(1e-6));
  double t = 0.0, dt = 0.1, taken = 0.0;
  Vector y = Vector::Ones(1);
  try {
    while (t < 1.0) dt = stepper.step(system, t, y, dt, 1.0 - t, taken);
    FAIL() << "no exception";
  } catch (const StepSizeUnderflow& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("at t = "), std::string::npos) << message;
    EXPECT_NE(message.find("dt = "), std::string::npos) << message;
  }
  EXPECT_GT(t, 0.49);
  EXPECT_LE(t, 0.5);
  EXPECT_GT(stepper.statistics().rejected, 0);
  EXPECT_TRUE(y.allFinite());
}

TEST(AdaptiveStepper, RequiresAPositiveLimit) {
  auto dopri5 = make_integrator("dopri5");
  AdaptiveStepper stepper(*dopri5, {});
  double t = 0.0, taken = 0.0;
  Vector y = Vector::Ones(1);
  EXPECT_THROW(stepper.step(RationalDecay{}, t, y, 0.1, 0.0, taken), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::ode::testing
