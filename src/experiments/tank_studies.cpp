// Experiments on tanks with more than one thing in them (beyond the thesis, §1.3 and §9.2.2):
//  * steering: the same jellyfish steered toward a point on its left, not steered, and steered
//    toward the mirror point on its right; the heading over time shows whether it turns;
//  * obstacle-flow: uniform flow past a fixed cylinder held by the immersed boundary; drag
//    coefficient, leakage through the outline, and a picture of the flow.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/experiment_scenes.hpp"

namespace jellysim::experiments {
namespace {


constexpr double kDegree = std::numbers::pi / 180.0;

/// Heading as an angle from +y, counter-clockwise positive, in degrees.
double heading_deg(Vec2 h) { return std::atan2(-h.x, h.y) / kDegree; }

struct HeadingTrace {
  std::vector<double> t, heading_deg, bearing_deg;
  std::string failure;
  double wall_seconds = 0.0;
};

/// Runs one jellyfish, recording its heading and the bearing of `target` (when steering) per frame.
HeadingTrace trace_heading(jellyfish::SwimSettings settings, std::optional<Vec2> target) {
  settings.school.front().steering = target.has_value();
  if (target) settings.school.front().steer_target_m = *target;
  jellyfish::SwimSimulation sim(settings);
  HeadingTrace trace;
  const jellyfish::SwimRunStats stats = sim.run([&](const jellyfish::SwimSimulation& s) -> std::string {
    const jellyfish::Jellyfish& j = s.jellyfish();
    trace.t.push_back(s.time_s());
    trace.heading_deg.push_back(heading_deg(j.heading()));
    const std::vector<Vec2> u = j.umbrella_points();
    const Vec2 aperture = 0.5 * (u.front() + u.back());
    trace.bearing_deg.push_back(target ? heading_deg(*target - aperture) : 0.0);
    return {};
  });
  trace.failure = stats.failure;
  trace.wall_seconds = stats.wall_seconds;
  return trace;
}

/// Mean of |a − b| over the samples from index `from` on.
double mean_abs_difference(const std::vector<double>& a, const std::vector<double>& b, std::size_t from) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = from; k < a.size() && k < b.size(); ++k, ++n) sum += std::abs(a[k] - b[k]);
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

double mean_from(const std::vector<double>& a, std::size_t from) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = from; k < a.size(); ++k, ++n) sum += a[k];
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

// The three runs' headings and the targets' bearings over their first n frames (heading.png).
render::ChartSpec heading_chart(const HeadingTrace& to_left, const HeadingTrace& none, const HeadingTrace& to_right,
                                std::size_t n) {
  render::ChartSpec chart;
  chart.title = "Steering toward a target (heading from +y, degrees)";
  chart.x_label = "t";
  chart.x_unit = "s";
  chart.y_label = "heading";
  chart.y_unit = "°";
  auto series = [&](const std::string& label, const std::vector<double>& y) {
    render::Series s;
    s.label = label;
    s.x.assign(none.t.begin(), none.t.begin() + static_cast<std::ptrdiff_t>(n));
    s.y.assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
    return s;
  };
  chart.series = {series("steered left", to_left.heading_deg), series("not steered", none.heading_deg),
                  series("steered right", to_right.heading_deg), series("bearing of left target", to_left.bearing_deg),
                  series("bearing of right target", to_right.bearing_deg)};
  return chart;
}

