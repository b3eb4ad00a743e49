#pragma once
// Stam's semi-Lagrangian method, thesis §4.2.4: forces, implicit diffusion (eq. 4.17), optional
// projection, back-traced advection, projection (eq. 4.14). Unconditionally stable.
// With the other advection schemes (MacCormack, BFECC, monotone cubic) the step is second order
// in time (issue 20): Crank–Nicolson along the trajectories, the pressure gradient split between
// the departure and the arrival point, and the trajectories traced in the velocity extrapolated
// to the middle of the step (docs/fluids.md).
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/semi_lagrangian.hpp"

namespace jellysim::fluid {

class SemiLagrangianSolver final : public FluidSolver {
 public:
  SemiLagrangianSolver(const MacGrid& grid, const FluidSettings& settings);
  std::string_view name() const override { return "semi-lagrangian"; }
  StepReport step(double dt_s) override;
  double stable_time_step() const override;
  void archive(core::StateArchive& a) override;

 private:
  StepReport second_order_step(double dt_s);
  /// True when the velocity and pressure are exactly what the last step left (nobody edited them
  /// in between), so that the history may be extrapolated.
  bool history_continues() const;

  Velocity advected_;
  ImplicitDiffusion diffusion_;
  CompensatedAdvection compensated_;
  // History of the second-order step: the velocity at the start and at the end of the last step,
  // the last pressure, the last step's Δt.
  /// u −= ½Δt∇p̃/ρ on the interior faces (p̃ = last_pressure_), boundaries re-applied.
  void subtract_half_pressure_gradient(Velocity& vel, double dt_s) const;

  Velocity carrier_, last_start_, last_end_;
  // The last pressure (p̃ during a step) and the projection's last increment ρφ.
  Field last_pressure_, increment_;
  double last_dt_s_ = 0.0;
  bool has_history_ = false;
};

}  // namespace jellysim::fluid
