#pragma once
// A first-order ODE system y' = f(t, y) (thesis eq. 2.20), with an optional analytic Jacobian
// for implicit methods and an optional second-order split y = [q; v], q' = v for leap-frog.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>

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
  virtual void compute_jacobian(double /*t*/, const Vector& /*y*/, SparseMatrix& /*jac*/) const {}

 private:
  mutable std::int64_t evaluations_ = 0;
  mutable std::int64_t jacobian_evaluations_ = 0;
};

}  // namespace jellysim::ode
