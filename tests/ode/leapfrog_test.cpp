// Leap-frog specifics (its order and energy behaviour are in convergence_test and energy_test).
#include "jellysim/ode/leapfrog.hpp"

#include <gtest/gtest.h>

#include "test_problems.hpp"

namespace jellysim::ode::testing {
namespace {

TEST(Leapfrog, RejectsFirstOrderSystems) {
  Leapfrog leapfrog;
  const RationalDecay system;
  Vector y1;
  try {
    leapfrog.step(system, 0.0, 0.1, Vector::Ones(1), y1, nullptr);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("position_size"), std::string::npos) << e.what();
  }
}

TEST(Leapfrog, TwoEvaluationsPerStep) {
  Leapfrog leapfrog;
  const Kepler system(0.5);
  Vector y = system.initial_state(), y1;
  for (int i = 0; i < 10; ++i) {
    leapfrog.step(system, 0.01 * i, 0.01, y, y1, nullptr);
    y.swap(y1);
  }
  EXPECT_EQ(system.evaluations(), 20);
}

TEST(Leapfrog, IsTimeReversibleForPositionOnlyForces) {
  Leapfrog leapfrog;
  const Kepler system(0.5);
  const Vector y0 = system.initial_state();
  Vector forward, back;
  leapfrog.step(system, 0.0, 0.05, y0, forward, nullptr);
  leapfrog.step(system, 0.05, -0.05, forward, back, nullptr);
  EXPECT_LT((back - y0).lpNorm<Eigen::Infinity>(), 1e-14);
}

}  // namespace
}  // namespace jellysim::ode::testing
