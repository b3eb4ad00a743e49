#pragma once
// Fluidless motion and equilibrium of a shell body (docs/three-d.md, "Part 3"): the body as a
// second-order ODE system y = [x; v] for the project's integrators (ode::Leapfrog, explicit and
// symplectic), and a Newton solver for static equilibrium on the assembled stiffness matrix.
#include <functional>
#include <vector>

#include "jellysim/ode/ode_system.hpp"
#include "jellysim/shell/shell_body.hpp"

namespace jellysim::shell {

/// Loads and supports of a shell body.
struct ShellLoads {
  Vector external_force;         ///< constant force per component (N), 3 × vertices; empty: none
  std::vector<char> fixed;       ///< per component, 1: held where it starts; empty: none
  double damping_per_s = 0.0;    ///< mass-proportional drag, force −c m v (a stand-in for the water)
};

/// M a = f_elastic(x) + f_external − c M v, with a = 0 and v = 0 on fixed components. `before_force`
/// runs before every force evaluation with the time (the muscles' actuation). The Jacobian
/// [[0, I], [−M⁻¹K, −cI]] (K = stiffness_matrix, fixed rows zero) lets ode::BackwardEuler step it.
class ShellSystem final : public ode::OdeSystem {
 public:
  ShellSystem(ShellBody& body, ShellLoads loads, std::function<void(double)> before_force = {});
  Eigen::Index dimension() const override { return 2 * position_size(); }
  Eigen::Index position_size() const override { return 3 * static_cast<Eigen::Index>(body_.vertex_count()); }
  /// y = [x; 0] from positions.
  Vector initial_state(const Vector& x) const;
  bool has_jacobian() const override { return true; }

 protected:
  void compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const override;
  void compute_jacobian(double t, const ode::Vector& y, ode::SparseMatrix& jac) const override;

 private:
  ShellBody& body_;
  ShellLoads loads_;
  std::function<void(double)> before_force_;
};

/// ½ Σ m |v|² (J) for stacked velocities.
double kinetic_energy(const ShellBody& body, const Vector& v);

struct StaticSolution {
  Vector x;
  int iterations = 0;
  double residual_n = 0.0;  ///< largest unbalanced force on a free component at the end
};

/// Newton's method for f_elastic(x) + f_external = 0 on the free components, from x0, with the
/// assembled stiffness (stiffness_matrix) factorised by sparse LDLᵀ; stops when the largest free
/// force is below tolerance_n, when it falls by less than half in an iteration (round-off), or
/// after max_iterations.
StaticSolution solve_static(const ShellBody& body, const ShellLoads& loads, const Vector& x0, double tolerance_n,
                            int max_iterations = 30);

}  // namespace jellysim::shell
