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
};

using LinearOperator = std::function<void(const Eigen::VectorXd& in, Eigen::VectorXd& out)>;

/// Solves A x = b starting from x (the initial guess); stops when ‖b − Ax‖ ≤ tolerance·‖b‖.
GmresReport gmres(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                  int max_iterations, int restart = 30);

}  // namespace jellysim::coupling
