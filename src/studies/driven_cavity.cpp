#include "jellysim/studies/driven_cavity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/projection.hpp"
#include "jellysim/fluid/tracers.hpp"
#include "jellysim/sim/frame_clock.hpp"

namespace jellysim::studies {
namespace {

fluid::FluidSettings cavity_fluid_settings(const DrivenCavitySettings& s) {
  fluid::FluidSettings f;
  f.viscosity_m2_per_s = s.lid_speed_m_per_s * s.size_m / s.reynolds;
  f.density_kg_per_m3 = 1.0;
  f.boundaries = fluid::Boundaries::lid_driven_cavity(s.lid_speed_m_per_s);
  f.pressure_solver = s.pressure_solver;
  f.pressure.relative_tolerance = s.pressure_tolerance;
  f.pressure.max_iterations = s.pressure_solver == "sor" ? 100000 : 200;
  f.safety_factor = s.safety_factor;
  f.donor_cell_blend = s.donor_cell_blend;
  f.time_step_policy = fluid::TimeStepPolicy::reduce;
  f.project_before_advection = s.project_before_advection;
  f.convection = s.convection;
  f.advection = s.advection;
  return f;
}

double max_change(const fluid::Velocity& a, const fluid::Velocity& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.u.raw().size(); ++k) m = std::max(m, std::abs(a.u.raw()[k] - b.u.raw()[k]));
  for (std::size_t k = 0; k < a.v.raw().size(); ++k) m = std::max(m, std::abs(a.v.raw()[k] - b.v.raw()[k]));
  return m;
}

}  // namespace

CentrelineProfile vertical_centreline_u(const fluid::FlowState& s, double x_m) {
  CentrelineProfile p;
  const fluid::MacGrid& g = s.grid;
  auto add = [&](double y) {
    p.position_m.push_back(y);
    p.velocity_m_per_s.push_back(s.velocity.u.sample({x_m, y}));
  };
  add(g.origin_m.y);
  for (int j = 0; j < g.ny; ++j) add(g.world_from_grid(0.0, j + 0.5).y);
  add(g.origin_m.y + g.height_m);
  return p;
}

CentrelineProfile horizontal_centreline_v(const fluid::FlowState& s, double y_m) {
  CentrelineProfile p;
  const fluid::MacGrid& g = s.grid;
  auto add = [&](double x) {
    p.position_m.push_back(x);
    p.velocity_m_per_s.push_back(s.velocity.v.sample({x, y_m}));
  };
  add(g.origin_m.x);
  for (int i = 0; i < g.nx; ++i) add(g.world_from_grid(i + 0.5, 0.0).x);
  add(g.origin_m.x + g.width_m);
  return p;
}

namespace {

/// The least-squares paraboloid ψ ≈ a + bξ + cη + dξ² + eξη + fη² through the 3 × 3 samples
/// p[η+1][ξ+1] (ξ, η ∈ {−1, 0, 1}, in cells), solved in the basis {1, ξ, η, ξ² − 2/3, ξη,
/// η² − 2/3}, which is orthogonal on those nine points (so each coefficient is one sum).
/// Returns the stationary point's offset (in cells) and value when it is a minimum within one
/// cell of the centre sample.
std::optional<std::array<double, 3>> paraboloid_minimum(const double (&p)[3][3]) {
  double s0 = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int eta = -1; eta <= 1; ++eta)
    for (int xi = -1; xi <= 1; ++xi) {
      const double v = p[eta + 1][xi + 1];
      s0 += v;
      sx += xi * v;
      sy += eta * v;
      sxx += (xi * xi - 2.0 / 3.0) * v;
      sxy += xi * eta * v;
      syy += (eta * eta - 2.0 / 3.0) * v;
    }
  // Σξ² = Ση² = 6, Σ(ξη)² = 4, Σ(ξ² − 2/3)² = Σ(η² − 2/3)² = 2 over the nine points.
  const double b = sx / 6.0, c = sy / 6.0, e = sxy / 4.0, d = sxx / 2.0, f = syy / 2.0;
  const double a = s0 / 9.0 - 2.0 / 3.0 * (d + f);
  // ∇ψ = 0: [2d e; e 2f] (ξ, η) = −(b, c); a minimum needs the Hessian positive definite.
  const double det = 4.0 * d * f - e * e;
  if (!(d > 0.0 && det > 0.0)) return std::nullopt;
  const double xi = (-b * 2.0 * f + c * e) / det;
  const double eta = (-c * 2.0 * d + b * e) / det;
  if (!(std::abs(xi) <= 1.0 && std::abs(eta) <= 1.0)) return std::nullopt;
  return std::array<double, 3>{xi, eta, a + b * xi + c * eta + d * xi * xi + e * xi * eta + f * eta * eta};
}

}  // namespace

