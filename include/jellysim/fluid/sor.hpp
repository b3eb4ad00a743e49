#pragma once
// Successive over-relaxation for the pressure equation, thesis eqs. 4.10–4.12 (after Griebel,
// Dornseifer & Neunhoeffer): lexicographic Gauss–Seidel sweeps blended with relaxation ω, stopped
// on the max-norm of the residual of eq. 4.12.
#include "jellysim/fluid/poisson.hpp"

namespace jellysim::fluid {

class SorSolver final : public PressureSolver {
 public:
  explicit SorSolver(const PressureSolverSettings& settings) : settings_(settings) {}
  std::string_view name() const override { return "sor"; }
  PressureSolveReport solve(const PoissonOperator& op, std::span<const double> b,
                            std::span<double> p) override;

 private:
  PressureSolverSettings settings_;
  std::vector<double> rhs_;  // b made compatible (reused between calls)
};

/// One SOR sweep of eq. 4.11 over the whole grid, in lexicographic order.
void sor_sweep(const PoissonOperator& op, std::span<const double> b, std::span<double> p, double omega);

}  // namespace jellysim::fluid
