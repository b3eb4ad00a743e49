#pragma once
// Restarted GMRES (Saad & Schultz 1986) for small matrix-free systems A x = b: the semi-implicit
// immersed-boundary coupling solves one per step, with A applied through the fluid's projection.
#include <functional>

#include <Eigen/Dense>

namespace jellysim::coupling {

struct GmresReport {
  int iterations = 0;             ///< operator applications
  double relative_residual = 0.0; ///< ‖b − A x‖ / ‖b‖ at exit
  bool converged = false;
  bool restarted = false;         ///< more than one cycle of `restart` iterations was needed
};

using LinearOperator = std::function<void(const Eigen::VectorXd& in, Eigen::VectorXd& out)>;

/// Solves A x = b starting from x (the initial guess); stops when ‖b − Ax‖ ≤ tolerance·‖b‖.
GmresReport gmres(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                  int max_iterations, int restart = 30);

/// GMRES from x = 0 for callers that keep by-products of each operator application: the k-th
/// application is to the k-th Krylov basis vector v_k, and on return x = Σ coefficients[k]·v_k
/// unless report.restarted (then coefficients is empty and x is still the solution). Saves two
/// applications over gmres(): none for the zero initial guess, and no final check of the residual
/// (the Givens recurrence gives it; exact in exact arithmetic).
GmresReport gmres_from_zero(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                            Eigen::VectorXd& coefficients, double tolerance, int max_iterations, int restart = 30);

}  // namespace jellysim::coupling
