#include "jellysim/studies/driven_cavity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

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

GhiaComparison compare_with_ghia_re100(const fluid::FlowState& s) {
  GhiaComparison c;
  for (const fluid::ProfilePoint& r : fluid::kGhiaRe100CentrelineU) {
    const double e = s.velocity.u.sample({0.5, r.position}) - r.velocity;
    c.u_error.push_back(e);
    c.max_abs_u_error = std::max(c.max_abs_u_error, std::abs(e));
  }
  for (const fluid::ProfilePoint& r : fluid::kGhiaRe100CentrelineV) {
    const double e = s.velocity.v.sample({r.position, 0.5}) - r.velocity;
    c.v_error.push_back(e);
    c.max_abs_v_error = std::max(c.max_abs_v_error, std::abs(e));
  }
  return c;
}

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
  if (std::abs(settings.reynolds - 100.0) < 1e-9 && L == 1.0 && U == 1.0)
    result.ghia = compare_with_ghia_re100(result.final_state);
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
