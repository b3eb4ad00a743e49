#pragma once
// Backward Euler without a Jacobian, for systems that have none (first user: the particle-fluid scenes) (thesis eq. 2.33, Newton's method
// eq. 2.36): a Jacobian-free Newton–Krylov solve. The SPH forces have no analytic Jacobian, so each
// Newton system (I − Δt J) δ = −G is solved by restarted GMRES, with the products J v taken as
// finite-difference directional derivatives of the right-hand side (Knoll & Keyes 2004):
//   J v ≈ (f(t1, y1 + ε v) − f(t1, y1)) / ε,   ε = √u (1 + ‖y1‖) / ‖v‖,  u = machine epsilon.
// Every product costs one evaluation of f (counted by OdeSystem::evaluations()). The method has no
// embedded pair, so the adaptive controller uses step doubling.
#include "jellysim/ode/derivative_cache.hpp"
#include "jellysim/ode/integrator.hpp"

#include <memory>
#include <string_view>

namespace jellysim::ode {

struct NewtonKrylovSettings {
  /// Newton has converged when the scaled RMS norm (as ode::error_norm, each component divided by
  /// atol + rtol max(|y_i|, |y1_i|)) of the residual G or of the correction δ is <= 1.
  double atol = 1e-7;
  double rtol = 1e-7;
  int max_newton_iterations = 12;
  double gmres_tolerance = 1e-4;  ///< ‖b − A x‖ <= tolerance ‖b‖ for each Newton system
  int max_gmres_iterations = 300;
  int gmres_restart = 40;
};

/// Throws std::invalid_argument naming the setting when one is out of range.
void validate(const NewtonKrylovSettings& s);

class JacobianFreeBackwardEuler final : public ode::Integrator {
 public:
  explicit JacobianFreeBackwardEuler(NewtonKrylovSettings settings = {});

  std::string_view name() const override { return "backward-euler"; }
  int order() const override { return 1; }
  /// Solves G(y1) = y1 − y − Δt f(t + Δt, y1) = 0 (eq. 2.33) from the explicit Euler predictor,
  /// applying at least one Newton correction. ok = false when Newton does not converge within
  /// max_newton_iterations or a correction is not finite (the controller then shrinks the step).
  ode::StepOutcome step(const ode::OdeSystem& system, double t, double dt, const ode::Vector& y, ode::Vector& y_out,
                        ode::Vector* error) override;
  void reset() override { start_.clear(); }

  /// Newton corrections and GMRES operator applications of the last step.
  int last_newton_iterations() const { return last_newton_; }
  int last_gmres_iterations() const { return last_gmres_; }

 private:
  enum class Newton { iterate, converged, failed };
  Newton newton_iteration(const ode::OdeSystem& system, double t1, double dt, const ode::Vector& y, ode::Vector& y1,
                          int iteration);
  bool converged(const ode::Vector& v, const ode::Vector& y, const ode::Vector& y1) const;
  /// out = (I − Δt J(y1)) v with J v by a finite difference around (t1, y1), f1 = f(t1, y1).
  void apply_iteration_matrix(const ode::OdeSystem& system, double t1, double dt, const ode::Vector& y1,
                              const ode::Vector& v, ode::Vector& out);

  NewtonKrylovSettings settings_;
  ode::DerivativeCache start_;  ///< f(t, y): shared by the full step and the first half step
  ode::Vector f_, f1_, residual_, delta_, rhs_, shifted_, f_shifted_;
  int last_newton_ = 0, last_gmres_ = 0;
};

/// The integrator for a system without a Jacobian (a particle-fluid scene): every name of
/// integrator_names(); backward Euler is the Jacobian-free version above. Throws
/// std::invalid_argument for an unknown name.
std::unique_ptr<Integrator> make_jacobian_free_integrator(std::string_view name, const NewtonKrylovSettings& newton = {});

}  // namespace jellysim::ode