PrimaryVortex find_primary_vortex(const fluid::FlowState& s) {
  const fluid::Field psi = fluid::stream_function_at_nodes(s.velocity);
  const fluid::MacGrid& g = s.grid;
  // The minimum over the interior nodes (every one has its 3 × 3 neighbourhood in the grid).
  int im = -1, jm = -1;
  for (int j = 1; j < g.ny; ++j)
    for (int i = 1; i < g.nx; ++i)
      if (im < 0 || psi(i, j) < psi(im, jm)) {
        im = i;
        jm = j;
      }
  PrimaryVortex v;
  if (im < 0) return v;  // fewer than 2 cells a side: no interior node
  v.centre_m = psi.position(im, jm);
  v.stream_function_m2_per_s = psi(im, jm);
  double p[3][3];
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a) p[b][a] = psi(im + a - 1, jm + b - 1);
  if (const auto fit = paraboloid_minimum(p)) {
    v.centre_m = g.world_from_grid(im + (*fit)[0], jm + (*fit)[1]);
    v.stream_function_m2_per_s = (*fit)[2];
  }
  return v;
}

std::optional<GhiaComparison> compare_with_ghia(const fluid::FlowState& s, double reynolds) {
  const fluid::GhiaCavityReference* ref = fluid::ghia_reference(reynolds);
  if (!ref) return std::nullopt;
  GhiaComparison c;
  c.reynolds = ref->reynolds;
  c.reference_u = ref->centreline_u;
  c.reference_v = ref->centreline_v;
  for (const fluid::ProfilePoint& r : c.reference_u) {
    const double e = s.velocity.u.sample({0.5, r.position}) - r.velocity;
    c.u_error.push_back(e);
    c.max_abs_u_error = std::max(c.max_abs_u_error, std::abs(e));
  }
  for (const fluid::ProfilePoint& r : c.reference_v) {
    const double e = s.velocity.v.sample({r.position, 0.5}) - r.velocity;
    if (static_cast<int>(c.v_error.size()) != ref->misprinted_v_index)
      c.max_abs_v_error = std::max(c.max_abs_v_error, std::abs(e));
    c.v_error.push_back(e);
  }
  c.vortex = find_primary_vortex(s);
  c.reference_vortex = ref->primary_vortex;
  c.vortex_centre_error_m = c.vortex.centre_m - Vec2{c.reference_vortex.x, c.reference_vortex.y};
  c.psi_min_error = c.vortex.stream_function_m2_per_s - c.reference_vortex.stream_function;
  return c;
}

GhiaComparison compare_with_ghia_re100(const fluid::FlowState& s) { return *compare_with_ghia(s, 100.0); }

