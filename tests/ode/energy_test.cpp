// Energy of an undamped spring over 1000 periods at a moderate fixed step (thesis §2.4.1-2.4.3):
// forward Euler gains energy, predictor-corrector and backward Euler lose it, leap-frog keeps it
// within a bounded oscillation without drift.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "jellysim/ode/integrator.hpp"
#include "test_problems.hpp"
#include "test_support.hpp"

namespace jellysim::ode::testing {
namespace {

constexpr int kPeriods = 1000;
constexpr int kStepsPerPeriod = 125;  // ω dt ≈ 0.05

/// Relative energy deviation E/E0 - 1 at every step, over kPeriods periods of ω = 1.
std::vector<double> energy_history(const std::string& method) {
  const HarmonicOscillator system(1.0);
  auto integrator = make_integrator(method);
  const double dt = 2.0 * std::numbers::pi / kStepsPerPeriod;
  Vector y{{1.0, 0.0}}, next;
  const double e0 = system.energy(y);
  std::vector<double> deviation;
  double t = 0.0;
  for (int i = 0; i < kPeriods * kStepsPerPeriod; ++i) {
    EXPECT_TRUE(integrator->step(system, t, dt, y, next, nullptr).ok);
    y.swap(next);
    t += dt;
    deviation.push_back(system.energy(y) / e0 - 1.0);
  }
  return deviation;
}

/// Energy at the end of every period.
std::vector<double> per_period(const std::vector<double>& deviation) {
  std::vector<double> out;
  for (int p = 1; p <= kPeriods; ++p) out.push_back(1.0 + deviation[static_cast<std::size_t>(p * kStepsPerPeriod - 1)]);
  return out;
}

void print_summary(const std::string& method, const std::vector<double>& energies) {
  std::printf("  %-20s E/E0 after 1, 10, 1000 periods: %.4g, %.4g, %.4g\n", method.c_str(), energies[0], energies[9],
              energies.back());
}

TEST(Energy, ForwardEulerGainsEnergyEveryPeriod) {
  const std::vector<double> energies = per_period(energy_history("forward-euler"));
  print_summary("forward-euler", energies);
  EXPECT_TRUE(std::is_sorted(energies.begin(), energies.end()));
  EXPECT_GT(energies.front(), 1.0);
  EXPECT_GT(energies.back(), 1e6);
}

class Dissipative : public ::testing::TestWithParam<std::string> {};

TEST_P(Dissipative, LosesEnergyEveryPeriod) {
  const std::vector<double> energies = per_period(energy_history(GetParam()));
  print_summary(GetParam(), energies);
  EXPECT_TRUE(std::is_sorted(energies.rbegin(), energies.rend()));
  EXPECT_LT(energies.front(), 1.0);
  EXPECT_LT(energies.back(), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Methods, Dissipative, ::testing::Values("predictor-corrector", "backward-euler"),
                         [](const auto& info) { return gtest_name(info.param); });

double max_abs(std::vector<double>::const_iterator begin, std::vector<double>::const_iterator end) {
  double m = 0.0;
  for (auto it = begin; it != end; ++it) m = std::max(m, std::abs(*it));
  return m;
}

double mean(std::vector<double>::const_iterator begin, std::vector<double>::const_iterator end) {
  double sum = 0.0;
  for (auto it = begin; it != end; ++it) sum += *it;
  return sum / static_cast<double>(end - begin);
}

TEST(Energy, LeapfrogStaysBoundedWithoutDrift) {
  const std::vector<double> deviation = energy_history("leapfrog");
  const auto first = deviation.begin(), last = deviation.end();
  const auto one_period = static_cast<std::ptrdiff_t>(kStepsPerPeriod);
  const double worst = max_abs(first, last);
  const double drift = mean(last - one_period, last) - mean(first, first + one_period);
  std::printf("  leapfrog             max |E/E0 - 1| = %.3e, mean drift first->last period = %.3e\n", worst, drift);
  EXPECT_LT(worst, 1e-3);  // ≈ (ω dt)² / 4 for the kick-drift-kick form
  EXPECT_LT(std::abs(drift), 1e-3 * worst);
}

}  // namespace
}  // namespace jellysim::ode::testing
