#include "jellysim/ode/leapfrog.hpp"

#include <stdexcept>

namespace jellysim::ode {

namespace {

Eigen::Index require_second_order(const OdeSystem& system) {
  const Eigen::Index m = system.position_size();
  if (m <= 0 || system.dimension() != 2 * m) {
    throw std::invalid_argument(
        "leapfrog needs a second-order system y = [q; v] (position_size() > 0 and dimension() == "
        "2 * position_size())");
  }
  return m;
}

}  // namespace

StepOutcome Leapfrog::step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                           Vector* /*error: no embedded pair*/) {
  const Eigen::Index m = require_second_order(system);
  start_.evaluate(system, t, y, f_);
  y_out = y;
  y_out.tail(m) += (0.5 * dt) * f_.tail(m);  // kick: v_{1/2}
  y_out.head(m) += dt * y_out.tail(m);       // drift: q1 = q + dt v_{1/2} (eq. 2.32)
  system.derivative(t + dt, y_out, f_);      // a(q1, v_{1/2})
  y_out.tail(m) += (0.5 * dt) * f_.tail(m);  // kick: v1
  return {};
}

}  // namespace jellysim::ode
