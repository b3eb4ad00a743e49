#include "jellysim/fluid/fluid_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "jellysim/core/state_archive.hpp"
#include "jellysim/fluid/eulerian_solver.hpp"
#include "semi_lagrangian_solver.hpp"

namespace jellysim::fluid {

FluidSolver::FluidSolver(const MacGrid& grid, const FluidSettings& settings)
    : settings_(settings),
      state_(grid),
      body_acceleration_(grid),
      projector_(make_pressure_solver(settings.pressure_solver, settings.pressure), settings.geometry) {
  settings_.boundaries.validate();
  if (settings_.geometry == Geometry::axisymmetric) {
    if (settings_.boundaries.west.type != BoundaryType::free_slip)
      throw std::invalid_argument("axisymmetric flow: the west side is the axis and must be free-slip (symmetry)");
    if (settings_.pressure_solver == "multigrid")
      throw std::invalid_argument("axisymmetric flow: the multigrid pressure solver is planar only (use fft, direct or sor)");
  }
  projector_.set_extrapolation(settings_.extrapolate_pressure_guess);
  if (!(settings_.viscosity_m2_per_s >= 0.0)) throw std::invalid_argument("viscosity must be >= 0");
  if (!(settings_.density_kg_per_m3 > 0.0)) throw std::invalid_argument("density must be > 0");
  if (!(settings_.safety_factor > 0.0 && settings_.safety_factor <= 1.0))
    throw std::invalid_argument("safety factor must lie in (0, 1]");
  apply_boundaries();
}

void FluidSolver::add_body_accelerations(Velocity& vel, double dt_s) const {
  const MacGrid& g = state_.grid;
  const Vec2 gravity = settings_.gravity_m_per_s2;
  const FaceRange ru = interior_u_faces(g, settings_.boundaries);
  for (int j = ru.j_begin; j < ru.j_end; ++j) {
    const double* a = body_acceleration_.u.ptr(0, j);
    double* u = vel.u.ptr(0, j);
    for (int i = ru.i_begin; i < ru.i_end; ++i) u[i] += dt_s * (gravity.x + a[i]);
  }
  const FaceRange rv = interior_v_faces(g, settings_.boundaries);
  for (int j = rv.j_begin; j < rv.j_end; ++j) {
    const double* a = body_acceleration_.v.ptr(0, j);
    double* v = vel.v.ptr(0, j);
    for (int i = rv.i_begin; i < rv.i_end; ++i) v[i] += dt_s * (gravity.y + a[i]);
  }
}

PressureSolveReport FluidSolver::project(double dt_s) {
  return projector_.project(state_, settings_.boundaries, dt_s, settings_.density_kg_per_m3);
}

const std::vector<std::string>& fluid_solver_names() {
  static const std::vector<std::string> names{"eulerian", "semi-lagrangian"};
  return names;
}

std::unique_ptr<FluidSolver> make_fluid_solver(std::string_view name, const MacGrid& grid,
                                               const FluidSettings& settings) {
  if (name == "eulerian") return std::make_unique<EulerianSolver>(grid, settings);
  if (name == "semi-lagrangian") return std::make_unique<SemiLagrangianSolver>(grid, settings);
  throw std::invalid_argument("unknown fluid solver '" + std::string(name) +
                              "' (expected eulerian or semi-lagrangian)");
}

const std::vector<std::string>& scheme_names_for(std::string_view solver) {
  if (solver == "eulerian") return convection_scheme_names();
  if (solver == "semi-lagrangian") return advection_scheme_names();
  throw std::invalid_argument("unknown fluid solver '" + std::string(solver) +
                              "' (expected eulerian or semi-lagrangian)");
}

void set_scheme(FluidSettings& settings, std::string_view solver, std::string_view scheme) {
  const std::vector<std::string>& names = scheme_names_for(solver);
  if (solver == "eulerian") {
    if (const auto c = convection_scheme_from_string(scheme)) return void(settings.convection = *c);
  } else if (const auto a = advection_scheme_from_string(scheme)) {
    return void(settings.advection = *a);
  }
  std::string allowed;
  for (const std::string& n : names) allowed += (allowed.empty() ? "" : ", ") + n;
  throw std::invalid_argument("the " + std::string(solver) + " solver has no scheme '" + std::string(scheme) +
                              "' (expected one of " + allowed + ")");
}

void FluidSolver::archive(core::StateArchive& a) {
  const core::StateArchive::Scope scope(a, "fluid");
  fluid::archive(a, "velocity", state_.velocity);
  fluid::archive(a, "pressure", state_.pressure);
  fluid::archive(a, "body_acceleration", body_acceleration_);
  a.value("time", time_s_);
  a.value("viscosity", settings_.viscosity_m2_per_s);
  const core::StateArchive::Scope projection(a, "projector");
  projector_.archive(a);
}

void FluidSolver::set_viscosity(double nu_m2_per_s) {
  if (!(nu_m2_per_s >= 0.0 && std::isfinite(nu_m2_per_s))) throw std::invalid_argument("viscosity must be >= 0");
  settings_.viscosity_m2_per_s = nu_m2_per_s;
}

namespace {

// Largest |u| and |v| over the faces and the prescribed side velocities (walls, in-flow).
std::array<double, 2> largest_speeds(const Velocity& vel, const Boundaries* sides) {
  double u_max = vel.u.max_abs_interior();
  double v_max = vel.v.max_abs_interior();
  if (sides)
    for (const BoundaryCondition* c : {&sides->west, &sides->east, &sides->south, &sides->north}) {
      if (c->type == BoundaryType::outflow || c->type == BoundaryType::periodic) continue;
      u_max = std::max(u_max, std::abs(c->velocity_m_per_s.x));
      v_max = std::max(v_max, std::abs(c->velocity_m_per_s.y));
    }
  return {u_max, v_max};
}

double viscous_time_step(const MacGrid& g, double nu) {  // eq. 4.9
  return nu > 0.0 ? 0.5 / nu / (1.0 / (g.dx() * g.dx()) + 1.0 / (g.dy() * g.dy()))
                  : std::numeric_limits<double>::infinity();
}

}  // namespace

double stability_time_step(const Velocity& vel, double viscosity_m2_per_s, double safety_factor,
                           const Boundaries* sides) {
  const MacGrid& g = vel.u.grid();
  const double inf = std::numeric_limits<double>::infinity();
  const auto [u_max, v_max] = largest_speeds(vel, sides);
  if (!std::isfinite(u_max) || !std::isfinite(v_max)) return 0.0;
  const double convective = std::min(u_max > 0.0 ? g.dx() / u_max : inf, v_max > 0.0 ? g.dy() / v_max : inf);  // eq. 4.8
  return safety_factor * std::min(convective, viscous_time_step(g, viscosity_m2_per_s));
}

double stability_time_step(const Velocity& vel, double viscosity_m2_per_s, double safety_factor,
                           ConvectionScheme scheme, const Boundaries* sides) {
  if (scheme == ConvectionScheme::donor_cell) return stability_time_step(vel, viscosity_m2_per_s, safety_factor, sides);
  const MacGrid& g = vel.u.grid();
  const auto [u_max, v_max] = largest_speeds(vel, sides);
  if (!std::isfinite(u_max) || !std::isfinite(v_max)) return 0.0;
  // Forward Euler with limited face values of limiter range [0, 2] is TVD for a Courant number
  // ≤ 1/(1 + 2/2) = ½ in one dimension (Hundsdorfer & Verwer 2003, §III.1); unsplit in 2D the
  // Courant numbers add up.
  // Combined with the viscous limit as rates (1/Δt = 1/Δt_convective + 1/Δt_viscous): the step is
  // then a convex combination of a convective and a viscous forward-Euler step, each within its
  // own limit. (Each limit alone, as eq. 4.8/4.9 take them, let a 2Δt oscillation grow next to the
  // lid of a 128² Re 100 cavity, where both limits are close.)
  const double convective_rate = 2.0 * (u_max / g.dx() + v_max / g.dy());
  const double viscous_rate = 1.0 / viscous_time_step(g, viscosity_m2_per_s);
  const double rate = convective_rate + viscous_rate;
  return rate > 0.0 ? safety_factor / rate : std::numeric_limits<double>::infinity();
}

}  // namespace jellysim::fluid
