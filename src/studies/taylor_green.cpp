#include "jellysim/studies/taylor_green.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "jellysim/fluid/fluid_solver.hpp"

namespace jellysim::studies {
namespace {

fluid::MacGrid periodic_square(const fluid::TaylorGreen& flow, int cells) {
  return fluid::MacGrid(cells, cells, flow.length_m, flow.length_m);
}

fluid::FluidSettings taylor_green_settings(const fluid::TaylorGreen& flow, const std::string& pressure_solver,
                                    double tolerance, double safety) {
  fluid::FluidSettings f;
  f.viscosity_m2_per_s = flow.viscosity_m2_per_s;
  f.density_kg_per_m3 = 1.0;
  f.boundaries = fluid::Boundaries::all(fluid::BoundaryType::periodic);
  f.pressure_solver = pressure_solver;
  f.pressure.relative_tolerance = tolerance;
  f.pressure.max_iterations = pressure_solver == "sor" ? 200000 : 200;
  f.safety_factor = safety;
  f.time_step_policy = fluid::TimeStepPolicy::refuse;
  return f;
}

struct ErrorNorms {
  double l2, max;
};

ErrorNorms velocity_error(const fluid::Velocity& vel, const fluid::TaylorGreen& flow, double t) {
  const fluid::MacGrid& g = vel.u.grid();
  double sum = 0.0, m = 0.0;
  int n = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double eu = vel.u(i, j) - flow.velocity(vel.u.position(i, j), t).x;
      const double ev = vel.v(i, j) - flow.velocity(vel.v.position(i, j), t).y;
      sum += eu * eu + ev * ev;
      m = std::max({m, std::abs(eu), std::abs(ev)});
      n += 2;
    }
  return {std::sqrt(sum / n), m};
}

double step_size(const fluid::FluidSolver& solver, const std::string& name, double courant, const fluid::MacGrid& g,
                 const fluid::TaylorGreen& flow) {
  return name == "eulerian" ? solver.stable_time_step() : courant * g.dx() / flow.speed_m_per_s;
}

}  // namespace

double optimal_sor_omega(int nx, int ny) {
  return 2.0 / (1.0 + std::sin(std::numbers::pi / std::max(nx, ny)));
}

const std::vector<std::string>& schemes_of(const TaylorGreenSettings& s, const std::string& solver) {
  return solver == "eulerian" ? s.convection_schemes : s.advection_schemes;
}

TaylorGreenRun run_taylor_green_once(const std::string& solver_name, const std::string& scheme, int cells,
                                     const TaylorGreenSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  const fluid::MacGrid g = periodic_square(s.flow, cells);
  fluid::FluidSettings f = taylor_green_settings(s.flow, s.pressure_solver, s.pressure_tolerance, s.safety_factor);
  fluid::set_scheme(f, solver_name, scheme);
  auto solver = fluid::make_fluid_solver(solver_name, g, f);
  solver->state().velocity = s.flow.sample(g, 0.0);
  solver->apply_boundaries();
  // A uniform Δt that ends exactly at end_time and respects the (initial, largest) limit.
  const double dt_limit = step_size(*solver, solver_name, s.semi_lagrangian_courant, g, s.flow);
  const int steps = std::max(1, static_cast<int>(std::ceil(s.end_time_s / dt_limit - 1e-9)));
  const double dt = s.end_time_s / steps;
  for (int k = 0; k < steps; ++k) solver->step(dt);
  const ErrorNorms e = velocity_error(solver->state().velocity, s.flow, s.end_time_s);
  TaylorGreenRun run{solver_name, scheme, cells, dt, steps, e.l2, e.max, 0.0};
  run.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

TaylorGreenResult run_taylor_green(const TaylorGreenSettings& settings) {
  TaylorGreenResult result;
  for (const std::string& solver : settings.solvers)
    for (const std::string& scheme : schemes_of(settings, solver)) {
      const std::size_t first = result.runs.size();
      for (int cells : settings.grids) result.runs.push_back(run_taylor_green_once(solver, scheme, cells, settings));
      for (std::size_t k = first + 1; k < result.runs.size(); ++k) {
        const TaylorGreenRun& coarse = result.runs[k - 1];
        const TaylorGreenRun& fine = result.runs[k];
        const double ratio = std::log(static_cast<double>(fine.cells) / coarse.cells);
        result.orders.push_back({solver, scheme, coarse.cells, fine.cells,
                                 std::log(coarse.error_l2 / fine.error_l2) / ratio,
                                 std::log(coarse.error_max / fine.error_max) / ratio});
      }
    }
  return result;
}

double TaylorGreenResult::fitted_order_l2(const std::string& solver, const std::string& scheme) const {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const TaylorGreenRun& r : runs) {
    if (r.solver != solver || r.scheme != scheme) continue;
    const double x = std::log(1.0 / r.cells);  // log Δx up to a constant
    const double y = std::log(r.error_l2);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  if (n < 2) throw std::logic_error("fitted_order_l2 needs at least two grids");
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::vector<SolverCostRow> run_solver_cost(const SolverCostSettings& settings) {
  std::vector<SolverCostRow> rows;
  for (const std::string& solver_name : settings.solvers)
    for (const std::string& pressure : settings.pressure_solvers)
      for (int cells : settings.grids) {
        const fluid::MacGrid g = periodic_square(settings.flow, cells);
        fluid::FluidSettings f = taylor_green_settings(settings.flow, pressure, settings.pressure_tolerance, settings.safety_factor);
        if (settings.sor_optimal_omega) f.pressure.sor_omega = optimal_sor_omega(cells, cells);
        auto solver = fluid::make_fluid_solver(solver_name, g, f);
        solver->state().velocity = settings.flow.sample(g, 0.0);
        solver->apply_boundaries();
        const double dt = step_size(*solver, solver_name, settings.semi_lagrangian_courant, g, settings.flow);
        solver->step(dt);  // warm-up: allocations, first pressure field
        int iterations = 0;
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < settings.steps; ++k) iterations += solver->step(dt).pressure.iterations;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        SolverCostRow row{solver_name, pressure, cells, dt, settings.steps, elapsed / settings.steps, 0.0,
                          static_cast<double>(iterations) / settings.steps, 0.0};
        row.seconds_per_simulated_second = row.seconds_per_step / dt;
        row.error_l2 = velocity_error(solver->state().velocity, settings.flow, solver->time_s()).l2;
        rows.push_back(row);
      }
  return rows;
}

}  // namespace jellysim::studies
