#include "semi_lagrangian_solver.hpp"

#include <limits>
#include <stdexcept>

#include "jellysim/fluid/semi_lagrangian.hpp"

namespace jellysim::fluid {

SemiLagrangianSolver::SemiLagrangianSolver(const MacGrid& grid, const FluidSettings& settings)
    : FluidSolver(grid, settings), advected_(grid), diffusion_(grid) {}

double SemiLagrangianSolver::stable_time_step() const { return std::numeric_limits<double>::infinity(); }

StepReport SemiLagrangianSolver::step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("time step must be positive");
  const Boundaries& b = settings_.boundaries;
  StepReport report;
  report.dt_s = dt_s;
  Velocity& vel = state_.velocity;
  apply_velocity_boundaries(vel, b);
  add_body_accelerations(vel, dt_s);                                          // step 1
  report.diffusion_iterations = diffusion_.solve(                              // step 2, eq. 4.17
      vel, b, settings_.viscosity_m2_per_s * dt_s, settings_.diffusion_tolerance);
  apply_velocity_boundaries(vel, b);
  if (settings_.project_before_advection) {                                   // §4.2.4 remark
    // Two projections of different fields per step: no extrapolation across them.
    projector_.reset_history();
    project(dt_s);
    projector_.reset_history();
  }
  // advect_velocity writes every interior face of advected_ and then all boundary values and
  // ghosts, so advected_ needs no copy of vel first.
  advect_velocity(vel, b, dt_s, advected_);                                   // step 3
  std::swap(vel, advected_);
  report.pressure = project(dt_s);                                            // step 4, eq. 4.14
  time_s_ += dt_s;
  return report;
}

}  // namespace jellysim::fluid
