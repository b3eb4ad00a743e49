// Measured global order of convergence against problems with known solutions: the slope of
// log(error) against log(dt) over several halvings of dt must match the method's order (±0.3).
#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>

#include "jellysim/ode/integrator.hpp"
#include "test_problems.hpp"
#include "test_support.hpp"

namespace jellysim::ode::testing {
namespace {

struct Case {
  std::string method;
  double expected_order;
  int coarsest_steps;  ///< step counts coarsest_steps * 2^k, k = 0..3
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) { return gtest_name(info.param.method); }

void PrintTo(const Case& c, std::ostream* os) { *os << c.method; }

template <typename ErrorAt>
double measured_order(const Case& c, double t_end, ErrorAt error_at) {
  std::vector<double> dts, errors;
  for (int steps = c.coarsest_steps; steps <= 8 * c.coarsest_steps; steps *= 2) {
    dts.push_back(t_end / steps);
    errors.push_back(error_at(steps));
  }
  const double slope = fitted_slope(dts, errors);
  std::printf("  %-20s dt %.3g..%.3g  error %.3e..%.3e  order %.3f\n", c.method.c_str(), dts.front(), dts.back(),
              errors.front(), errors.back(), slope);
  return slope;
}

// Nonlinear and non-autonomous, so stage times and all order conditions matter (a linear test
// problem only checks the stability polynomial).
class RationalDecayOrder : public ::testing::TestWithParam<Case> {};

TEST_P(RationalDecayOrder, MatchesTheMethodOrder) {
  const Case& c = GetParam();
  const RationalDecay system;
  const double t_end = 2.0;
  const double order = measured_order(c, t_end, [&](int steps) {
    auto integrator = make_integrator(c.method);
    const Vector y = integrate_fixed(*integrator, system, Vector::Ones(1), 0.0, t_end, steps);
    return std::abs(y[0] - RationalDecay::exact(t_end));
  });
  EXPECT_NEAR(order, c.expected_order, 0.3);
}

INSTANTIATE_TEST_SUITE_P(Methods, RationalDecayOrder,
                         ::testing::Values(Case{"forward-euler", 1, 200}, Case{"predictor-corrector", 1, 200},
                                           Case{"rk2", 2, 50}, Case{"rk4", 4, 10}, Case{"dopri5", 5, 40},
                                           Case{"backward-euler", 1, 200}),
                         case_name);

// A second-order system with a position-only, nonlinear force (leap-frog's home ground).
class KeplerOrder : public ::testing::TestWithParam<Case> {};

TEST_P(KeplerOrder, MatchesTheMethodOrder) {
  const Case& c = GetParam();
  const Kepler system(0.5);
  const Vector y0 = system.initial_state();
  const double order = measured_order(c, Kepler::period(), [&](int steps) {
    auto integrator = make_integrator(c.method);
    return (integrate_fixed(*integrator, system, y0, 0.0, Kepler::period(), steps) - y0).lpNorm<Eigen::Infinity>();
  });
  EXPECT_NEAR(order, c.expected_order, 0.3);
}

INSTANTIATE_TEST_SUITE_P(Methods, KeplerOrder,
                         ::testing::Values(Case{"leapfrog", 2, 400}, Case{"rk2", 2, 400}, Case{"rk4", 4, 200},
                                           Case{"dopri5", 5, 100}),
                         case_name);

// A linear second-order system for the first-order methods (on Kepler they need tiny steps to
// reach their asymptotic regime).
class HarmonicOrder : public ::testing::TestWithParam<Case> {};

TEST_P(HarmonicOrder, MatchesTheMethodOrder) {
  const Case& c = GetParam();
  const HarmonicOscillator system(1.0);
  const Vector y0{{1.0, 0.0}};
  const double t_end = 2.0;
  const double order = measured_order(c, t_end, [&](int steps) {
    auto integrator = make_integrator(c.method);
    return (integrate_fixed(*integrator, system, y0, 0.0, t_end, steps) - system.exact(t_end, y0))
        .lpNorm<Eigen::Infinity>();
  });
  EXPECT_NEAR(order, c.expected_order, 0.3);
}

INSTANTIATE_TEST_SUITE_P(Methods, HarmonicOrder,
                         ::testing::Values(Case{"forward-euler", 1, 50}, Case{"predictor-corrector", 1, 50},
                                           Case{"leapfrog", 2, 50}, Case{"backward-euler", 1, 50}),
                         case_name);

// With a velocity-dependent force the closing kick uses v_{1/2}: leap-frog drops to first order
// (documented in leapfrog.hpp).
TEST(LeapfrogOrder, DropsToFirstOrderWithDrag) {
  const DampedOscillator system(1.0, 0.2);
  const Vector y0{{1.0, 0.0}};
  const double t_end = 5.0;
  const double order = measured_order(Case{"leapfrog (drag)", 1, 200}, t_end, [&](int steps) {
    auto integrator = make_integrator("leapfrog");
    return (integrate_fixed(*integrator, system, y0, 0.0, t_end, steps) - system.exact(t_end, y0))
        .lpNorm<Eigen::Infinity>();
  });
  EXPECT_NEAR(order, 1.0, 0.3);
}

}  // namespace
}  // namespace jellysim::ode::testing
