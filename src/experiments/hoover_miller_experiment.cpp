// The Hoover–Miller jellyfish bell as IB2d ships it (docs/ib2d.md): IB2d's convergence example
// (Battista & Mizuhara 2019) at a Reynolds number and resolution, run with our semi-implicit
// coupling. Writes the bell's trajectory, its displacement per cycle and the cost per simulated
// second, and the vorticity around the bell at the end of each contraction.
#include <cmath>

#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/jellyfish/hoover_miller.hpp"
#include "jellysim/render/field_picture.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace jellysim::experiments {
namespace {


/// The experiment's scene: the definition's tank, coupling and schedule with the cells, viscosity
/// and duration set from `re`, `grid` and `cycles` (the bell is generated at the tank's resolution).
struct HooverMillerRun {
  jellyfish::SwimSettings settings;
  jellyfish::HooverMillerBell bell;
  double re = 150.0;
  int grid = 256;
  int cycles = 3;
  std::string muscles = "ib2d";  ///< "ib2d" (IB2d's fixed muscle stiffness) or "per-length" (the consistent variant)
};

HooverMillerRun read_hoover_miller(config::Config c) {
  HooverMillerRun run;
  const scene::HooverMillerFields fields = scene::read_hoover_miller_fields(c);
  run.re = fields.re;
  run.grid = fields.grid;
  run.cycles = fields.cycles;
  jellyfish::HooverMillerSpec spec;
  spec.resolution = run.grid;
  run.muscles = fields.muscles;
  spec.muscles_per_length = run.muscles == "per-length";
  run.bell = jellyfish::hoover_miller_bell(spec);
  c.set("duration=" + std::to_string(run.cycles));
  c.set("tank.cells=[" + std::to_string(spec.cells_x()) + ", " + std::to_string(spec.cells_y()) + "]");
  c.set("tank.viscosity=" + config::format_number(1.0 / run.re));  // μ = 1000/Re Pa·s, ρ = 1000 kg/m³
  run.settings = scene::read_swim_settings(c);
  if (run.settings.structures.size() != 1 || !run.settings.school.empty() || !run.settings.obstacles.empty())
    throw InputError("experiment hoover-miller needs exactly one object, of type \"ib2d\" (the bell), and no jellyfish");
  // The consistent variant's bell: the same points, springs and schedule rows, its muscles per length.
  if (spec.muscles_per_length) run.settings.structures[0].structure = run.bell.structure;
  return run;
}

/// The picture of the bell (its springs; muscles thin) and the vorticity around it.
render::FieldPicture bell_picture(const jellyfish::SwimSimulation& sim, const HooverMillerRun& run, Vec2 centre) {
  render::FieldPicture p = swim_picture(sim, 0.0);
  p.view_m = std::array<Vec2, 2>{Vec2{0.0, centre.y - 1.5}, Vec2{run.settings.tank.width_m, centre.y + 2.5}};
  return p;
}

/// strokes.png: the vorticity at the end of each contraction, one panel per stroke on one scale.
void write_strokes_picture(const io::OutputDir& out, std::vector<render::FieldPicture>& strokes,
                           const std::vector<fluid::FlowState>& stroke_flows) {
  for (std::size_t k = 0; k < strokes.size(); ++k) strokes[k].state = &stroke_flows[k];
  write_vorticity_panels(out, "strokes.png", strokes);
}

/// The centroid's height from its start and the margin gap over time (trajectory.png).
render::ChartSpec trajectory_chart(const std::vector<double>& t, const std::vector<double>& centroid_y,
                                   const std::vector<double>& gap) {
  render::ChartSpec chart;
  chart.title = "Hoover-Miller bell: centroid height and margin gap";
  chart.x_label = "t";
  chart.x_unit = "s";
  chart.y_label = "m";
  render::Series sy, sg;
  sy.label = "centroid y - start";
  sy.x = t;
  for (double y : centroid_y) sy.y.push_back(y - (centroid_y.empty() ? 0.0 : centroid_y.front()));
  sg.label = "margin gap";
  sg.x = t;
  sg.y = gap;
  chart.series = {sy, sg};
  return chart;
}

/// summary.json's figures: the run, the swim per cycle (jellyfish::cycle_displacements), the margin gap and the cost.
nlohmann::ordered_json hoover_miller_figures(const HooverMillerRun& run, const std::vector<double>& per_cycle,
                                             const std::vector<double>& gap, const jellyfish::SwimRunStats& stats) {
  nlohmann::ordered_json fig;
  fig["units"] = {{"length", "m"}, {"time", "s"}};
  fig["re"] = run.re;
  fig["grid"] = run.grid;
  fig["muscles"] = run.muscles;
  fig["cells"] = {run.settings.tank.cells_x, run.settings.tank.cells_y};
  fig["markers"] = run.bell.structure.vertices.size();
  fig["cycle_displacements_m"] = per_cycle;
  fig["displacement_per_cycle_m"] = jellyfish::later_cycle_displacement(per_cycle);
  fig["margin_gap_min_m"] = gap.empty() ? 0.0 : *std::min_element(gap.begin(), gap.end());
  fig["margin_gap_max_m"] = gap.empty() ? 0.0 : *std::max_element(gap.begin(), gap.end());
  fig["wall_seconds_per_simulated_second"] =
      stats.simulated_seconds > 0 ? stats.wall_seconds / stats.simulated_seconds : 0.0;
  fig["dt_s"] = stats.steps > 0 ? stats.simulated_seconds / static_cast<double>(stats.steps) : 0.0;
  fig["dt_min_s"] = stats.smallest_step_s;
  fig["dt_max_s"] = stats.largest_step_s;
  fig["steps"] = stats.steps;
  fig["krylov_iterations"] = stats.krylov_iterations;
  fig["simulated_seconds"] = stats.simulated_seconds;
  fig["wall_seconds"] = stats.wall_seconds;
  return fig;
}

std::function<Outcome(const io::OutputDir&)> prepare_hoover_miller(const Context& ctx) {
  const HooverMillerRun run = read_hoover_miller(ctx.config);
  return [run, ctx](const io::OutputDir& out) {
    jellyfish::SwimSimulation sim(run.settings);
    const jellyfish::Ib2dParts& parts = sim.structure(0);
    const int n = run.bell.bell_points;
    const int west_margin = (n + 1) / 2 - 1, east_margin = n - 1;
    io::CsvWriter csv({"t", "centroid_y", "centroid_x", "margin_gap"});
    std::vector<double> t, centroid_y, gap;
    std::vector<fluid::FlowState> stroke_flows;
    std::vector<render::FieldPicture> strokes;
    int next_stroke = 0;
    const double half_frame = 0.5 * run.settings.frame_interval_s;
    const jellyfish::SwimRunStats stats = sim.run(
        [&](const jellyfish::SwimSimulation& s) -> std::string {
          const elastic::Body& b = s.body();
          const Vec2 c = s.structure_centroid(0);
          const double g = norm(b.points.position[static_cast<std::size_t>(parts.first_point + east_margin)] -
                                b.points.position[static_cast<std::size_t>(parts.first_point + west_margin)]);
          csv.row({s.time_s(), c.y, c.x, g});
          t.push_back(s.time_s());
          centroid_y.push_back(c.y);
          gap.push_back(g);
          // The end of each contraction: the muscles' rest length |cos(π t)| is 0 at t = k + ½.
          if (next_stroke < run.cycles && std::abs(s.time_s() - (next_stroke + 0.5)) <= half_frame) {
            render::FieldPicture p = bell_picture(s, run, c);
            stroke_flows.push_back(s.flow());
            char caption[96];
            std::snprintf(caption, sizeof caption, "Re %g, N %d, t = %.2f s", run.re, run.grid, s.time_s());
            p.caption = caption;
            strokes.push_back(p);
            ++next_stroke;
          }
          return {};
        },
        ctx.progress);
    out.write_text("trajectory.csv", csv.text());

    write_strokes_picture(out, strokes, stroke_flows);

    const std::vector<double> per_cycle = jellyfish::cycle_displacements(t, centroid_y, run.cycles, half_frame);

    if (!t.empty()) out.write_text("trajectory.png", render::chart_png(trajectory_chart(t, centroid_y, gap)));

    const nlohmann::ordered_json fig = hoover_miller_figures(run, per_cycle, gap, stats);
    write_summary(out, "experiment hoover-miller", ctx.config, fig, stats.failure);
    return Outcome{stats.failure};
  };
}

}  // namespace

Experiment hoover_miller_experiment() {
  Experiment e{"hoover-miller",
               "IB2d's Hoover-Miller jellyfish bell (its convergence example) with our coupling: swimming and cost",
               "experiments/hoover-miller.toml", prepare_hoover_miller};
  e.base_path = "scenes/jellyfish.toml";
  e.shorthands = {"re", "grid", "cycles"};
  return e;
}

}  // namespace jellysim::experiments
