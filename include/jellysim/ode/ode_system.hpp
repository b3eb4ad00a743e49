#pragma once
// A first-order ODE system y' = f(t, y) (thesis eq. 2.20), with an optional analytic Jacobian
// for implicit methods and an optional second-order split y = [q; v], q' = v for leap-frog.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <span>

namespace jellysim::ode {

using Vector = Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double>;

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  /// Number of components of y.
  virtual Eigen::Index dimension() const = 0;

  /// dydt = f(t, y). Counts one function evaluation.
  void derivative(double t, const Vector& y, Vector& dydt) const {
    ++evaluations_;
    compute_derivative(t, y, dydt);
  }

  /// A Runge–Kutta stage (eq. 2.38): y_stage = y + h Σ_j weights[j] k[j] (terms with a zero weight
  /// skipped, the others added in j order), and dydt = f(t, y_stage). Counts one function
  /// evaluation. A system may form y_stage inside its own evaluation (in parallel parts, say); the
  /// result is bit for bit the default's.
  void stage_derivative(double t, const Vector& y, double h, std::span<const double> weights,
                        std::span<const Vector> k, Vector& y_stage, Vector& dydt) const {
    ++evaluations_;
    compute_stage_derivative(t, y, h, weights, k, y_stage, dydt);
  }

  /// True when jacobian() is implemented (needed by backward Euler).
  virtual bool has_jacobian() const { return false; }
  /// J = df/dy at (t, y), as a sparse matrix of size dimension() x dimension(). Counts one
  /// Jacobian evaluation.
  void jacobian(double t, const Vector& y, SparseMatrix& jac) const {
    ++jacobian_evaluations_;
    compute_jacobian(t, y, jac);
  }

  /// For second-order systems in the form y = [q; v] with q' = v (thesis eqs. 2.29-2.30):
  /// the length of q (half the dimension). 0 means "not a second-order system".
  virtual Eigen::Index position_size() const { return 0; }

  std::int64_t evaluations() const { return evaluations_; }
  std::int64_t jacobian_evaluations() const { return jacobian_evaluations_; }
  void reset_counters() const { evaluations_ = 0; jacobian_evaluations_ = 0; }

 protected:
  virtual void compute_derivative(double t, const Vector& y, Vector& dydt) const = 0;
  /// Forms y_stage (form_stage_state, ode/stage_sum.hpp), then calls compute_derivative.
  virtual void compute_stage_derivative(double t, const Vector& y, double h, std::span<const double> weights,
                                        std::span<const Vector> k, Vector& y_stage, Vector& dydt) const;
  virtual void compute_jacobian(double /*t*/, const Vector& /*y*/, SparseMatrix& /*jac*/) const {}

 private:
  mutable std::int64_t evaluations_ = 0;
  mutable std::int64_t jacobian_evaluations_ = 0;
};

}  // namespace jellysim::ode
