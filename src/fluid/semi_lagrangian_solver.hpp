#pragma once
// Stam's semi-Lagrangian method, thesis §4.2.4: forces, implicit diffusion (eq. 4.17), optional
// projection, back-traced advection, projection (eq. 4.14). Unconditionally stable.
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/semi_lagrangian.hpp"

namespace jellysim::fluid {

class SemiLagrangianSolver final : public FluidSolver {
 public:
  SemiLagrangianSolver(const MacGrid& grid, const FluidSettings& settings);
  std::string_view name() const override { return "semi-lagrangian"; }
  StepReport step(double dt_s) override;
  double stable_time_step() const override;

 private:
  Velocity advected_;
  ImplicitDiffusion diffusion_;
};

}  // namespace jellysim::fluid
