// Adaptive step-size control (thesis §2.4.6): embedded pair where the method has one, step doubling
// otherwise; the standard controller of Hairer, Nørsett & Wanner, Solving ODEs I, §II.4.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "jellysim/ode/integrator.hpp"

namespace jellysim::ode {

double error_norm(const Vector& error, const Vector& y, const Vector& y_new, double atol, double rtol) {
  if (error.size() == 0) return 0.0;
  const Eigen::ArrayXd scale = atol + rtol * y.array().abs().max(y_new.array().abs());
  return std::sqrt((error.array() / scale).square().mean());
}

namespace {

void validate(const AdaptiveSettings& s) {
  const bool ok = s.atol >= 0.0 && s.rtol >= 0.0 && s.atol + s.rtol > 0.0 && s.safety > 0.0 && s.safety <= 1.0 &&
                  s.min_factor > 0.0 && s.min_factor <= 1.0 && s.max_factor >= 1.0 && s.dt_min > 0.0 &&
                  s.dt_max >= s.dt_min;
  if (!ok) {
    throw std::invalid_argument(
        "adaptive settings need atol, rtol >= 0 (not both 0), 0 < safety <= 1, 0 < min_factor <= 1 <= max_factor "
        "and 0 < dt_min <= dt_max");
  }
}

constexpr double kFailed = std::numeric_limits<double>::infinity();

}  // namespace

AdaptiveStepper::AdaptiveStepper(Integrator& integrator, AdaptiveSettings settings)
    : integrator_(integrator), settings_(settings) {
  validate(settings_);
}

double AdaptiveStepper::step(const OdeSystem& system, double& t, Vector& y, double dt_try, double dt_limit,
                             double& dt_taken) {
  if (!(dt_limit > 0.0)) throw std::invalid_argument("AdaptiveStepper::step: dt_limit must be positive");
  dt_try = std::min(dt_try, settings_.dt_max);
  while (true) {
    if (!(dt_try >= settings_.dt_min)) throw_underflow(t, dt_try);
    const double dt = std::min(dt_try, dt_limit);
    const double err = attempt(system, t, y, dt);
    const double factor = step_factor(err);
    if (err <= 1.0) return accept(t, y, dt, dt_try, factor, dt_taken);
    ++stats_.rejected;
    dt_try = dt * std::min(factor, 1.0);  // a rejected step never grows
  }
}

double AdaptiveStepper::attempt(const OdeSystem& system, double t, const Vector& y, double dt) {
  return uses_step_doubling() ? attempt_step_doubling(system, t, y, dt) : attempt_embedded(system, t, y, dt);
}

double AdaptiveStepper::attempt_embedded(const OdeSystem& system, double t, const Vector& y, double dt) {
  const StepOutcome outcome = integrator_.step(system, t, dt, y, y_new_, &error_);
  if (!outcome.ok) return kFailed;
  if (!outcome.has_error) throw std::logic_error("integrator with an embedded pair returned no error estimate");
  return error_norm(error_, y, y_new_, settings_.atol, settings_.rtol);
}

double AdaptiveStepper::attempt_step_doubling(const OdeSystem& system, double t, const Vector& y, double dt) {
  const double half = 0.5 * dt;
  const bool ok = integrator_.step(system, t, dt, y, y_full_, nullptr).ok &&
                  integrator_.step(system, t, half, y, y_half_, nullptr).ok &&
                  integrator_.step(system, t + half, half, y_half_, y_new_, nullptr).ok;
  if (!ok) return kFailed;
  // Richardson: y_full - y ≈ C dt^(p+1), y_new - y ≈ C dt^(p+1) / 2^p, so the error of y_new is
  // (y_new - y_full) / (2^p - 1).
  error_ = (y_new_ - y_full_) / (std::pow(2.0, integrator_.order()) - 1.0);
  return error_norm(error_, y, y_new_, settings_.atol, settings_.rtol);
}

double AdaptiveStepper::step_factor(double err) const {
  if (!std::isfinite(err)) return settings_.min_factor;
  const int q =
      uses_step_doubling() ? integrator_.order() : std::min(integrator_.order(), integrator_.embedded_order());
  const double optimal = settings_.safety * std::pow(err, -1.0 / (q + 1));  // +inf when err == 0
  return std::clamp(optimal, settings_.min_factor, settings_.max_factor);
}

double AdaptiveStepper::accept(double& t, Vector& y, double dt, double dt_try, double factor, double& dt_taken) {
  ++stats_.accepted;
  t += dt;
  y.swap(y_new_);  // no copy: the entries stay where the last stage wrote them
  dt_taken = dt;
  const double suggested = dt * factor;
  // A step cut short by dt_limit says nothing against the longer dt_try unless it asks to shrink.
  const bool limited = dt < dt_try;
  const double next = limited && factor >= 1.0 ? std::max(suggested, dt_try) : suggested;
  return std::min(next, settings_.dt_max);
}

void AdaptiveStepper::throw_underflow(double t, double dt) const {
  std::ostringstream message;
  message.precision(10);
  message << "adaptive step size underflow at t = " << t << ": dt = " << dt << " < dt_min = " << settings_.dt_min
          << " (" << integrator_.name() << ")";
  throw StepSizeUnderflow(message.str());
}

}  // namespace jellysim::ode
