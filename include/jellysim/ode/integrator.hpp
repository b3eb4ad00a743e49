#pragma once
// Time integrators for y' = f(t, y) (thesis §2.4) behind one interface, a by-name registry, and an
// adaptive step-size controller (§2.4.6) that uses an embedded pair where the method has one and
// step doubling otherwise.
#include "jellysim/ode/ode_system.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace jellysim::ode {

/// Outcome of one attempted step.
struct StepOutcome {
  bool ok = true;            ///< false: the step could not be taken (e.g. Newton did not converge)
  bool has_error = false;    ///< true: `error` holds a local error estimate (y_high - y_low)
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Registry name, e.g. "forward-euler", "dopri5".
  virtual std::string_view name() const = 0;
  /// Global order of accuracy of the propagated solution.
  virtual int order() const = 0;
  /// Order of the embedded lower-order solution, or 0 without an embedded pair.
  virtual int embedded_order() const { return 0; }
  bool has_embedded_pair() const { return embedded_order() > 0; }

  /// Advances y from t by dt into y_out. When the method has an embedded pair and `error` is
  /// non-null, writes the embedded local error estimate into *error and sets has_error.
  virtual StepOutcome step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                           Vector* error) = 0;

  /// Forget cached data (e.g. first-same-as-last stages) after the state was changed externally.
  virtual void reset() {}
};

/// Names accepted by make_integrator, in presentation order:
/// forward-euler, predictor-corrector, leapfrog, rk2, rk4, dopri5, backward-euler.
const std::vector<std::string>& integrator_names();
/// Creates an integrator by name; throws std::invalid_argument naming the allowed values.
std::unique_ptr<Integrator> make_integrator(std::string_view name);

/// Settings of the adaptive controller. Error norm: RMS over components of
/// err_i / (atol + rtol * max(|y_i|, |y_new_i|)); a step is accepted when the norm <= 1.
struct AdaptiveSettings {
  double atol = 1e-6;
  double rtol = 1e-6;
  double safety = 0.9;       ///< safety factor on the optimal step
  double min_factor = 0.2;   ///< smallest shrink per attempt
  double max_factor = 5.0;   ///< largest growth per step
  double dt_min = 1e-12;     ///< below this the controller gives up (throws StepSizeUnderflow)
  double dt_max = 1e300;
};

struct StepStatistics {
  std::int64_t accepted = 0;
  std::int64_t rejected = 0;
};

/// Thrown when the adaptive controller needs a step smaller than dt_min.
struct StepSizeUnderflow : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Adaptive step control around any integrator. Without an embedded pair it uses step doubling:
/// one step of dt against two of dt/2; the two half steps are kept (local extrapolation is not used).
class AdaptiveStepper {
 public:
  AdaptiveStepper(Integrator& integrator, AdaptiveSettings settings);

  /// Takes one accepted step from (t, y), trying first with `dt_try` (not exceeding `dt_limit`),
  /// shrinking on rejection. On return t and y are advanced, and the function returns the step
  /// suggested for the next call. `dt_taken` receives the accepted step size.
  /// A step shortened by `dt_limit` (e.g. to land on an output frame) does not shrink the
  /// suggestion below `dt_try` unless its own error asks for a smaller step. A failed attempt
  /// (StepOutcome::ok == false) or a non-finite error counts as a rejection and shrinks by
  /// min_factor. Throws StepSizeUnderflow when the step wanted falls below dt_min, and
  /// std::invalid_argument when dt_limit <= 0.
  double step(const OdeSystem& system, double& t, Vector& y, double dt_try, double dt_limit, double& dt_taken);

  const StepStatistics& statistics() const { return stats_; }
  bool uses_step_doubling() const { return !integrator_.has_embedded_pair(); }

 private:
  /// Error norm of one attempt from (t, y) with step dt (result in y_new_); +inf when the step failed.
  double attempt(const OdeSystem& system, double t, const Vector& y, double dt);
  double attempt_embedded(const OdeSystem& system, double t, const Vector& y, double dt);
  double attempt_step_doubling(const OdeSystem& system, double t, const Vector& y, double dt);
  /// Controller factor clamp(safety * err^(-1/(q+1)), min_factor, max_factor); min_factor when err
  /// is not finite.
  double step_factor(double err) const;
  double accept(double& t, Vector& y, double dt, double dt_try, double factor, double& dt_taken);
  [[noreturn]] void throw_underflow(double t, double dt) const;

  Integrator& integrator_;
  AdaptiveSettings settings_;
  StepStatistics stats_;
  Vector y_new_, y_half_, y_full_, error_;
};

/// Weighted RMS error norm used by the controller (exposed for tests).
double error_norm(const Vector& error, const Vector& y, const Vector& y_new, double atol, double rtol);

}  // namespace jellysim::ode
