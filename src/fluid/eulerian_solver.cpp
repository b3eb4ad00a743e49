#include "jellysim/fluid/eulerian_solver.hpp"
#include "jellysim/fluid/limited_flux.hpp"

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

/// The fluxes of a face-centred quantity through the four sides of its control volume.
struct SideFluxes {
  double east, west, north, south;
};

// The fluxes of u around the x-face (i, j) with limited face values of u (same carriers as
// convection_u).
template <ConvectionScheme S>
SideFluxes limited_u_side_fluxes(const Velocity& vel, const StencilReader& u, int i, int j) {
  const Field& v = vel.v;
  const double c = u(i, j);
  return {limited_flux<S>(0.5 * (c + u(i + 1, j)), u(i - 1, j), c, u(i + 1, j), u(i + 2, j)),
          limited_flux<S>(0.5 * (u(i - 1, j) + c), u(i - 2, j), u(i - 1, j), c, u(i + 1, j)),
          limited_flux<S>(0.5 * (v(i - 1, j + 1) + v(i, j + 1)), u(i, j - 1), c, u(i, j + 1), u(i, j + 2)),
          limited_flux<S>(0.5 * (v(i - 1, j) + v(i, j)), u(i, j - 2), u(i, j - 1), c, u(i, j + 1))};
}

// The same for v around the y-face (i, j).
template <ConvectionScheme S>
SideFluxes limited_v_side_fluxes(const Velocity& vel, const StencilReader& v, int i, int j) {
  const Field& u = vel.u;
  const double c = v(i, j);
  return {limited_flux<S>(0.5 * (u(i + 1, j - 1) + u(i + 1, j)), v(i - 1, j), c, v(i + 1, j), v(i + 2, j)),
          limited_flux<S>(0.5 * (u(i, j - 1) + u(i, j)), v(i - 2, j), v(i - 1, j), c, v(i + 1, j)),
          limited_flux<S>(0.5 * (c + v(i, j + 1)), v(i, j - 1), c, v(i, j + 1), v(i, j + 2)),
          limited_flux<S>(0.5 * (v(i, j - 1) + c), v(i, j - 2), v(i, j - 1), c, v(i, j + 1))};
}

/// ∂(u²)/∂x + ∂(uv)/∂y (planar) from the side fluxes around x-face (i, j).
double planar_divergence(const SideFluxes& f, const MacGrid& g) {
  return (f.east - f.west) / g.dx() + (f.north - f.south) / g.dy();
}

/// (1/r) ∂(r u²)/∂r + ∂(uv)/∂z around the r-face (i, j): the r-fluxes at the cell centres either side.
double axisymmetric_u_divergence(const SideFluxes& f, const MacGrid& g, int i) {
  return ((i + 0.5) * f.east - (i - 0.5) * f.west) / (i * g.dx()) + (f.north - f.south) / g.dy();
}

/// (1/r) ∂(r u v)/∂r + ∂(v²)/∂z around the z-face (i, j): the r-fluxes through the faces at iΔr
/// (zero on the axis) and (i + 1)Δr.
double axisymmetric_v_divergence(const SideFluxes& f, const MacGrid& g, int i) {
  return ((i + 1.0) * f.east - i * f.west) / ((i + 0.5) * g.dx()) + (f.north - f.south) / g.dy();
}

// ∂(u²)/∂x + ∂(uv)/∂y at the x-face (i, j) with limited face values of u.
template <ConvectionScheme S>
double limited_convection_u(const Velocity& vel, const StencilReader& u, int i, int j) {
  return planar_divergence(limited_u_side_fluxes<S>(vel, u, i, j), vel.u.grid());
}

// ∂(uv)/∂x + ∂(v²)/∂y at the y-face (i, j) with limited face values of v.
template <ConvectionScheme S>
double limited_convection_v(const Velocity& vel, const StencilReader& v, int i, int j) {
  return planar_divergence(limited_v_side_fluxes<S>(vel, v, i, j), vel.u.grid());
}

}  // namespace

double convection_u_limited(const Velocity& vel, const Boundaries& b, int i, int j, ConvectionScheme scheme) {
  const StencilReader u(vel.u, b);
  switch (scheme) {
    case ConvectionScheme::van_leer: return limited_convection_u<ConvectionScheme::van_leer>(vel, u, i, j);
    case ConvectionScheme::koren: return limited_convection_u<ConvectionScheme::koren>(vel, u, i, j);
    case ConvectionScheme::donor_cell: break;
  }
  return convection_u(vel, i, j, 1.0);
}

double convection_v_limited(const Velocity& vel, const Boundaries& b, int i, int j, ConvectionScheme scheme) {
  const StencilReader v(vel.v, b);
  switch (scheme) {
    case ConvectionScheme::van_leer: return limited_convection_v<ConvectionScheme::van_leer>(vel, v, i, j);
    case ConvectionScheme::koren: return limited_convection_v<ConvectionScheme::koren>(vel, v, i, j);
    case ConvectionScheme::donor_cell: break;
  }
  return convection_v(vel, i, j, 1.0);
}