DrivenCavityResult run_driven_cavity(const DrivenCavitySettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const fluid::MacGrid grid(settings.cells, settings.cells, settings.size_m, settings.size_m);
  auto solver = fluid::make_fluid_solver(settings.solver, grid, cavity_fluid_settings(settings));
  DrivenCavityResult result;
  result.viscosity_m2_per_s = solver->settings().viscosity_m2_per_s;
  const double U = settings.lid_speed_m_per_s;
  const double L = settings.size_m;
  fluid::Velocity previous = solver->state().velocity;
  const int n = settings.tracers_per_side;
  fluid::Tracers tracers = n > 0 ? fluid::Tracers::lattice({0.05 * L, 0.05 * L}, {0.95 * L, 0.95 * L}, n, n) : fluid::Tracers{};
  const bool frames = settings.on_frame && settings.frame_interval_s > 0.0;
  // Frames (when asked for) on the shared clock; the run stops at max_time_s (exactly: no end
  // tolerance, a last sliver step is taken) or at a steady state.
  sim::FrameClock clock(frames ? settings.frame_interval_s : 0.0, settings.max_time_s, 1e-12,
                        sim::FrameClock::Ending::at_duration, 0.0);
  sim::ClockedRun loop;
  loop.time = [&] { return solver->time_s(); };
  loop.frame = [&](std::int64_t) {
    if (frames) settings.on_frame(solver->time_s(), solver->state(), tracers.positions());
    return std::string();
  };
  loop.step = [&](double) -> sim::StepResult {
    double dt = settings.time_step_s;
    if (dt <= 0.0) {
      dt = settings.solver == "eulerian" ? solver->stable_time_step() : grid.dx() / U;
      if (!std::isfinite(dt)) dt = settings.safety_factor * grid.dx() / U;  // fluid at rest
    }
    const double full_step = dt;
    dt = std::min(dt, settings.max_time_s - solver->time_s());
    // Land on the next frame time (not capped: a frame just past the end is landed on too).
    const double frame_time = clock.scheduled_frame_time();
    if (frames && solver->time_s() + dt >= frame_time - 1e-12) dt = frame_time - solver->time_s();
    const fluid::StepReport report = solver->step(dt);
    tracers.advect(solver->state().velocity, solver->settings().boundaries, dt);
    result.steps += report.substeps;
    if (!report.message.empty() && result.messages.size() < 3) result.messages.push_back(report.message);
    // The change per unit time of a step shortened to land on a frame or the end is round-off over
    // a sliver of time: only steps of at least half the regular size measure it.
    if (dt >= 0.5 * full_step) {
      result.final_change_rate = max_change(solver->state().velocity, previous) / dt * L / (U * U);
      result.history.push_back({solver->time_s(), result.final_change_rate});
      result.steady = result.final_change_rate < settings.steady_tolerance;
    }
    previous = solver->state().velocity;
    return {result.steady ? sim::StepResult::Kind::stop : sim::StepResult::Kind::ok, {}};
  };
  sim::run_frames(clock, loop);
  result.simulated_time_s = solver->time_s();
  result.final_state = solver->state();
  result.final_tracers_m = tracers.positions();
  result.max_divergence_per_s = fluid::max_divergence(result.final_state.velocity);
  result.centreline_u = vertical_centreline_u(result.final_state, 0.5 * L);
  result.centreline_v = horizontal_centreline_v(result.final_state, 0.5 * L);
  result.primary_vortex = find_primary_vortex(result.final_state);
  if (L == 1.0 && U == 1.0) result.ghia = compare_with_ghia(result.final_state, settings.reynolds);
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<CavityFigurePanel> run_cavity_figure_8_7(const CavityFigureSettings& settings) {
  std::vector<CavityFigurePanel> panels;
  for (const char* solver : {"eulerian", "semi-lagrangian"})
    for (double nu : settings.viscosities_m2_per_s) {
      DrivenCavitySettings s;
      s.solver = solver;
      s.reynolds = 1.0 / nu;  // U = L = 1
      s.cells = settings.cells;
      s.time_step_s = settings.time_step_s;
      s.max_time_s = settings.duration_s;
      s.steady_tolerance = 0.0;  // run the whole duration, like the thesis' animation
      s.pressure_solver = settings.pressure_solver;
      panels.push_back({solver, nu, run_driven_cavity(s)});
    }
  return panels;
}

}  // namespace jellysim::studies
