#pragma once
// One generic explicit Runge–Kutta stepper driven by a Butcher tableau (thesis eqs. 2.37-2.40),
// with the embedded error estimate y - y_hat when the tableau has one and FSAL reuse of the last
// stage.
#include <vector>

#include "jellysim/ode/butcher_tableau.hpp"
#include "jellysim/ode/derivative_cache.hpp"
#include "jellysim/ode/integrator.hpp"

namespace jellysim::ode {

class ExplicitRungeKutta final : public Integrator {
 public:
  /// Validates the tableau (throws std::invalid_argument when malformed).
  explicit ExplicitRungeKutta(ButcherTableau tableau);

  std::string_view name() const override { return tableau_.name; }
  int order() const override { return tableau_.order; }
  int embedded_order() const override { return tableau_.embedded_order; }
  const ButcherTableau& tableau() const { return tableau_; }

  /// With an FSAL tableau, the next step reuses the last stage when it starts from exactly the
  /// (t + dt, y_out) of this one (advance t by `t += dt` to hit it).
  StepOutcome step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                   Vector* error) override;
  void reset() override;

 private:
  void first_stage(const OdeSystem& system, double t, const Vector& y);

  ButcherTableau tableau_;
  std::vector<double> error_weights_;  ///< b - b_hat: the error estimate is dt Σ (b_i - b_hat_i) k_i
  std::vector<Vector> k_;
  Vector stage_y_;
  DerivativeCache start_;  ///< f at the start of the last step (shared by step-doubling attempts)
  DerivativeCache end_;    ///< FSAL: f at the end of the last step
};

}  // namespace jellysim::ode
