#include "jellysim/ode/backward_euler.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace jellysim::ode {

BackwardEuler::BackwardEuler(NewtonSettings settings) : settings_(settings) {
  if (settings_.max_iterations < 1) throw std::invalid_argument("backward-euler: max_iterations must be >= 1");
}

StepOutcome BackwardEuler::step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                                Vector* /*error: no embedded pair*/) {
  if (!system.has_jacobian()) throw std::invalid_argument("backward-euler needs a system with an analytic Jacobian");
  start_.evaluate(system, t, y, f_);
  y_out = y + dt * f_;  // explicit Euler predictor (eq. 2.22)
  for (int iteration = 0; iteration < settings_.max_iterations; ++iteration) {
    const Newton state = newton_iteration(system, t + dt, dt, y, y_out, iteration);
    if (state != Newton::iterate) return {.ok = state == Newton::converged};
  }
  return {.ok = false};
}

BackwardEuler::Newton BackwardEuler::newton_iteration(const OdeSystem& system, double t1, double dt, const Vector& y,
                                                      Vector& y1, int iteration) {
  system.derivative(t1, y1, f_);
  residual_ = y1 - y - dt * f_;  // G(y1), eq. 2.35 with g(y1) = y + dt f(t1, y1)
  // Always correct the predictor once: accepting an unstable explicit Euler step whenever it lies
  // within tolerance would let a stiff decay stall at the atol level.
  if (iteration > 0 && converged(residual_, y, y1)) {
    last_iterations_ = iteration;
    return Newton::converged;
  }
  const bool refresh = iteration == 0 || !settings_.simplified;
  if (refresh && !factorize(system, t1, dt, y1)) return Newton::failed;
  delta_ = solver_.solve(-residual_);  // eq. 2.36: (I - dt J) Δ = -G
  y1 += delta_;
  if (!delta_.allFinite()) return Newton::failed;
  last_iterations_ = iteration + 1;
  return converged(delta_, y, y1) ? Newton::converged : Newton::iterate;
}

bool BackwardEuler::converged(const Vector& v, const Vector& y, const Vector& y1) const {
  return error_norm(v, y, y1, settings_.atol, settings_.rtol) <= 1.0;
}

bool BackwardEuler::factorize(const OdeSystem& system, double t1, double dt, const Vector& y1) {
  const Eigen::Index n = y1.size();
  system.jacobian(t1, y1, jacobian_);
  if (jacobian_.rows() != n || jacobian_.cols() != n) {
    throw std::invalid_argument("backward-euler: the Jacobian must be " + std::to_string(n) + " x " +
                                std::to_string(n));
  }
  if (identity_.rows() != n) {
    identity_.resize(n, n);
    identity_.setIdentity();
  }
  iteration_matrix_ = identity_ - dt * jacobian_;  // dG/dy1
  iteration_matrix_.makeCompressed();
  analyse_pattern_if_changed();
  solver_.factorize(iteration_matrix_);
  return solver_.info() == Eigen::Success;
}

void BackwardEuler::analyse_pattern_if_changed() {
  const SparseMatrix& m = iteration_matrix_;
  const auto* outer = m.outerIndexPtr();
  const auto* inner = m.innerIndexPtr();
  const auto outer_size = static_cast<std::size_t>(m.outerSize()) + 1;
  const auto nonzeros = static_cast<std::size_t>(m.nonZeros());
  const bool same = pattern_outer_.size() == outer_size && pattern_inner_.size() == nonzeros &&
                    std::equal(outer, outer + outer_size, pattern_outer_.begin()) &&
                    std::equal(inner, inner + nonzeros, pattern_inner_.begin());
  if (same) return;
  solver_.analyzePattern(m);
  ++pattern_analyses_;
  pattern_outer_.assign(outer, outer + outer_size);
  pattern_inner_.assign(inner, inner + nonzeros);
}

}  // namespace jellysim::ode
