// The thesis's slice in planar water (a plane section of an infinitely deep body, as the thesis
// simulates it) and in axisymmetric water (the meridian of a body of revolution, the water 3D
// around it; issue 22): the same bell, stroke and resolution. Writes comparison.csv, the wakes
// side by side and summary.json.
#include <algorithm>
#include <cmath>

#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/render/field_picture.hpp"
#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/parameters.hpp"

namespace jellysim::experiments {
namespace {


/// The two runs, by their tank.geometry values.
struct GeometryRun {
  const char* name;
};
constexpr GeometryRun kGeometries[] = {{"planar"}, {"axisymmetric"}};

struct Comparison {
  std::array<jellyfish::SwimSettings, 2> settings;
  int cycles = 4;
};

Comparison read_comparison(config::Config c) {
  Comparison run;
  run.cycles = scene::read_axisymmetric_vs_planar_cycles(c);
  const double frequency = scene::Reader(c, scene::jellyfish_scene()).number("jellyfish.frequency");
  c.set("duration=" + config::format_number(run.cycles / frequency));
  for (std::size_t g = 0; g < 2; ++g) {
    c.set(std::string("tank.geometry=\"") + kGeometries[g].name + "\"");
    run.settings[g] = scene::read_swim_settings(c);
    if (run.settings[g].school.size() != 1 || !run.settings[g].obstacles.empty() || !run.settings[g].structures.empty())
      throw InputError("experiment axisymmetric-vs-planar compares one jellyfish: the scene must have exactly one "
                       "jellyfish and no [[objects]]");
  }
  return run;
}

/// What one run gives the comparison.
struct RunResult {
  std::vector<jellyfish::MetricsRow> metrics;
  jellyfish::SwimRunStats stats;
  fluid::FlowState flow;  ///< at the end (the whole tank)
  render::FieldPicture picture;
};

RunResult run_geometry(const jellyfish::SwimSettings& settings, const char* name, const sim::ProgressCallback& progress) {
  jellyfish::SwimSimulation sim(settings);
  std::vector<jellyfish::SliceFrame> frames;
  RunResult r;
  r.stats = sim.run(
      [&](const jellyfish::SwimSimulation& s) -> std::string {
        frames.push_back(s.jellyfish(0).slice_frame(s.time_s()));
        return {};
      },
      progress);
  jellyfish::MetricsSettings ms;
  ms.density_kg_per_m3 = settings.tank.density_kg_per_m3;
  ms.viscosity_m2_per_s = settings.tank.viscosity_m2_per_s;
  r.metrics = jellyfish::compute_metrics(frames, ms);
  r.flow = sim.flow();
  r.picture = swim_picture(sim, 0.0);
  const double d = settings.jellyfish().diameter_m;
  const Vec2 apex = frames.back().umbrella[frames.back().umbrella.size() / 2];
  // The bell and its wake: from five diameters below the apex to one above (moved into the tank),
  // the tank's width.
  const double height = std::min(6.0 * d, settings.tank.height_m);
  const double bottom = std::clamp(apex.y - 5.0 * d, 0.0, settings.tank.height_m - height);
  r.picture.view_m = std::array<Vec2, 2>{Vec2{0.0, bottom}, Vec2{settings.tank.width_m, bottom + height}};
  char caption[96];
  std::snprintf(caption, sizeof caption, "%s, t = %.2f s", name, sim.time_s());
  r.picture.caption = caption;
  return r;
}

/// Position along the axis at the end of cycle k (the recorded frame nearest k / f).
double position_after(const std::vector<jellyfish::MetricsRow>& m, int k, double frequency_hz) {
  const double t = k / frequency_hz;
  const auto nearest = std::min_element(m.begin(), m.end(), [t](const auto& a, const auto& b) {
    return std::abs(a.t - t) < std::abs(b.t - t);
  });
  return nearest->position;
}

// wakes.png: the vorticity at the end of each run, side by side on one colour scale.
void write_wakes_picture(const io::OutputDir& out, std::vector<RunResult>& results) {
  std::vector<render::FieldPicture> panels;
  for (RunResult& r : results) {
    r.picture.state = &r.flow;
    panels.push_back(r.picture);
  }
  write_vorticity_panels(out, "wakes.png", panels);
}

std::function<Outcome(const io::OutputDir&)> prepare_axisymmetric_vs_planar(const Context& ctx) {
  const Comparison run = read_comparison(ctx.config);
  return [run, ctx](const io::OutputDir& out) {
    io::CsvWriter csv({"geometry", "distance_per_cycle_bell_diameters", "first_cycle_bell_diameters",
                       "peak_speed_m_per_s", "mean_speed_m_per_s", "cavity_volume_ratio", "distance_m", "steps"});
    nlohmann::ordered_json fig;
    fig["units"] = {{"length", "m"}, {"time", "s"}, {"speed", "m/s"}};
    fig["cycles"] = run.cycles;
    fig["cells"] = {run.settings[0].tank.cells_x, run.settings[0].tank.cells_y};
    std::vector<RunResult> results;
    std::string failure;
    std::array<double, 2> per_cycle{}, peak{}, volume_ratio{}, cost{};
    for (std::size_t g = 0; g < 2 && failure.empty(); ++g) {
      const jellyfish::SwimSettings& s = run.settings[g];
      results.push_back(run_geometry(s, kGeometries[g].name, ctx.progress));
      const RunResult& r = results.back();
      const double d = s.jellyfish().diameter_m, f = s.jellyfish().frequency_hz;
      const int done = static_cast<int>(std::floor(r.stats.simulated_seconds * f + 1e-9));
      if (!r.stats.failure.empty()) failure = std::string(kGeometries[g].name) + ": " + r.stats.failure;
      if (done < 2) continue;
      // The periodic state: cycles 2 to the last (the first starts from rest).
      const double first = position_after(r.metrics, 1, f);
      per_cycle[g] = (position_after(r.metrics, done, f) - first) / (done - 1) / d;
      volume_ratio[g] = 1.0;  // the smallest cavity volume over the rest volume
      for (const jellyfish::MetricsRow& m : r.metrics) {
        peak[g] = std::max(peak[g], m.velocity);
        volume_ratio[g] = std::min(volume_ratio[g], m.volume_ratio);
      }
      const double mean_speed = r.metrics.back().position / r.metrics.back().t;
      cost[g] = r.stats.wall_seconds / r.stats.simulated_seconds;
      csv.row(kGeometries[g].name, {per_cycle[g], first / d, peak[g], mean_speed, volume_ratio[g],
                                    r.metrics.back().position, static_cast<double>(r.stats.steps)});
      nlohmann::ordered_json one;
      one["distance_per_cycle_bell_diameters"] = per_cycle[g];
      one["first_cycle_bell_diameters"] = first / d;
      one["peak_speed_m_per_s"] = peak[g];
      one["mean_speed_m_per_s"] = mean_speed;
      one["cavity_volume_ratio"] = volume_ratio[g];
      one["distance_m"] = r.metrics.back().position;
      one["steps"] = r.stats.steps;
      one["krylov_iterations"] = r.stats.krylov_iterations;
      one["wall_seconds_per_simulated_second"] = cost[g];
      one["wall_seconds_per_step"] = r.stats.steps > 0 ? r.stats.wall_seconds / static_cast<double>(r.stats.steps) : 0.0;
      fig[kGeometries[g].name] = one;
    }
    out.write_text("comparison.csv", csv.text());
    if (results.size() == 2 && failure.empty()) {
      fig["distance_ratio"] = per_cycle[0] > 0 ? per_cycle[1] / per_cycle[0] : 0.0;
      fig["cost_ratio"] = cost[0] > 0 ? cost[1] / cost[0] : 0.0;  // per simulated second (the faster bell takes more steps)
      fig["cost_per_step_ratio"] = fig["axisymmetric"]["wall_seconds_per_step"].get<double>() /
                                   std::max(fig["planar"]["wall_seconds_per_step"].get<double>(), 1e-300);
    }
    write_wakes_picture(out, results);
    write_summary(out, "experiment axisymmetric-vs-planar", ctx.config, fig, failure);
    return Outcome{failure};
  };
}

}  // namespace

Experiment axisymmetric_vs_planar_experiment() {
  Experiment e{"axisymmetric-vs-planar",
               "the same bell and stroke in planar and in axisymmetric water: distance, speed, cavity volume, wakes",
               "experiments/axisymmetric-vs-planar.toml", prepare_axisymmetric_vs_planar};
  e.base_path = "scenes/jellyfish.toml";
  e.shorthands = {"cycles"};
  return e;
}

}  // namespace jellysim::experiments
