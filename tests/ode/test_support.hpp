#pragma once
// Integration loops and a slope fit shared by the ode tests.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "jellysim/ode/integrator.hpp"

namespace jellysim::ode::testing {

/// A registry name as a GoogleTest parameter name ('-' is not allowed there).
inline std::string gtest_name(std::string name) {
  for (char& ch : name) ch = ch == '-' ? '_' : ch;
  return name;
}

/// `steps` fixed steps from (t0, y) to t1; t advances by `t += dt` so FSAL caching applies.
inline Vector integrate_fixed(Integrator& integrator, const OdeSystem& system, Vector y, double t0, double t1,
                              int steps) {
  const double dt = (t1 - t0) / steps;
  double t = t0;
  Vector next;
  for (int i = 0; i < steps; ++i) {
    if (!integrator.step(system, t, dt, y, next, nullptr).ok) throw std::runtime_error("fixed step failed");
    y.swap(next);
    t += dt;
  }
  return y;
}

struct AdaptiveRun {
  Vector y;
  StepStatistics stats;
};

/// Adaptive integration from (t0, y) to exactly t1, starting with step dt0.
inline AdaptiveRun integrate_adaptive(Integrator& integrator, const OdeSystem& system, Vector y, double t0, double t1,
                                      const AdaptiveSettings& settings, double dt0) {
  AdaptiveStepper stepper(integrator, settings);
  double t = t0, dt = dt0, taken = 0.0;
  while (t < t1) {
    const double remaining = t1 - t;
    dt = stepper.step(system, t, y, dt, remaining, taken);
    if (taken == remaining) t = t1;  // land exactly, whatever the rounding of t + remaining
  }
  return {y, stepper.statistics()};
}

/// Least-squares slope of log(error) against log(dt).
inline double fitted_slope(const std::vector<double>& dts, const std::vector<double>& errors) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(dts.size());
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double x = std::log(dts[i]), y = std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace jellysim::ode::testing
