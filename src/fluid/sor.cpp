#include "jellysim/fluid/sor.hpp"

#include <algorithm>

namespace jellysim::fluid {

void sor_sweep(const PoissonOperator& op, std::span<const double> b, std::span<double> p, double omega) {
  const int nx = op.nx();
  for (int j = 0; j < op.ny(); ++j)
    for (int i = 0; i < nx; ++i) {
      const double diag = op.diagonal(i, j);
      if (diag == 0.0) continue;  // a single cell with Neumann sides everywhere
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      // Eq. 4.11: p ← (1 − ω) p + ω / diag · (Σ neighbours − b).
      p[k] = (1.0 - omega) * p[k] + omega / diag * (op.neighbour_sum(p, i, j) - b[k]);
    }
}

PressureSolveReport SorSolver::solve(const PoissonOperator& op, std::span<const double> b,
                                     std::span<double> p) {
  rhs_.assign(b.begin(), b.end());
  if (op.singular()) op.remove_weighted_mean(rhs_);
  PressureSolveReport report;
  report.rhs_max = max_abs(rhs_);
  const double target = std::max(settings_.relative_tolerance * report.rhs_max, settings_.absolute_tolerance);
  const int check = std::max(1, settings_.sor_check_interval);
  report.residual_max = op.residual_max(p, rhs_);  // eq. 4.12, max-norm
  while (report.residual_max > target && report.iterations < settings_.max_iterations) {
    for (int s = 0; s < check && report.iterations < settings_.max_iterations; ++s, ++report.iterations)
      sor_sweep(op, rhs_, p, settings_.sor_omega);
    report.residual_max = op.residual_max(p, rhs_);
  }
  report.converged = report.residual_max <= target;
  if (op.singular()) op.remove_weighted_mean(p);
  return report;
}

}  // namespace jellysim::fluid