std::function<Outcome(const io::OutputDir&)> prepare_steering(const Context& ctx) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  if (settings.school.size() != 1)
    throw InputError("experiment steering needs exactly one jellyfish (the [jellyfish] table, no jellyfish objects)");
  const scene::SteeringScene steering = scene::read_steering(ctx.config);
  const Vec2 offset = steering.target_offset;
  const double settle_cycles = steering.settle_cycles;
  return [settings, offset, settle_cycles, ctx](const io::OutputDir& out) {
    const Vec2 start = settings.jellyfish().aperture_centre_m;
    const Vec2 left = start + Vec2{-offset.x, offset.y}, right = start + offset;
    // Three independent runs (left, none, right) as the project's pool's tasks, one per core.
    const std::array<std::optional<Vec2>, 3> targets{left, std::nullopt, right};
    std::array<HeadingTrace, 3> traces;
    WorkerPool pool(std::min(resolve_threads(0), static_cast<int>(targets.size())));
    pool.run_tasks(targets.size(), [&](std::size_t k) { traces[k] = trace_heading(settings, targets[k]); });
    const HeadingTrace& to_left = traces[0];
    const HeadingTrace& none = traces[1];
    const HeadingTrace& to_right = traces[2];

    io::CsvWriter csv({"t", "heading_left", "heading_none", "heading_right", "bearing_left", "bearing_right"});
    const std::size_t n = std::min({none.t.size(), to_left.t.size(), to_right.t.size()});
    for (std::size_t k = 0; k < n; ++k)
      csv.row({none.t[k], to_left.heading_deg[k], none.heading_deg[k], to_right.heading_deg[k], to_left.bearing_deg[k],
               to_right.bearing_deg[k]});
    out.write_text("heading.csv", csv.text());

    out.write_text("heading.png", render::chart_png(heading_chart(to_left, none, to_right, n)));

    // After the settling time: mean heading and mean distance from the target's bearing.
    const double frequency = settings.jellyfish().frequency_hz;
    const auto from = static_cast<std::size_t>(std::lround(settle_cycles / frequency / settings.frame_interval_s));
    nlohmann::ordered_json fig;
    fig["units"] = {{"angle", "degrees"}, {"time", "s"}, {"length", "m"}};
    fig["target_left"] = {left.x, left.y};
    fig["target_right"] = {right.x, right.y};
    fig["settle_cycles"] = settle_cycles;
    fig["initial_bearing_left"] = to_left.bearing_deg.empty() ? 0.0 : to_left.bearing_deg.front();
    auto at_settle = [&](const std::vector<double>& h) { return h.empty() ? 0.0 : h[std::min(from, h.size() - 1)]; };
    fig["heading_at_settle_left"] = at_settle(to_left.heading_deg);
    fig["heading_at_settle_none"] = at_settle(none.heading_deg);
    fig["heading_at_settle_right"] = at_settle(to_right.heading_deg);
    fig["mean_heading_left"] = mean_from(to_left.heading_deg, from);
    fig["mean_heading_none"] = mean_from(none.heading_deg, from);
    fig["mean_heading_right"] = mean_from(to_right.heading_deg, from);
    fig["mean_bearing_error_left"] = mean_abs_difference(to_left.heading_deg, to_left.bearing_deg, from);
    fig["mean_bearing_error_right"] = mean_abs_difference(to_right.heading_deg, to_right.bearing_deg, from);
    fig["final_heading_left"] = to_left.heading_deg.empty() ? 0.0 : to_left.heading_deg.back();
    fig["final_heading_none"] = none.heading_deg.empty() ? 0.0 : none.heading_deg.back();
    fig["final_heading_right"] = to_right.heading_deg.empty() ? 0.0 : to_right.heading_deg.back();
    fig["simulated_seconds"] = settings.duration_s;
    fig["wall_seconds"] = none.wall_seconds + to_left.wall_seconds + to_right.wall_seconds;
    std::string failure = !to_left.failure.empty() ? "steered left: " + to_left.failure
                          : !none.failure.empty()  ? "not steered: " + none.failure
                          : !to_right.failure.empty() ? "steered right: " + to_right.failure : "";
    write_summary(out, "experiment steering", ctx.config, fig, failure);
    return Outcome{failure};
  };
}

// The drag coefficient over time (obstacle-flow's drag.png).
render::ChartSpec drag_chart(const std::vector<double>& t, const std::vector<double>& cd) {
  render::ChartSpec chart;
  chart.title = "Flow past a cylinder: drag coefficient";
  chart.x_label = "t";
  chart.x_unit = "s";
  chart.y_label = "C_D = F / (rho U^2 D / 2)";
  render::Series s;
  s.label = "C_D";
  s.x = t;
  s.y = cd;
  chart.series = {s};
  return chart;
}

