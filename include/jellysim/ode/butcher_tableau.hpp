#pragma once
// Explicit Runge–Kutta methods as data (thesis §2.4.5): a Butcher tableau per method, driving the
// one generic stepper in explicit_runge_kutta.hpp.
#include <cstddef>
#include <string>
#include <vector>

namespace jellysim::ode {

/// Stage i evaluates k_i = f(t + c_i dt, y + dt Σ_{j<i} a_ij k_j); the step is y + dt Σ b_i k_i and
/// the embedded solution (when b_hat is not empty) y + dt Σ b_hat_i k_i.
struct ButcherTableau {
  std::string name;
  std::vector<double> c;               ///< nodes, c[0] = 0
  std::vector<std::vector<double>> a;  ///< strictly lower triangular: a[i] holds a_i0 .. a_i(i-1)
  std::vector<double> b;               ///< weights of the propagated solution
  std::vector<double> b_hat;           ///< weights of the embedded solution; empty without a pair
  int order = 0;
  int embedded_order = 0;  ///< 0 without an embedded pair
  /// First same as last: the last stage is f(t + dt, y_out), reusable as the next step's first.
  bool fsal = false;

  std::size_t stages() const { return b.size(); }
};

/// Eq. 2.22: y1 = y + dt f(t, y).
ButcherTableau forward_euler_tableau();
/// Eqs. 2.26-2.27 with one correction: y1 = y + dt f(t + dt, y + dt f(t, y)).
ButcherTableau predictor_corrector_tableau();
/// Trapezoidal rule / Heun (eq. 2.40 with a1 = a2 = 1/2, c1 = 1), forward Euler embedded.
ButcherTableau rk2_tableau();
/// The classical fourth-order Runge–Kutta method.
ButcherTableau rk4_tableau();
/// Dormand & Prince (1980) 5(4), FSAL, propagating the fifth-order solution.
ButcherTableau dopri5_tableau();

/// Checks shapes, c_i = Σ_j a_ij, Σ b = 1 (and Σ b_hat = 1) and the FSAL structure; throws
/// std::invalid_argument on the first violation.
void validate(const ButcherTableau& tableau);

}  // namespace jellysim::ode
