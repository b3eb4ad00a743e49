#pragma once
// Leap-frog (thesis eqs. 2.31-2.32) for second-order systems y = [q; v], q' = v, in its synchronised
// kick-drift-kick form.
#include "jellysim/ode/derivative_cache.hpp"
#include "jellysim/ode/integrator.hpp"

namespace jellysim::ode {

/// v_{1/2} = v + dt/2 a(t, q, v);  q1 = q + dt v_{1/2};  v1 = v_{1/2} + dt/2 a(t + dt, q1, v_{1/2}).
/// Merging the closing kick of one step with the opening kick of the next gives the staggered
/// eqs. 2.31-2.32: v_{n+1/2} = v_{n-1/2} + dt a(q_n), q_{n+1} = q_n + dt v_{n+1/2}.
/// Second order and symplectic for position-only forces. With velocity-dependent forces (drag)
/// the closing kick uses v_{1/2} in place of the unknown v1, which keeps the method explicit but
/// lowers it to first order. Two evaluations per step.
class Leapfrog final : public Integrator {
 public:
  std::string_view name() const override { return "leapfrog"; }
  int order() const override { return 2; }
  /// Throws std::invalid_argument unless system.position_size() > 0 and dimension() equals twice it.
  StepOutcome step(const OdeSystem& system, double t, double dt, const Vector& y, Vector& y_out,
                   Vector* error) override;
  void reset() override { start_.clear(); }

 private:
  DerivativeCache start_;  ///< f at the start of the last step (shared by step-doubling attempts)
  Vector f_;
};

}  // namespace jellysim::ode