std::function<Outcome(const io::OutputDir&)> prepare_obstacle_flow(const Context& ctx) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  if (settings.obstacles.empty()) throw InputError("experiment obstacle-flow needs at least one obstacle in [[objects]]");
  const jellyfish::ObstacleSpec& body = settings.obstacles.front();
  if (body.shape != jellyfish::ObstacleShape::circle)
    throw InputError("experiment obstacle-flow measures a cylinder: objects[0] must be a circle");
  const Vec2 inflow = settings.tank.boundaries.west.velocity_m_per_s;
  if (settings.tank.boundaries.west.type != fluid::BoundaryType::inflow || !(inflow.x > 0))
    throw InputError("experiment obstacle-flow needs tank.boundaries[0] = \"inflow\" with tank.inflow_velocity x > 0");
  return [settings, inflow, ctx](const io::OutputDir& out) {
    const double diameter = 2.0 * settings.obstacles.front().radius_m;
    const double speed = inflow.x;
    const double dynamic = 0.5 * settings.tank.density_kg_per_m3 * speed * speed * diameter;
    jellyfish::SwimSimulation sim(settings);
    io::CsvWriter csv({"t", "force_x", "force_y", "drag_coefficient", "lift_coefficient", "leakage_fraction"});
    std::vector<double> t, cd, leak;
    std::unique_ptr<render::FieldPicture> picture;
    const jellyfish::SwimRunStats stats = sim.run(
        [&](const jellyfish::SwimSimulation& s) -> std::string {
          const Vec2 f = s.obstacle_force(0);
          const double leakage = s.obstacle_leakage(0) / (speed * diameter);
          csv.row({s.time_s(), f.x, f.y, f.x / dynamic, f.y / dynamic, leakage});
          t.push_back(s.time_s());
          cd.push_back(f.x / dynamic);
          leak.push_back(leakage);
          return {};
        },
        ctx.progress);
    out.write_text("forces.csv", csv.text());
    render::FieldPictureOptions po;
    po.quantity = render::FieldQuantity::vorticity;
    const render::FieldPicture p = swim_picture(sim, 0.0);
    out.write_text("flow.png", render::field_png(p, po));
    out.write_text("drag.png", render::chart_png(drag_chart(t, cd)));
    nlohmann::ordered_json fig;
    fig["units"] = {{"force", "N/m"}, {"velocity", "m/s"}, {"length", "m"}};
    fig["reynolds_number"] = speed * diameter / std::max(settings.tank.viscosity_m2_per_s, 1e-12);
    fig["diameter"] = diameter;
    fig["inflow_speed"] = speed;
    fig["blockage"] = diameter / settings.tank.height_m;
    const std::size_t half = cd.size() / 2;
    fig["mean_drag_coefficient"] = mean_from(cd, half);
    fig["mean_leakage_fraction"] = mean_from(leak, half);
    fig["simulated_seconds"] = stats.simulated_seconds;
    fig["wall_seconds"] = stats.wall_seconds;
    fig["steps"] = stats.steps;
    fig["krylov_iterations"] = stats.krylov_iterations;
    write_summary(out, "experiment obstacle-flow", ctx.config, fig, stats.failure);
    return Outcome{stats.failure};
  };
}

}  // namespace

Experiment steering_experiment() {
  Experiment e{"steering", "A jellyfish steered toward a point on its left, not steered, and steered right (beyond §9.2.2)",
               "experiments/steering.toml", prepare_steering};
  e.base_path = "scenes/jellyfish.toml";
  e.base_overlay_path = "scenes/jellyfish-thesis.toml";  // measured on the thesis's tank (docs/scenes.md)
  return e;
}

Experiment obstacle_flow_experiment() {
  Experiment e{"obstacle-flow", "Uniform flow past a fixed cylinder held by the immersed boundary: drag and leakage",
               "experiments/obstacle-flow.toml", prepare_obstacle_flow};
  e.base_path = "scenes/jellyfish.toml";
  return e;
}

}  // namespace jellysim::experiments
