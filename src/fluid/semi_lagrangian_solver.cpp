#include "semi_lagrangian_solver.hpp"

#include <algorithm>
#include <limits>
#include <span>
#include <stdexcept>

#include "jellysim/core/state_archive.hpp"
#include "jellysim/fluid/semi_lagrangian.hpp"

namespace jellysim::fluid {

SemiLagrangianSolver::SemiLagrangianSolver(const MacGrid& grid, const FluidSettings& settings)
    : FluidSolver(grid, settings), advected_(grid), diffusion_(grid, settings.geometry), compensated_(grid) {}

void SemiLagrangianSolver::archive(core::StateArchive& a) {
  FluidSolver::archive(a);
  const core::StateArchive::Scope scope(a, "semi_lagrangian");
  a.value("has_history", has_history_);
  a.value("last_dt", last_dt_s_);
  if (!has_history_) return;
  // The second-order step's history (allocated by the first step; a restored solver has not taken one).
  const MacGrid& g = state_.grid;
  if (last_start_.u.count_x() == 0) last_start_ = last_end_ = Velocity(g);
  if (last_pressure_.count_x() == 0) last_pressure_ = increment_ = Field(g, kCellCentres);
  fluid::archive(a, "last_start", last_start_);
  fluid::archive(a, "last_end", last_end_);
  fluid::archive(a, "last_pressure", last_pressure_);
  fluid::archive(a, "increment", increment_);
}

double SemiLagrangianSolver::stable_time_step() const { return std::numeric_limits<double>::infinity(); }

StepReport SemiLagrangianSolver::step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("time step must be positive");
  if (settings_.advection != AdvectionScheme::linear) return second_order_step(dt_s);
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

namespace {

bool same_samples(const Field& a, const Field& b) {
  return std::ranges::equal(a.raw(), b.raw());
}

// out = a + (a − b)·ratio on every stored sample (ghosts included).
void extrapolate(const Field& a, const Field& b, double ratio, Field& out) {
  const std::span<const double> x = a.raw(), y = b.raw();
  const std::span<double> o = out.raw();
  for (std::size_t k = 0; k < o.size(); ++k) o[k] = x[k] + (x[k] - y[k]) * ratio;
}

}  // namespace

bool SemiLagrangianSolver::history_continues() const {
  return has_history_ && same_samples(state_.velocity.u, last_end_.u) &&
         same_samples(state_.velocity.v, last_end_.v) && same_samples(state_.pressure, last_pressure_);
}

// The two-time-level semi-Lagrangian scheme with Crank–Nicolson along the trajectories (e.g.
// Staniforth & Côté 1991, Mon. Wea. Rev. 119; Xiu & Karniadakis 2001, J. Comput. Phys. 172) and
// an incremental pressure: from the departure point x_d to the arrival point x,
//   u*(x) = A[u + ½νΔt∇²u + Δt·a − ½Δt∇p̃/ρ](x_d) − ½Δt∇p̃/ρ,  (I − ½νΔt∇²) u** = u*,
//   u = u** − Δt∇φ (projection),  p = p̃ + ρφ,
// with p̃ the last pressure, so the pressure gradient acts half at each end of the trajectory
// (the trapezoidal rule) and the projection only corrects p̃; p̃ lags by Δt, which changes the
// step by O(Δt³). (Extrapolating p̃ to t + ½Δt is unstable: the error of p̃ then feeds back through
// the difference of the gradient at both ends, with growth factors above 1 at Courant numbers
// near 1; measured in the driven cavity, documented in docs/fluids.md.) The trajectories are
// traced in the velocity extrapolated to t + ½Δt, except on the first step and after an edit of
// the flow between steps.
StepReport SemiLagrangianSolver::second_order_step(double dt_s) {
  const Boundaries& b = settings_.boundaries;
  const MacGrid& g = state_.grid;
  StepReport report;
  report.dt_s = dt_s;
  Velocity& vel = state_.velocity;
  apply_velocity_boundaries(vel, b);
  const bool continues = history_continues();
  if (!continues) {  // the coupled jellyfish edits the flow every step: no allocation here
    if (increment_.count_x() != g.nx) increment_ = Field(g, kCellCentres);
    else increment_.fill(0.0);
  }
  // Carrier u(t + ½Δt) ≈ u + (u − u_last_start)·½Δt/Δt_last.
  if (continues) {
    const double ratio = 0.5 * dt_s / last_dt_s_;
    extrapolate(vel.u, last_start_.u, ratio, carrier_.u);
    extrapolate(vel.v, last_start_.v, ratio, carrier_.v);
    apply_velocity_boundaries(carrier_, b);
  } else {
    carrier_ = vel;
  }
  last_start_ = vel;
  std::swap(last_pressure_, state_.pressure);  // p̃ (the state's pressure is rewritten below)
  // Departure-side terms: the explicit half of the diffusion, forces, half the pressure gradient
  // (forces after the diffusion, so that a force balanced by the pressure, such as gravity at
  // rest, cancels exactly).
  const double half_nu_dt = 0.5 * settings_.viscosity_m2_per_s * dt_s;
  diffusion_.apply_explicit(vel, b, half_nu_dt);
  add_body_accelerations(vel, dt_s);
  subtract_half_pressure_gradient(vel, dt_s);
  compensated_.advect(settings_.advection, carrier_, vel, b, dt_s, advected_);
  std::swap(vel, advected_);
  subtract_half_pressure_gradient(vel, dt_s);  // the arrival half
  report.diffusion_iterations = diffusion_.solve(vel, b, half_nu_dt, settings_.diffusion_tolerance);
  // The projection sees its own last result as the pressure (its initial guess extrapolates the
  // increments), then p = p̃ + ρφ.
  state_.pressure = increment_;
  report.pressure = project(dt_s);
  increment_ = state_.pressure;
  {
    const std::span<const double> p_tilde = last_pressure_.raw();
    const std::span<double> p = state_.pressure.raw();
    for (std::size_t k = 0; k < p.size(); ++k) p[k] += p_tilde[k];
  }
  time_s_ += dt_s;
  last_end_ = vel;
  last_pressure_ = state_.pressure;
  last_dt_s_ = dt_s;
  has_history_ = true;
  return report;
}

void SemiLagrangianSolver::subtract_half_pressure_gradient(Velocity& vel, double dt_s) const {
  const MacGrid& g = state_.grid;
  const Boundaries& b = settings_.boundaries;
  const Field& p = last_pressure_;
  const double cx = 0.5 * dt_s / (settings_.density_kg_per_m3 * g.dx());
  const double cy = 0.5 * dt_s / (settings_.density_kg_per_m3 * g.dy());
  const FaceRange ru = interior_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i) vel.u(i, j) -= cx * (p(i, j) - p(i - 1, j));
  const FaceRange rv = interior_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i) vel.v(i, j) -= cy * (p(i, j) - p(i, j - 1));
  apply_velocity_boundaries(vel, b);
}

}  // namespace jellysim::fluid
