#include "jellysim/fluid/eulerian_solver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace jellysim::fluid {

double face_laplacian(const Field& f, int i, int j) {
  const MacGrid& g = f.grid();
  const double c = f(i, j);
  return (f(i + 1, j) - 2.0 * c + f(i - 1, j)) / (g.dx() * g.dx()) +
         (f(i, j + 1) - 2.0 * c + f(i, j - 1)) / (g.dy() * g.dy());
}

namespace {

// Flux of a quantity q through a face moving with velocity `carrier` (already averaged to the
// face), blending central and donor-cell values: carrier·(q₋ + q₊)/2 + γ|carrier|(q₋ − q₊)/2.
inline double blended_flux(double carrier, double q_minus, double q_plus, double gamma) {
  return carrier * 0.5 * (q_minus + q_plus) + gamma * std::abs(carrier) * 0.5 * (q_minus - q_plus);
}

}  // namespace

double convection_u(const Velocity& vel, int i, int j, double gamma) {
  const Field& u = vel.u;
  const Field& v = vel.v;
  const MacGrid& g = u.grid();
  const double east = blended_flux(0.5 * (u(i, j) + u(i + 1, j)), u(i, j), u(i + 1, j), gamma);
  const double west = blended_flux(0.5 * (u(i - 1, j) + u(i, j)), u(i - 1, j), u(i, j), gamma);
  const double north = blended_flux(0.5 * (v(i - 1, j + 1) + v(i, j + 1)), u(i, j), u(i, j + 1), gamma);
  const double south = blended_flux(0.5 * (v(i - 1, j) + v(i, j)), u(i, j - 1), u(i, j), gamma);
  return (east - west) / g.dx() + (north - south) / g.dy();
}

double convection_v(const Velocity& vel, int i, int j, double gamma) {
  const Field& u = vel.u;
  const Field& v = vel.v;
  const MacGrid& g = u.grid();
  const double east = blended_flux(0.5 * (u(i + 1, j - 1) + u(i + 1, j)), v(i, j), v(i + 1, j), gamma);
  const double west = blended_flux(0.5 * (u(i, j - 1) + u(i, j)), v(i - 1, j), v(i, j), gamma);
  const double north = blended_flux(0.5 * (v(i, j) + v(i, j + 1)), v(i, j), v(i, j + 1), gamma);
  const double south = blended_flux(0.5 * (v(i, j - 1) + v(i, j)), v(i, j - 1), v(i, j), gamma);
  return (east - west) / g.dx() + (north - south) / g.dy();
}

EulerianSolver::EulerianSolver(const MacGrid& grid, const FluidSettings& settings)
    : FluidSolver(grid, settings), predictor_(grid) {}

double EulerianSolver::stable_time_step() const {
  return stability_time_step(state_.velocity, settings_.viscosity_m2_per_s, settings_.safety_factor,
                             &settings_.boundaries);
}

double EulerianSolver::donor_cell_blend(double dt_s) const {
  if (settings_.donor_cell_blend) return std::clamp(*settings_.donor_cell_blend, 0.0, 1.0);
  const MacGrid& g = state_.grid;
  const double courant = std::max(state_.velocity.u.max_abs_interior() * dt_s / g.dx(),
                                  state_.velocity.v.max_abs_interior() * dt_s / g.dy());
  return std::min(1.0, courant);
}

void EulerianSolver::compute_predictor(double dt_s, double gamma) {
  const Velocity& vel = state_.velocity;
  const double nu = settings_.viscosity_m2_per_s;
  const Vec2 gravity = settings_.gravity_m_per_s2;
  predictor_ = vel;  // keeps the boundary values: F = u, G = v on the sides (Griebel et al.)
  const FaceRange ru = interior_u_faces(state_.grid, settings_.boundaries);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i)
      predictor_.u(i, j) = vel.u(i, j) + dt_s * (nu * face_laplacian(vel.u, i, j) - convection_u(vel, i, j, gamma) +
                                                 gravity.x + body_acceleration_.u(i, j));
  const FaceRange rv = interior_v_faces(state_.grid, settings_.boundaries);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i)
      predictor_.v(i, j) = vel.v(i, j) + dt_s * (nu * face_laplacian(vel.v, i, j) - convection_v(vel, i, j, gamma) +
                                                 gravity.y + body_acceleration_.v(i, j));
  apply_velocity_boundaries(predictor_, settings_.boundaries);
}

PressureSolveReport EulerianSolver::single_step(double dt_s) {
  apply_velocity_boundaries(state_.velocity, settings_.boundaries);
  last_gamma_ = donor_cell_blend(dt_s);
  compute_predictor(dt_s, last_gamma_);                                 // eq. 4.6
  std::swap(state_.velocity, predictor_);
  const PressureSolveReport report = project(dt_s);                     // eqs. 3.3, 4.10–4.12, 4.7
  time_s_ += dt_s;
  return report;
}

StepReport EulerianSolver::step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("time step must be positive");
  StepReport report;
  report.dt_s = dt_s;
  report.substeps = 0;
  double remaining = dt_s;
  while (remaining > 0.0) {
    const double limit = stable_time_step();
    if (!(limit > 0.0))  // stability_time_step returns 0 for a non-finite velocity
      throw std::runtime_error("Eulerian solver: the velocity is no longer finite");
    double h = remaining;
    if (h > limit * (1.0 + 1e-12)) {
      std::ostringstream msg;
      msg << "Eulerian solver: time step " << dt_s << " s exceeds the stability limit " << limit
          << " s (CFL eq. 4.8 / viscous eq. 4.9 with safety factor " << settings_.safety_factor << ")";
      if (settings_.time_step_policy == TimeStepPolicy::refuse) throw std::domain_error(msg.str());
      if (report.message.empty()) report.message = msg.str() + "; split into stable sub-steps";
      h = limit;
    }
    if (remaining - h < 1e-12 * dt_s) h = remaining;
    report.pressure = single_step(h);
    remaining -= h;
    ++report.substeps;
  }
  return report;
}

}  // namespace jellysim::fluid
