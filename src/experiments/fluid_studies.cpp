// Fluid solver studies (thesis ch. 4): `taylor-green` (accuracy and order of convergence against the
// exact solution) and `solver-cost` (time per step and per simulated second, and accuracy).
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/studies/taylor_green.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/study_scenes.hpp"

#include <cmath>

namespace jellysim::experiments {
namespace {

using scene::read_solver_cost;
using scene::read_taylor_green;

void write_chart(const io::OutputDir& out, const std::string& name, render::ChartSpec chart) {
  out.write_text(name, render::chart_png(chart));
}

// ---- taylor-green ---------------------------------------------------------------------------

void write_taylor_green(const io::OutputDir& out, const studies::TaylorGreenResult& r,
                        const studies::TaylorGreenSettings& s) {
  io::CsvWriter runs({"solver", "scheme", "cells", "dx", "dt", "steps", "error_l2", "error_max"});
  io::CsvWriter orders({"solver", "scheme", "coarse_cells", "fine_cells", "order_l2", "order_max"});
  render::ChartSpec chart;
  chart.title = "Taylor-Green vortex: velocity error at t = " + io::format_double(s.end_time_s) + " s";
  chart.x_label = "grid spacing dx";
  chart.x_unit = "m";
  chart.y_label = "RMS velocity error";
  chart.y_unit = "m/s";
  chart.log_x = chart.log_y = true;
  for (const std::string& solver : s.solvers)
    for (const std::string& scheme : studies::schemes_of(s, solver)) {
      render::Series series;
      const double order = r.fitted_order_l2(solver, scheme);
      series.label = solver + " " + scheme + " (order " + io::format_double(std::round(order * 100) / 100) + ")";
      series.markers = true;
      for (const auto& run : r.runs) {
        if (run.solver != solver || run.scheme != scheme) continue;
        const double dx = s.flow.length_m / run.cells;
        runs.row({solver, scheme}, {static_cast<double>(run.cells), dx, run.dt_s, static_cast<double>(run.steps),
                                    run.error_l2, run.error_max});
        series.x.push_back(dx);
        series.y.push_back(run.error_l2);
      }
      chart.series.push_back(std::move(series));
    }
  for (const auto& o : r.orders) {
    orders.row({o.solver, o.scheme}, {static_cast<double>(o.coarse_cells), static_cast<double>(o.fine_cells),
                                      o.order_l2, o.order_max});
  }
  out.write_text("taylor_green.csv", runs.text());
  out.write_text("orders.csv", orders.text());
  write_chart(out, "taylor_green.png", std::move(chart));
}

std::function<Outcome(const io::OutputDir&)> prepare_taylor_green(const Context& ctx) {
  const studies::TaylorGreenSettings settings = read_taylor_green(ctx.config);
  return [settings, ctx](const io::OutputDir& out) {
    const studies::TaylorGreenResult r = studies::run_taylor_green(settings);
    write_taylor_green(out, r, settings);
    nlohmann::ordered_json figures, fitted;
    double wall = 0.0;
    for (const auto& run : r.runs) wall += run.wall_time_s;
    for (const std::string& solver : settings.solvers)
      for (const std::string& scheme : studies::schemes_of(settings, solver))
        fitted[solver][scheme] = r.fitted_order_l2(solver, scheme);
    figures["wall_seconds"] = wall;
    figures["measured_orders_l2"] = fitted;
    write_summary(out, "taylor-green", ctx.config, figures, "");
    return Outcome{};
  };
}

// ---- solver-cost ----------------------------------------------------------------------------

void write_solver_cost(const io::OutputDir& out, const std::vector<studies::SolverCostRow>& rows) {
  io::CsvWriter csv({"solver", "pressure_solver", "cells", "dt", "steps", "mean_pressure_iterations", "error_l2"});
  nlohmann::ordered_json timings = nlohmann::ordered_json::array();
  render::ChartSpec chart;
  chart.title = "Fluid solver cost per step";
  chart.x_label = "cells";
  chart.y_label = "wall time per step";
  chart.y_unit = "s";
  chart.log_x = chart.log_y = true;
  for (const auto& r : rows) {
    const std::string label = r.solver + " + " + r.pressure_solver;
    csv.row({r.solver, r.pressure_solver},
            {static_cast<double>(r.cells), r.dt_s, static_cast<double>(r.steps), r.mean_pressure_iterations, r.error_l2});
    timings.push_back({{"solver", r.solver}, {"pressure_solver", r.pressure_solver}, {"cells", r.cells},
                       {"seconds_per_step", r.seconds_per_step},
                       {"seconds_per_simulated_second", r.seconds_per_simulated_second}});
    if (chart.series.empty() || chart.series.back().label != label) {
      chart.series.emplace_back();
      chart.series.back().label = label;
      chart.series.back().markers = true;
    }
    chart.series.back().x.push_back(static_cast<double>(r.cells) * r.cells);
    chart.series.back().y.push_back(r.seconds_per_step);
  }
  out.write_text("solver_cost.csv", csv.text());
  write_timings(out, {{"runs", timings}});
  write_chart(out, "solver_cost.png", std::move(chart));
}

std::function<Outcome(const io::OutputDir&)> prepare_solver_cost(const Context& ctx) {
  const studies::SolverCostSettings settings = read_solver_cost(ctx.config);
  return [settings, ctx](const io::OutputDir& out) {
    const std::vector<studies::SolverCostRow> rows = studies::run_solver_cost(settings);
    write_solver_cost(out, rows);
    nlohmann::ordered_json figures, per_step = nlohmann::ordered_json::object();
    for (const auto& r : rows) {
      per_step[r.solver + "+" + r.pressure_solver + "@" + std::to_string(r.cells)] = r.seconds_per_step;
    }
    figures["seconds_per_step"] = per_step;
    write_summary(out, "solver-cost", ctx.config, figures, "");
    return Outcome{};
  };
}

}  // namespace

Experiment taylor_green_experiment() {
  return {"taylor-green", "Periodic Taylor-Green vortex: errors and convergence order of both fluid solvers",
          "experiments/taylor-green.toml", prepare_taylor_green};
}

Experiment solver_cost_experiment() {
  return {"solver-cost", "Time per step and accuracy of both fluid solvers with SOR and multigrid pressure",
          "experiments/solver-cost.toml", prepare_solver_cost};
}

}  // namespace jellysim::experiments
