#include "jellysim/ode/explicit_runge_kutta.hpp"

#include "jellysim/ode/stage_sum.hpp"

#include <utility>

namespace jellysim::ode {

ExplicitRungeKutta::ExplicitRungeKutta(ButcherTableau tableau) : tableau_(std::move(tableau)) {
  validate(tableau_);
  for (std::size_t i = 0; i < tableau_.b_hat.size(); ++i) error_weights_.push_back(tableau_.b[i] - tableau_.b_hat[i]);
  k_.resize(tableau_.stages());
}

StepOutcome ExplicitRungeKutta::step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                                     Vector* error) {
  first_stage(system, t, y);
  const std::size_t stages = tableau_.stages();
  const std::size_t computed_here = tableau_.fsal ? stages - 1 : stages;
  for (std::size_t i = 1; i < computed_here; ++i)
    system.stage_derivative(t + tableau_.c[i] * dt, y, dt, tableau_.a[i], k_, stage_y_, k_[i]);
  if (tableau_.fsal) {  // last row of A equals b, so the last stage is evaluated at y_out itself
    system.stage_derivative(t + dt, y, dt, tableau_.b, k_, y_out, k_[stages - 1]);
  } else {
    form_stage_state(y, dt, tableau_.b, k_, y_out);
  }
  StepOutcome outcome;
  if (error != nullptr && has_embedded_pair()) {
    form_weighted_sum(dt, error_weights_, k_, *error);
    outcome.has_error = true;
  }
  // The last stage moves into the cache (k_ is scratch from here on) rather than being copied.
  if (tableau_.fsal) end_.store_by_swap(system, t + dt, y_out, k_[stages - 1]);
  return outcome;
}

void ExplicitRungeKutta::reset() {
  start_.clear();
  end_.clear();
}

void ExplicitRungeKutta::first_stage(const OdeSystem& system, double t, const Vector& y) {
  for (Vector& k : k_) k.resize(y.size());  // a swap with the caches may have left one empty
  if (end_.take(system, t, y, k_[0])) {
    start_.store(system, t, y, k_[0]);  // a rejected attempt is retried from here
  } else {
    start_.evaluate(system, t, y, k_[0]);
  }
}

}  // namespace jellysim::ode
