#pragma once
// Backward Euler (thesis eq. 2.33) solved by Newton's method (eq. 2.36) with the system's analytic
// sparse Jacobian and a sparse LU factorisation of the iteration matrix I - dt J.
#include <Eigen/SparseLU>
#include <vector>

#include "jellysim/ode/derivative_cache.hpp"
#include "jellysim/ode/integrator.hpp"

namespace jellysim::ode {

struct NewtonSettings {
  /// Converged when the scaled RMS norm of the residual G or of the Newton correction, each
  /// component divided by atol + rtol * max(|y_i|, |y1_i|), is <= 1.
  double rtol = 1e-10;
  double atol = 1e-10;
  int max_iterations = 10;
  bool simplified = false;  ///< simplified Newton: keep the first iteration's Jacobian and factors
};

class BackwardEuler final : public Integrator {
 public:
  explicit BackwardEuler(NewtonSettings settings = {});

  std::string_view name() const override { return "backward-euler"; }
  int order() const override { return 1; }
  /// Solves G(y1) = y1 - y - dt f(t + dt, y1) = 0 from the explicit Euler predictor, applying at
  /// least one Newton correction. Returns
  /// ok = false when Newton does not converge within max_iterations or I - dt J is singular.
  /// Throws std::invalid_argument when !system.has_jacobian().
  StepOutcome step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                   Vector* error) override;
  void reset() override { start_.clear(); }

  /// Newton corrections applied in the last successful step (at least one).
  int last_iterations() const { return last_iterations_; }
  /// Symbolic analyses of I - dt J so far (one per distinct sparsity pattern met in a row).
  int pattern_analyses() const { return pattern_analyses_; }

 private:
  enum class Newton { iterate, converged, failed };
  /// One Newton iteration on G(y1) = 0, updating y1 in place.
  Newton newton_iteration(const OdeSystem& system, double t1, double dt, const Vector& y, Vector& y1, int iteration);
  bool converged(const Vector& v, const Vector& y, const Vector& y1) const;
  /// Evaluates J at (t1, y1) and factorises I - dt J; false when the factorisation fails.
  bool factorize(const OdeSystem& system, double t1, double dt, const Vector& y1);
  /// Symbolic analysis of I - dt J, redone only when its sparsity pattern changes.
  void analyse_pattern_if_changed();

  NewtonSettings settings_;
  DerivativeCache start_;
  Vector f_, residual_, delta_;
  SparseMatrix jacobian_, identity_, iteration_matrix_;
  Eigen::SparseLU<SparseMatrix> solver_;
  std::vector<SparseMatrix::StorageIndex> pattern_outer_, pattern_inner_;
  int last_iterations_ = 0;
  int pattern_analyses_ = 0;
};

}  // namespace jellysim::ode
