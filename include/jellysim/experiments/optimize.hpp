#pragma once
// `jellysim optimize PLAN.toml --out DIR` (issue 37, docs/control.md): the muscle control found by
// search. A plan names a jellyfish scene, design variables (scene keys with bounds), an objective
// computed from the swim (stroke_figures), constraints on those figures, an NLopt algorithm, a
// budget and a seed. Every evaluation is a `jellysim simulate` of the scene with the variables set,
// resolved by scene::resolve_config and run in-process; evaluations.csv, best.toml, progress.png and
// summary.json are written, and a killed run resumes from evaluations.csv.
#include "jellysim/config/config.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/math/vec2.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace jellysim::experiments {

/// A design variable: a numeric scene key and its bounds.
struct DesignVariable {
  std::string key;
  double lower = 0.0, upper = 0.0;
};

/// A constraint: a figure of stroke_figures kept in [lower, upper] (either may be infinite).
struct FigureBound {
  std::string figure;
  double lower = 0.0, upper = 0.0;
};

/// A plan as read and checked (docs/control.md, "The plan").
struct OptimizePlan {
  std::filesystem::path file;
  std::filesystem::path scene;          ///< empty: the built-in scene
  std::optional<double> cycles;         ///< simulated cycles (duration = cycles / frequency) ...
  std::optional<double> duration;       ///< ... or seconds
  std::vector<std::string> objectives;  ///< one, or two for the Pareto sweep
  bool maximize = true;                 ///< sense of objectives[0] (the Pareto sweep: per objective, see docs)
  std::string algorithm = "bobyqa";
  int evaluations = 40;                 ///< budget per optimisation
  int seed = 1;
  int threads = 0;                      ///< the Pareto sweep's sub-problems at a time (0: one per core)
  int pareto_points = 5;                ///< weights of the Pareto sweep
  std::vector<std::string> shared;      ///< [set]: key=value for every evaluation
  std::vector<DesignVariable> variables;
  std::vector<FigureBound> constraints;
  std::optional<Vec2> target;           ///< [target] position (m)
  double target_time_s = 0.0;           ///< [target] time (s)
};

/// The objectives, in the plan's names.
const std::vector<std::string>& objective_names();
/// The figures stroke_figures computes (objectives and constraint figures).
const std::vector<std::string>& stroke_figure_names();

/// Parses a plan; throws InputError naming the file (and line where the TOML reader gives one),
/// the field and the allowed values.
OptimizePlan parse_optimize_plan(std::string_view text, const std::filesystem::path& file);
OptimizePlan read_optimize_plan(const std::filesystem::path& file);

/// The figures of one swim (docs/control.md, "Objectives"): distance_per_cycle, speed,
/// cost_of_transport, efficiency, reach (when a target is given), muscle_work, peak_muscle_tension,
/// min_volume_ratio, min_aperture_ratio, distance_travelled.
std::map<std::string, double> stroke_figures(const jellyfish::SwimSettings& settings, const SwimRecording& rec,
                                             const std::optional<Vec2>& target, double target_time_s);

/// One evaluation's result: its figures (empty when it failed) and why it failed.
struct Evaluation {
  std::map<std::string, double> figures;
  bool failed = false;
};

/// Evaluates a resolved configuration. The command's is evaluate_swim; tests pass a cheap one.
using Evaluator = std::function<Evaluation(const config::Config&)>;
/// Told after each evaluation of a single-objective search: evaluations done, the budget.
using EvaluationProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Runs the swim of a resolved jellyfish configuration (as `simulate` would, without files) and
/// measures it; a run that fails (blow-up) is a failed evaluation.
Evaluation evaluate_swim(const config::Config& config, const std::optional<Vec2>& target, double target_time_s);

/// The configuration of one evaluation: the built-in scene, the plan's scene, [set], the variables'
/// values and the duration (cycles / frequency). Throws InputError as resolve_config does.
config::Config evaluation_config(const OptimizePlan& plan, const std::vector<double>& x);

/// Checks the plan against the scene: every variable a number the scene reads, the evaluations at
/// both corners of the box valid as `simulate` would check them, the algorithm able to take the
/// variables. Throws InputError naming the plan and field; run_optimize calls it first.
void validate_plan_against_scene(const OptimizePlan& plan);

/// Checks the plan against the scene (every variable a number the scene reads, both bounds
/// accepted, the duration), then runs it into `out`: evaluations.csv (resumed from when present),
/// best.toml, progress.png, summary.json (and pareto.csv, pareto.png for two objectives). Throws
/// InputError before anything is written. Returns summary.json's figures. `progress` hears each
/// evaluation of a single-objective search (`--progress json`; the Pareto sweep's run on threads and
/// report only their end).
nlohmann::ordered_json run_optimize(const OptimizePlan& plan, const std::filesystem::path& out, bool quiet,
                                    const Evaluator& evaluator = {}, const EvaluationProgress& progress = {});

/// The Pareto sweep of a two-objective plan (docs/control.md, "Pareto front") as independent
/// sub-problems, one per weight, for a backend that solves them where it likes: run_optimize's
/// threads, or the MPI ranks of `jellysim optimize` under mpirun. Every rank builds the sweep from
/// the plan (the baseline evaluated once per rank, the earlier run's evaluations.csv read for the
/// resume); a sub-problem's rows travel as evaluations.csv text; only the rank that opened the
/// output writes files, in sub-problem order, so every backend writes the same bytes.
class ParetoSweep {
 public:
  ParetoSweep(const OptimizePlan& plan, const std::filesystem::path& out, bool quiet, const Evaluator& evaluator = {});
  ~ParetoSweep();
  ParetoSweep(const ParetoSweep&) = delete;
  ParetoSweep& operator=(const ParetoSweep&) = delete;

  /// The sub-problems (the plan's pareto_points).
  std::size_t size() const;
  /// The weight of objectives[0] in sub-problem k.
  double weight(std::size_t k) const;
  /// Creates the output directory: from now on each evaluation here rewrites evaluations.csv.
  void open_output();
  /// Solves sub-problem k here (one NLopt search); returns its rows as evaluations.csv text.
  std::string solve(std::size_t k);
  /// Sub-problem k's rows solved elsewhere (solve's text); rewrites evaluations.csv.
  void accept(std::size_t k, const std::string& rows);
  /// Evaluations in sub-problem k so far.
  std::size_t evaluations(std::size_t k) const;
  /// Writes evaluations.csv, pareto.csv, pareto.png, best.toml and summary.json (with `engine`,
  /// e.g. "threads: 2"); returns summary.json's figures.
  nlohmann::ordered_json finish(const std::string& engine, double wall_seconds);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace jellysim::experiments