namespace {

/// The γ-blended fluxes of u through the four sides of its control volume around x-face (i, j).
SideFluxes u_side_fluxes(const Velocity& vel, int i, int j, double gamma) {
  const Field& u = vel.u;
  const Field& v = vel.v;
  return {blended_flux(0.5 * (u(i, j) + u(i + 1, j)), u(i, j), u(i + 1, j), gamma),
          blended_flux(0.5 * (u(i - 1, j) + u(i, j)), u(i - 1, j), u(i, j), gamma),
          blended_flux(0.5 * (v(i - 1, j + 1) + v(i, j + 1)), u(i, j), u(i, j + 1), gamma),
          blended_flux(0.5 * (v(i - 1, j) + v(i, j)), u(i, j - 1), u(i, j), gamma)};
}

/// The same for v around y-face (i, j).
SideFluxes v_side_fluxes(const Velocity& vel, int i, int j, double gamma) {
  const Field& u = vel.u;
  const Field& v = vel.v;
  return {blended_flux(0.5 * (u(i + 1, j - 1) + u(i + 1, j)), v(i, j), v(i + 1, j), gamma),
          blended_flux(0.5 * (u(i, j - 1) + u(i, j)), v(i - 1, j), v(i, j), gamma),
          blended_flux(0.5 * (v(i, j) + v(i, j + 1)), v(i, j), v(i, j + 1), gamma),
          blended_flux(0.5 * (v(i, j - 1) + v(i, j)), v(i, j - 1), v(i, j), gamma)};
}

}  // namespace

double convection_u(const Velocity& vel, int i, int j, double gamma) {
  return planar_divergence(u_side_fluxes(vel, i, j, gamma), vel.u.grid());
}

double convection_v(const Velocity& vel, int i, int j, double gamma) {
  return planar_divergence(v_side_fluxes(vel, i, j, gamma), vel.u.grid());
}

// ---- Axisymmetric flow without swirl (x = r from the axis, y = z; fluid_solver.hpp) ----
// u = u_r on the r-faces at r = iΔr, v = u_z on the z-faces at the cell radii r_i = (i + ½)Δr.

double axisymmetric_viscous_u(const Field& u, int i, int j) {
  // (1/r) ∂/∂r (r ∂u/∂r) − u/r² + ∂²u/∂z², the r-derivatives through the cell centres either side.
  const MacGrid& g = u.grid();
  const double r = i * g.dx(), c = u(i, j);
  const double radial = ((i + 0.5) * (u(i + 1, j) - c) - (i - 0.5) * (c - u(i - 1, j))) / (i * g.dx() * g.dx());
  return radial - c / (r * r) + (u(i, j + 1) - 2.0 * c + u(i, j - 1)) / (g.dy() * g.dy());
}

double axisymmetric_viscous_v(const Field& v, int i, int j) {
  // (1/r) ∂/∂r (r ∂v/∂r) + ∂²v/∂z², fluxes through the faces at iΔr and (i + 1)Δr (none at the axis).
  const MacGrid& g = v.grid();
  const double c = v(i, j);
  const double radial = ((i + 1.0) * (v(i + 1, j) - c) - i * (c - v(i - 1, j))) / ((i + 0.5) * g.dx() * g.dx());
  return radial + (v(i, j + 1) - 2.0 * c + v(i, j - 1)) / (g.dy() * g.dy());
}

double axisymmetric_convection_u(const Velocity& vel, int i, int j, double gamma) {
  // No swirl: no −u_θ²/r term.
  return axisymmetric_u_divergence(u_side_fluxes(vel, i, j, gamma), vel.u.grid(), i);
}

double axisymmetric_convection_v(const Velocity& vel, int i, int j, double gamma) {
  return axisymmetric_v_divergence(v_side_fluxes(vel, i, j, gamma), vel.u.grid(), i);
}

EulerianSolver::EulerianSolver(const MacGrid& grid, const FluidSettings& settings)
    : FluidSolver(grid, settings), predictor_(grid) {}

double EulerianSolver::stable_time_step() const {
  const double dt = stability_time_step(state_.velocity, settings_.viscosity_m2_per_s, settings_.safety_factor,
                                        settings_.convection, &settings_.boundaries);
  if (settings_.geometry == Geometry::planar || settings_.viscosity_m2_per_s <= 0.0) return dt;
  // The radial viscous operator of u_r next to the axis has Gershgorin sum 5/Δr² (−u/r² included)
  // where the planar one has 4/Δx²: forward Euler needs Δt ≤ 2/(ν (5/Δr² + 4/Δz²)).
  const MacGrid& g = state_.grid;
  const double axisymmetric_viscous =
      2.0 / (settings_.viscosity_m2_per_s * (5.0 / (g.dx() * g.dx()) + 4.0 / (g.dy() * g.dy())));
  return std::min(dt, settings_.safety_factor * axisymmetric_viscous);
}

