#pragma once
// Restarted GMRES (Saad & Schultz 1986) for small matrix-free systems A x = b: the semi-implicit
// immersed-boundary coupling solves one per step, with A applied through the fluid's projection,
// and the Jacobian-free backward Euler (newton_krylov.hpp) one per Newton iteration.
#include <functional>

#include <Eigen/Dense>

namespace jellysim::ode {

struct GmresReport {
  int iterations = 0;             ///< operator applications
  double relative_residual = 0.0; ///< ‖b − A x‖ / ‖b‖ at exit
  bool converged = false;
  bool restarted = false;         ///< more than one cycle of `restart` iterations was needed
  /// gmres_from_zero only: x = Σ coefficients[k]·v_k holds (false after a restart, a stop at
  /// max_iterations or a convergence found only by the final residual check).
  bool coefficients_valid = false;
};

using LinearOperator = std::function<void(const Eigen::VectorXd& in, Eigen::VectorXd& out)>;

/// Solves A x = b starting from x (the initial guess); stops when ‖b − Ax‖ ≤ tolerance·‖b‖.
GmresReport gmres(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                  int max_iterations, int restart = 30);

/// GMRES from x = 0 for callers that keep by-products of each operator application: the k-th
/// application is to the k-th Krylov basis vector v_k, and on return x = Σ coefficients[k]·v_k
/// when report.coefficients_valid (otherwise coefficients is empty and x is still the result). Saves two
/// applications over gmres(): none for the zero initial guess, and no final check of the residual
/// (the Givens recurrence gives it; exact in exact arithmetic).
GmresReport gmres_from_zero(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                            Eigen::VectorXd& coefficients, double tolerance, int max_iterations, int restart = 30);

}  // namespace jellysim::ode
