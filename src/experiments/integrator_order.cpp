#include "integrator_order.hpp"

#include "jellysim/elastic/elastic_system.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/experiment_scenes.hpp"

#include <cmath>

namespace jellysim::experiments {
namespace {

elastic::Body make_spring_pair(const SpringProblem& p) {
  elastic::Body body;
  const double half = 0.5 * (p.rest_length + p.amplitude);
  body.add_point({-half, 0.0}, p.point_mass);
  body.add_point({half, 0.0}, p.point_mass);
  body.add_linear_spring(0, 1, p.stiffness, p.rest_length);
  return body;
}

/// Exact state [x0, y0, x1, y1, vx0, vy0, vx1, vy1] at time t.
ode::Vector exact_state(const SpringProblem& p, double t) {
  const double w = p.omega();
  const double half_length = 0.5 * (p.rest_length + p.amplitude * std::cos(w * t));
  const double half_rate = -0.5 * p.amplitude * w * std::sin(w * t);
  ode::Vector y(8);
  y << -half_length, 0.0, half_length, 0.0, -half_rate, 0.0, half_rate, 0.0;
  return y;
}

ConvergenceRun run_fixed_steps(ode::Integrator& integrator, const SpringProblem& p, int steps) {
  elastic::Body body = make_spring_pair(p);
  elastic::ElasticSystem system(body);
  ode::Vector y = system.pack_state(), y_next(y.size());
  const double dt = p.end_time / steps;
  integrator.reset();
  for (int n = 0; n < steps; ++n) {
    if (!integrator.step(system, n * dt, dt, y, y_next, nullptr).ok) {
      throw RunError(std::string(integrator.name()) + " failed a step of " + io::format_double(dt));
    }
    y.swap(y_next);
  }
  return {dt, (y - exact_state(p, p.end_time)).lpNorm<Eigen::Infinity>(), system.evaluations()};
}

struct StudySettings {
  SpringProblem problem;
  std::vector<std::pair<std::string, int>> coarsest_steps;  // integrator, steps
  int refinements = 4;
};

/// The scene's fields (checked against its table, scene/experiment_scenes.hpp) as the study's settings.
StudySettings read_settings(const config::Config& c) {
  const scene::IntegratorOrderScene scene = scene::read_integrator_order(c);
  StudySettings s;
  s.problem.point_mass = scene.point_mass;
  s.problem.stiffness = scene.stiffness;
  s.problem.rest_length = scene.rest_length;
  s.problem.amplitude = scene.amplitude;
  s.problem.end_time = scene.end_time;
  s.refinements = scene.refinements;
  s.coarsest_steps = scene.coarsest_steps;
  return s;
}

void write_outputs(const io::OutputDir& out, const std::vector<ConvergenceStudy>& studies) {
  io::CsvWriter runs({"integrator", "dt", "error", "function_evaluations"});
  io::CsvWriter orders({"integrator", "expected_order", "measured_order"});
  render::ChartSpec chart;
  chart.title = "Global error at t = end_time (two-mass spring)";
  chart.x_label = "time step dt";
  chart.x_unit = "s";
  chart.y_label = "max-norm state error";
  chart.log_x = chart.log_y = true;
  for (const ConvergenceStudy& s : studies) {
    render::Series series;
    series.label = s.integrator + " (order " + io::format_double(std::round(s.measured_order * 100) / 100) + ")";
    series.markers = true;
    for (const ConvergenceRun& r : s.runs) {
      runs.row(s.integrator, {r.dt, r.error, static_cast<double>(r.function_evaluations)});
      series.x.push_back(r.dt);
      series.y.push_back(r.error);
    }
    orders.row(s.integrator, {static_cast<double>(s.expected_order), s.measured_order});
    chart.series.push_back(std::move(series));
  }
  out.write_text("convergence.csv", runs.text());
  out.write_text("orders.csv", orders.text());
  out.write_text("integrator_order.png", render::chart_png(chart));
}

std::function<Outcome(const io::OutputDir&)> prepare_integrator_order(const Context& ctx) {
  const StudySettings settings = read_settings(ctx.config);
  return [settings, ctx](const io::OutputDir& out) {
    std::vector<ConvergenceStudy> studies;
    nlohmann::ordered_json figures, measured;
    for (const auto& [name, steps] : settings.coarsest_steps) {
      studies.push_back(measure_convergence(name, settings.problem, steps, settings.refinements));
      measured[name] = studies.back().measured_order;
    }
    figures["omega"] = settings.problem.omega();
    figures["measured_orders"] = measured;
    write_outputs(out, studies);
    write_summary(out, "integrator-order", ctx.config, figures, "");
    return Outcome{};
  };
}

}  // namespace

double SpringProblem::omega() const { return std::sqrt(2.0 * stiffness / point_mass); }

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx; sy += ly; sxx += lx * lx; sxy += lx * ly;
  }
  const double dn = static_cast<double>(n);
  return (dn * sxy - sx * sy) / (dn * sxx - sx * sx);
}

ConvergenceStudy measure_convergence(const std::string& integrator_name, const SpringProblem& problem,
                                     int coarsest_steps, int refinements) {
  auto integrator = ode::make_integrator(integrator_name);
  ConvergenceStudy study{integrator_name, integrator->order(), {}, 0.0};
  std::vector<double> dts, errors;
  for (int r = 0; r <= refinements; ++r) {
    study.runs.push_back(run_fixed_steps(*integrator, problem, coarsest_steps << r));
    dts.push_back(study.runs.back().dt);
    errors.push_back(study.runs.back().error);
  }
  study.measured_order = log_log_slope(dts, errors);
  return study;
}

Experiment integrator_order_experiment() {
  return {"integrator-order", "Measured global order of convergence of every integrator (§2.4)",
          "experiments/integrator-order.toml", prepare_integrator_order};
}

}  // namespace jellysim::experiments
