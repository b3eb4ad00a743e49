#include "jellysim/ode/newton_krylov.hpp"

#include "jellysim/ode/gmres.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace jellysim::ode {

void validate(const NewtonKrylovSettings& s) {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("backward-euler: ") + what);
  };
  require(s.atol >= 0.0 && s.rtol >= 0.0 && s.atol + s.rtol > 0.0, "Newton atol, rtol must be >= 0, not both 0");
  require(s.max_newton_iterations >= 1, "max_newton_iterations must be >= 1");
  require(s.gmres_tolerance > 0.0 && s.gmres_tolerance < 1.0, "gmres_tolerance must be in (0, 1)");
  require(s.max_gmres_iterations >= 1 && s.gmres_restart >= 1, "GMRES iterations and restart must be >= 1");
}

JacobianFreeBackwardEuler::JacobianFreeBackwardEuler(NewtonKrylovSettings settings) : settings_(settings) {
  validate(settings_);
}

ode::StepOutcome JacobianFreeBackwardEuler::step(const ode::OdeSystem& system, double t, double dt, const ode::Vector& y,
                                                 ode::Vector& y_out, ode::Vector* /*error: no embedded pair*/) {
  last_newton_ = last_gmres_ = 0;
  start_.evaluate(system, t, y, f_);
  y_out = y + dt * f_;  // explicit Euler predictor (eq. 2.22)
  for (int iteration = 0; iteration < settings_.max_newton_iterations; ++iteration) {
    const Newton state = newton_iteration(system, t + dt, dt, y, y_out, iteration);
    if (state != Newton::iterate) return {.ok = state == Newton::converged};
  }
  return {.ok = false};
}

// One Newton iteration on G(y1) = y1 − y − Δt f(t1, y1) (eqs. 2.35–2.36) with the linear system
// (I − Δt J) δ = −G solved matrix-free by GMRES.
JacobianFreeBackwardEuler::Newton JacobianFreeBackwardEuler::newton_iteration(const ode::OdeSystem& system, double t1,
                                                                             double dt, const ode::Vector& y,
                                                                             ode::Vector& y1, int iteration) {
  system.derivative(t1, y1, f1_);
  residual_ = y1 - y - dt * f1_;
  // Always correct the predictor once (as ode::BackwardEuler): an explicit Euler step that happens
  // to lie within tolerance is not the implicit solution.
  if (iteration > 0 && converged(residual_, y, y1)) return Newton::converged;
  rhs_ = -residual_;
  delta_.setZero(y1.size());
  const LinearOperator op = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    apply_iteration_matrix(system, t1, dt, y1, v, out);
  };
  const GmresReport report =
      gmres(op, rhs_, delta_, settings_.gmres_tolerance, settings_.max_gmres_iterations, settings_.gmres_restart);
  last_gmres_ += report.iterations;
  if (!delta_.allFinite()) return Newton::failed;
  y1 += delta_;
  last_newton_ = iteration + 1;
  return converged(delta_, y, y1) ? Newton::converged : Newton::iterate;
}

void JacobianFreeBackwardEuler::apply_iteration_matrix(const ode::OdeSystem& system, double t1, double dt,
                                                       const ode::Vector& y1, const ode::Vector& v, ode::Vector& out) {
  const double v_norm = v.norm();
  if (v_norm == 0.0) {
    out.setZero(v.size());
    return;
  }
  const double eps = std::sqrt(std::numeric_limits<double>::epsilon()) * (1.0 + y1.norm()) / v_norm;
  shifted_ = y1 + eps * v;
  system.derivative(t1, shifted_, f_shifted_);
  out = v - (dt / eps) * (f_shifted_ - f1_);  // (I − Δt J) v
}

bool JacobianFreeBackwardEuler::converged(const ode::Vector& v, const ode::Vector& y, const ode::Vector& y1) const {
  return ode::error_norm(v, y, y1, settings_.atol, settings_.rtol) <= 1.0;
}

std::unique_ptr<Integrator> make_jacobian_free_integrator(std::string_view name, const NewtonKrylovSettings& newton) {
  if (name == "backward-euler") return std::make_unique<JacobianFreeBackwardEuler>(newton);
  return make_integrator(name);
}

}  // namespace jellysim::ode
