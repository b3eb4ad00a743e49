// `jellysim experiment 3d-vs-axisymmetric` (issue 40 part 4's check; docs/three-d.md "Against the
// axisymmetric solver"): the 3D scene's bell (the shell in 3D water, symmetric stroke) and the same
// bell as the axisymmetric solver's ring slice, at equal resolution: the tank's x–y section as the
// axisymmetric tank, the same cells along x and y, the same frames
// (scene::axisymmetric_counterpart). Each run's displacement per cycle (the 3D bell's surface
// centroid along its axis; the slice's centroid along its axis, the convergence study's figure),
// their ratios, and whether the distance per cycle agrees within 15 %. Writes comparison.csv and
// summary.json.
#include <cmath>

#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/scene/resolve.hpp"
#include "jellyfish_3d.hpp"

namespace jellysim::experiments {
namespace {

constexpr double kAgreement = 0.15;  ///< the issue's tolerance on the distance per cycle

struct Comparison3d {
  scene::Swim3dSettings three_d;
  jellyfish::SwimSettings axisymmetric;
};

Comparison3d read_comparison_3d(const config::Config& c) {
  if (!scene::is_3d_scene(c))
    throw InputError("experiment 3d-vs-axisymmetric: field 'tank.geometry' must be \"3d\" (the 3D scene, "
                     "scenes/jellyfish-3d.toml, is its base)");
  Comparison3d r{scene::read_swim3d_settings(c), {}};
  if (r.three_d.spec.bell.pacemaker)
    throw InputError("experiment 3d-vs-axisymmetric: field 'jellyfish.pacemaker' must be false (the axisymmetric "
                     "bell strokes symmetrically)");
  r.axisymmetric = read_swim_settings(scene::axisymmetric_counterpart(c, scene::builtin_jellyfish_scene()));
  return r;
}

/// One run's swimming: the displacement over each cycle and the mean after the first.
struct Swum {
  std::vector<double> cycles_m;
  double first_cycle_m = NAN, distance_per_cycle_m = NAN, wall_seconds = 0.0;
  std::string failure;
};

void finish(Swum& s) {
  if (s.cycles_m.empty()) return;
  s.first_cycle_m = s.cycles_m.front();
  if (s.cycles_m.size() < 2) return;
  double later = 0.0;
  for (std::size_t k = 1; k < s.cycles_m.size(); ++k) later += s.cycles_m[k];
  s.distance_per_cycle_m = later / static_cast<double>(s.cycles_m.size() - 1);
}

Swum swim_3d(const scene::Swim3dSettings& s, const io::OutputDir& out, const sim::ProgressCallback& progress) {
  const Recording3d rec = run_3d(s, out, progress);
  Swum r;
  r.cycles_m = swim3d::summarize(rec.frames, s.spec.frames_per_cycle).cycle_distance_m;
  r.wall_seconds = rec.wall_seconds;
  r.failure = rec.failure;
  finish(r);
  return r;
}

/// The slice's centroid along its axis at every cycle's end (frames frames_per_cycle apart).
Swum swim_axisymmetric(const jellyfish::SwimSettings& s, int frames_per_cycle, const sim::ProgressCallback& progress) {
  const SwimRecording rec = run_swim(s, {}, nullptr, progress);
  Swum r;
  const auto per = static_cast<std::size_t>(frames_per_cycle);
  for (std::size_t end = per; end < rec.metrics.size(); end += per)
    r.cycles_m.push_back(rec.metrics[end].position - rec.metrics[end - per].position);
  r.wall_seconds = rec.stats.wall_seconds;
  r.failure = rec.stats.failure;
  finish(r);
  return r;
}

nlohmann::ordered_json run_json(const Swum& s) {
  const auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
  return {{"first_cycle_m", number(s.first_cycle_m)}, {"distance_per_cycle_m", number(s.distance_per_cycle_m)},
          {"cycle_displacements_m", s.cycles_m}, {"wall_seconds", s.wall_seconds}};
}

/// The figures: both runs, the ratios 3D / axisymmetric and the verdict on the distance per cycle.
nlohmann::ordered_json comparison_json(const Comparison3d& c, const Swum& three_d, const Swum& axi) {
  const swim3d::Swim3dSpec& spec = c.three_d.spec;
  const double cell = spec.tank_size_m[0] / spec.cells[0];
  nlohmann::ordered_json j;
  j["units"] = {{"length", "m"}, {"time", "s"}};
  j["cells_across_bell"] = spec.bell.slice.diameter_m / cell;
  j["tank_cells_3d"] = spec.cells;
  j["cells_axisymmetric"] = {c.axisymmetric.tank.cells_x, c.axisymmetric.tank.cells_y};
  j["3d"] = run_json(three_d);
  j["axisymmetric"] = run_json(axi);
  const double first = three_d.first_cycle_m / axi.first_cycle_m;
  const double later = three_d.distance_per_cycle_m / axi.distance_per_cycle_m;
  j["first_cycle_ratio"] = std::isfinite(first) ? nlohmann::ordered_json(first) : nullptr;
  j["distance_per_cycle_ratio"] = std::isfinite(later) ? nlohmann::ordered_json(later) : nullptr;
  j["tolerance"] = kAgreement;
  j["distance_per_cycle_within_tolerance"] =
      std::isfinite(later) ? nlohmann::ordered_json(std::abs(later - 1.0) <= kAgreement) : nullptr;
  return j;
}

std::function<Outcome(const io::OutputDir&)> prepare_3d_vs_axisymmetric(const Context& ctx) {
  const Comparison3d c = read_comparison_3d(ctx.config);
  return [c, ctx](const io::OutputDir& out) {
    const Swum three_d = swim_3d(c.three_d, out, ctx.progress);
    const Swum axi = swim_axisymmetric(c.axisymmetric, c.three_d.spec.frames_per_cycle, ctx.progress);
    io::CsvWriter csv({"geometry", "cycle", "displacement_m"});
    for (std::size_t k = 0; k < three_d.cycles_m.size(); ++k) csv.row("3d", {static_cast<double>(k + 1), three_d.cycles_m[k]});
    for (std::size_t k = 0; k < axi.cycles_m.size(); ++k) csv.row("axisymmetric", {static_cast<double>(k + 1), axi.cycles_m[k]});
    out.write_text("comparison.csv", csv.text());
    const std::string failure = !three_d.failure.empty() ? "3d: " + three_d.failure
                                : !axi.failure.empty()   ? "axisymmetric: " + axi.failure
                                                         : "";
    write_summary(out, "experiment 3d-vs-axisymmetric", ctx.config, comparison_json(c, three_d, axi), failure);
    return Outcome{failure};
  };
}

}  // namespace

Experiment three_d_vs_axisymmetric_experiment() {
  Experiment e{"3d-vs-axisymmetric",
               "the 3D scene's shell bell against the axisymmetric solver's ring bell at equal resolution: distance "
               "per cycle and first cycle, their ratios (issue 40's 15 % check)",
               "experiments/3d-vs-axisymmetric.toml", prepare_3d_vs_axisymmetric};
  e.base_path = "scenes/jellyfish.toml";
  e.base_overlay_path = "scenes/jellyfish-3d.toml";  // the 3D scene, an overlay of the built-in one
  return e;
}

}  // namespace jellysim::experiments