double EulerianSolver::donor_cell_blend(double dt_s) const {
  if (settings_.donor_cell_blend) return std::clamp(*settings_.donor_cell_blend, 0.0, 1.0);
  const MacGrid& g = state_.grid;
  const double courant = std::max(state_.velocity.u.max_abs_interior() * dt_s / g.dx(),
                                  state_.velocity.v.max_abs_interior() * dt_s / g.dy());
  return std::min(1.0, courant);
}

template <class ConvectionU, class ConvectionV, class ViscousU, class ViscousV>
void EulerianSolver::compute_predictor_with(double dt_s, ConvectionU&& convection_u_at, ConvectionV&& convection_v_at,
                                            ViscousU&& viscous_u_at, ViscousV&& viscous_v_at) {
  const Velocity& vel = state_.velocity;
  const double nu = settings_.viscosity_m2_per_s;
  const Vec2 gravity = settings_.gravity_m_per_s2;
  predictor_ = vel;  // keeps the boundary values: F = u, G = v on the sides (Griebel et al.)
  const FaceRange ru = interior_u_faces(state_.grid, settings_.boundaries);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i)
      predictor_.u(i, j) = vel.u(i, j) + dt_s * (nu * viscous_u_at(i, j) - convection_u_at(i, j) +
                                                 gravity.x + body_acceleration_.u(i, j));
  const FaceRange rv = interior_v_faces(state_.grid, settings_.boundaries);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i)
      predictor_.v(i, j) = vel.v(i, j) + dt_s * (nu * viscous_v_at(i, j) - convection_v_at(i, j) +
                                                 gravity.y + body_acceleration_.v(i, j));
  apply_velocity_boundaries(predictor_, settings_.boundaries);
}

template <class ConvectionU, class ConvectionV>
void EulerianSolver::compute_predictor_with(double dt_s, ConvectionU&& convection_u_at, ConvectionV&& convection_v_at) {
  const Velocity& vel = state_.velocity;
  compute_predictor_with(
      dt_s, convection_u_at, convection_v_at, [&](int i, int j) { return face_laplacian(vel.u, i, j); },
      [&](int i, int j) { return face_laplacian(vel.v, i, j); });
}

template <ConvectionScheme S>
void EulerianSolver::compute_limited_predictor(double dt_s) {
  const Velocity& vel = state_.velocity;
  const StencilReader u(vel.u, settings_.boundaries);
  const StencilReader v(vel.v, settings_.boundaries);
  const MacGrid& g = state_.grid;
  if (settings_.geometry == Geometry::axisymmetric)  // the axis's free-slip ghosts are the mirror images
    return compute_predictor_with(
        dt_s, [&](int i, int j) { return axisymmetric_u_divergence(limited_u_side_fluxes<S>(vel, u, i, j), g, i); },
        [&](int i, int j) { return axisymmetric_v_divergence(limited_v_side_fluxes<S>(vel, v, i, j), g, i); },
        [&](int i, int j) { return axisymmetric_viscous_u(vel.u, i, j); },
        [&](int i, int j) { return axisymmetric_viscous_v(vel.v, i, j); });
  compute_predictor_with(
      dt_s, [&](int i, int j) { return limited_convection_u<S>(vel, u, i, j); },
      [&](int i, int j) { return limited_convection_v<S>(vel, v, i, j); });
}

void EulerianSolver::compute_predictor(double dt_s, double gamma) {
  const Velocity& vel = state_.velocity;
  if (settings_.geometry == Geometry::axisymmetric && settings_.convection == ConvectionScheme::donor_cell)
    return compute_predictor_with(
        dt_s, [&](int i, int j) { return axisymmetric_convection_u(vel, i, j, gamma); },
        [&](int i, int j) { return axisymmetric_convection_v(vel, i, j, gamma); },
        [&](int i, int j) { return axisymmetric_viscous_u(vel.u, i, j); },
        [&](int i, int j) { return axisymmetric_viscous_v(vel.v, i, j); });
  switch (settings_.convection) {
    case ConvectionScheme::van_leer: return compute_limited_predictor<ConvectionScheme::van_leer>(dt_s);
    case ConvectionScheme::koren: return compute_limited_predictor<ConvectionScheme::koren>(dt_s);
    case ConvectionScheme::donor_cell:
      return compute_predictor_with(
          dt_s, [&](int i, int j) { return convection_u(vel, i, j, gamma); },
          [&](int i, int j) { return convection_v(vel, i, j, gamma); });
  }
}

PressureSolveReport EulerianSolver::single_step(double dt_s) {
  apply_velocity_boundaries(state_.velocity, settings_.boundaries);
  last_gamma_ = settings_.convection == ConvectionScheme::donor_cell ? donor_cell_blend(dt_s) : 0.0;
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
          << " s (" << (settings_.convection == ConvectionScheme::donor_cell ? "CFL eq. 4.8" : "Courant sum 1/2 plus viscous rate of the limited scheme")
          << " / viscous eq. 4.9 with safety factor " << settings_.safety_factor << ")";
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
