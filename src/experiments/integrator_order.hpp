#pragma once
// Measured global order of convergence of the integrators on a problem with a known solution.
#include "jellysim/ode/integrator.hpp"

#include <string>
#include <vector>

namespace jellysim::experiments {

/// Two equal point masses joined by one linear spring, started at rest and stretched along x:
/// the length is l(t) = l_r + A cos(ω t), ω = sqrt(2 κ_l / m), the centre stays at the origin.
struct SpringProblem {
  double point_mass = 1.0, stiffness = 50.0, rest_length = 1.0, amplitude = 0.1, end_time = 2.0;
  double omega() const;
};

struct ConvergenceRun {
  double dt = 0.0;
  double error = 0.0;   ///< max-norm of the state error at end_time
  std::int64_t function_evaluations = 0;
};

struct ConvergenceStudy {
  std::string integrator;
  int expected_order = 0;
  std::vector<ConvergenceRun> runs;
  double measured_order = 0.0;  ///< least-squares slope of log(error) against log(dt)
};

/// Runs `integrator` with coarsest_steps, 2x, 4x ... (refinements halvings) fixed steps.
ConvergenceStudy measure_convergence(const std::string& integrator, const SpringProblem& problem, int coarsest_steps,
                                     int refinements);

/// Least-squares slope of log(y) against log(x).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace jellysim::experiments
