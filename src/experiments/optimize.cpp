// `jellysim optimize` (issue 37, docs/control.md): NLopt searching the design variables of a plan,
// each evaluation a swim of the scene resolved by scene::resolve_config; the evaluations recorded
// in evaluations.csv as they come (a rerun replays them from the file: NLopt is deterministic given
// the seed, so the replayed path is the same), then best.toml, progress.png and summary.json.
#include "jellysim/experiments/optimize.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/resolve.hpp"
#include "optimize_search.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

namespace jellysim::experiments {
namespace fs = std::filesystem;

config::Config evaluation_config(const OptimizePlan& plan, const std::vector<double>& x) {
  scene::ConfigSources sources{{}, plan.scene.string(), "jellyfish", true};
  if (!plan.scene.empty()) sources.scene_file = config::Config::load(plan.scene);
  sources.sets = plan.shared;
  // Evaluations write no frame files; best.toml says so too, so that `simulate best.toml` repeats
  // the evaluation's steps exactly.
  sources.sets.push_back("output.pictures=false");
  sources.sets.push_back("output.vtk=false");
  for (std::size_t i = 0; i < x.size() && i < plan.variables.size(); ++i)
    sources.sets.push_back(plan.variables[i].key + "=" + io::format_double(x[i]));
  const config::Config base = scene::builtin_jellyfish_scene();
  double duration = plan.duration.value_or(plan.target_time_s);
  if (plan.cycles) {
    const config::Config resolved = scene::resolve_config(base, sources, "the jellyfish scene");
    const double frequency = resolved.number("jellyfish.frequency");
    if (!(frequency > 0)) throw InputError("field 'cycles' needs jellyfish.frequency > 0");
    // One frame beyond the last cycle: the run's last frame lies on the frame clock, which may stop
    // short of cycles / f; the figures count the whole cycles recorded (stroke_figures).
    duration = *plan.cycles / frequency + resolved.number("output.frame_interval");
  }
  sources.sets.push_back("duration=" + io::format_double(duration));
  return scene::resolve_config(base, sources, "the jellyfish scene");
}

/// The scene's own values of the variables (the baseline stroke).
std::vector<double> scene_values(const OptimizePlan& plan) {
  const config::Config c = evaluation_config(plan, {});
  std::vector<double> x;
  for (const DesignVariable& v : plan.variables) {
    if (!c.has(v.key)) throw InputError(plan.file.string() + ": variables." + v.key + ": the scene has no such key");
    try {
      x.push_back(c.number(v.key));
    } catch (const InputError&) {
      throw InputError(plan.file.string() + ": variables." + v.key + ": not a number in the scene (" + c.literal(v.key) + ")");
    }
  }
  return x;
}

void validate_plan_against_scene(const OptimizePlan& plan) {
  scene_values(plan);  // every variable a number of the scene
  for (const bool upper : {false, true}) {
    std::vector<double> x;
    for (const DesignVariable& v : plan.variables) x.push_back(upper ? v.upper : v.lower);
    try {
      find_experiment("jellyfish").prepare(Context{evaluation_config(plan, x), {}});
    } catch (const InputError& e) {
      throw InputError(plan.file.string() + ": the variables at their " + (upper ? "upper" : "lower") +
                       " bounds: " + e.what());
    }
  }
  if (plan.algorithm == "bobyqa" && plan.variables.size() < 2)
    throw InputError(plan.file.string() + ": field 'algorithm' = \"bobyqa\" needs at least 2 variables (use cobyla, "
                     "sbplx or direct for one)");
}

namespace {

void write_progress_png(const OptimizeRun& run, const io::OutputDir& out, const std::string& objective) {
  render::Series all{"evaluations", {}, {}, true, false};
  render::Series best{"best so far (feasible)", {}, {}, false, true};
  double best_value = NAN;
  for (const SearchRow& r : run.rows) {
    if (r.failed || !std::isfinite(r.objective)) continue;
    all.x.push_back(static_cast<double>(r.evaluation));
    all.y.push_back(r.objective);
    if (r.feasible && (std::isnan(best_value) || run.better(r.objective, best_value))) best_value = r.objective;
    if (!std::isnan(best_value)) {
      best.x.push_back(static_cast<double>(r.evaluation));
      best.y.push_back(best_value);
    }
  }
  render::ChartSpec chart;
  chart.title = "optimize: " + objective + " (" + run.plan.algorithm + ")";
  chart.x_label = "evaluation";
  chart.y_label = objective;
  chart.y_unit = objective_unit(objective);
  chart.series = {all, best};
  out.write_text("progress.png", render::chart_png(chart));
}

}  // namespace

nlohmann::ordered_json optimize_summary(const OptimizeRun& run, double wall_seconds) {
  nlohmann::ordered_json j;
  const SearchRow* best = run.best();
  j["objective"] = run.plan.objectives[0];
  j["sense"] = run.plan.maximize ? "maximize" : "minimize";
  j["algorithm"] = run.plan.algorithm;
  j["seed"] = run.plan.seed;
  j["baseline_objective"] = run.rows.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(run.rows[0].objective);
  j["best_objective"] = best ? nlohmann::ordered_json(best->objective) : nlohmann::ordered_json();
  j["best_evaluation"] = best ? best->evaluation : -1;
  j["best_feasible"] = best && best->feasible;
  nlohmann::ordered_json vars = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < run.plan.variables.size() && best; ++i) vars[run.plan.variables[i].key] = best->x[i];
  j["best_variables"] = vars;
  nlohmann::ordered_json baseline_vars = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < run.plan.variables.size() && !run.rows.empty(); ++i)
    baseline_vars[run.plan.variables[i].key] = run.rows[0].x[i];
  j["baseline_variables"] = baseline_vars;
  j["evaluations"] = run.rows.size();
  j["replayed_evaluations"] = run.replayed;
  j["failed_evaluations"] = std::count_if(run.rows.begin(), run.rows.end(), [](const SearchRow& r) { return r.failed; });
  j["nlopt_result"] = run.result;
  j["wall_seconds"] = wall_seconds;
  return j;
}

nlohmann::ordered_json run_optimize(const OptimizePlan& plan, const fs::path& out_path, bool quiet,
                                    const Evaluator& evaluator, const EvaluationProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  validate_plan_against_scene(plan);
  if (plan.objectives.size() == 2) return run_pareto(plan, out_path, quiet, evaluator ? evaluator : swim_evaluator(plan));
  OptimizeRun run(plan, evaluator ? evaluator : swim_evaluator(plan), quiet);
  run.previous = read_evaluations_csv(out_path / "evaluations.csv", run.columns(), plan.variables.size());
  const io::OutputDir out = io::OutputDir::for_run(out_path, "optimize");
  run.out = &out;
  run.on_evaluation = progress;
  run.search(scene_values(plan));
  const SearchRow* best = run.best();
  if (best) out.write_text("best.toml", evaluation_config(plan, best->x).to_toml());
  write_progress_png(run, out, plan.objectives[0]);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::ordered_json figures = optimize_summary(run, wall);
  write_summary(out, "optimize", evaluation_config(plan, run.rows.empty() ? std::vector<double>{} : run.rows[0].x),
                figures, "");
  out.finish_manifest();
  return figures;
}

}  // namespace jellysim::experiments
