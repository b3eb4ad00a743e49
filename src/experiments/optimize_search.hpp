#pragma once
// The search of `jellysim optimize` (optimize_search.cpp): one NLopt run over a plan's variables,
// its evaluations as rows of evaluations.csv, replayed from an earlier run's file when resuming.
#include "jellysim/experiments/optimize.hpp"
#include "jellysim/io/output.hpp"

#include <mutex>

namespace jellysim::experiments {

/// One evaluation as a row of evaluations.csv.
struct SearchRow {
  int evaluation = 0;
  double weight = -1.0;             ///< the Pareto sweep's weight of objectives[0]; −1: single objective
  std::vector<double> x;            ///< the variables
  std::vector<double> objectives;   ///< the plan's objectives (one or two)
  std::vector<double> constraints;  ///< per [constraints] figure
  bool failed = false;
  bool feasible = false;            ///< not failed, every constraint within its bounds
  double objective = 0.0;           ///< objectives[0], or the Pareto sweep's scalarised objective
  double minimised = 0.0;           ///< what NLopt minimises (sense, penalties)
};

/// One optimisation: NLopt from x0 over the plan's box, evaluations recorded as they come.
class OptimizeRun {
 public:
  OptimizeRun(const OptimizePlan& plan, Evaluator evaluator, bool quiet) : plan(plan), evaluator_(std::move(evaluator)), quiet_(quiet) {}

  const OptimizePlan& plan;
  std::vector<SearchRow> rows;
  std::vector<SearchRow> previous;  ///< an earlier run's rows, replayed while they match
  const io::OutputDir* out = nullptr;
  std::size_t replayed = 0;
  std::string result;               ///< NLopt's result code (its name)
  double weight = -1.0;             ///< Pareto: the weight of objectives[0] (with baseline scales)
  std::vector<double> scales{1.0, 1.0};
  int budget = 0;                   ///< evaluations (0: plan.evaluations)
  /// Pareto: called after each evaluation instead of writing evaluations.csv itself.
  std::function<void()> on_row;
  /// `--progress json`: called after each evaluation with the count done and the budget.
  EvaluationProgress on_evaluation;

  /// evaluations.csv's columns for this plan.
  std::vector<std::string> columns() const;
  /// Evaluates x0 (the baseline), then lets NLopt search.
  void search(const std::vector<double>& x0);
  /// The best feasible row (or, when none is, the one NLopt found least bad); null when none.
  const SearchRow* best() const;
  /// True when objective a is better than b in the plan's sense.
  bool better(double a, double b) const { return plan.maximize ? a > b : a < b; }
  /// The row at x: found again, replayed from `previous`, or evaluated now.
  const SearchRow& evaluate(const std::vector<double>& x);
  /// Rows solved elsewhere (another MPI rank), as this run would have recorded them: feasibility
  /// and NLopt's minimised value recomputed in order.
  void adopt(const std::vector<SearchRow>& solved);
  /// evaluations.csv's text for these rows.
  static std::string csv_text(const std::vector<std::string>& columns, const std::vector<const SearchRow*>& rows);

 private:
  SearchRow make_row(const std::vector<double>& x, const Evaluation& e) const;
  /// Records a row: its feasibility and what NLopt minimises.
  void append(SearchRow row);
  double minimised(const SearchRow& r) const;
  bool native_constraints() const;

  Evaluator evaluator_;
  bool quiet_ = false;
};

/// The rows of an earlier run's evaluations.csv with these columns (none when it is absent or its
/// header differs: another plan's file, which the run then replaces).
std::vector<SearchRow> read_evaluations_csv(const std::filesystem::path& path, const std::vector<std::string>& columns,
                                           std::size_t variables);

/// The rows of evaluations.csv's text with these columns (as read_evaluations_csv).
std::vector<SearchRow> parse_evaluations_csv(const std::string& text, const std::vector<std::string>& columns,
                                            std::size_t variables);

/// The swim evaluator of a plan (evaluate_swim with its target).
Evaluator swim_evaluator(const OptimizePlan& plan);

/// The scene's own values of the plan's variables.
std::vector<double> scene_values(const OptimizePlan& plan);

/// Two objectives: a weighted-sum sweep (docs/control.md), its sub-problems (ParetoSweep) on
/// threads; writes evaluations.csv, pareto.csv, pareto.png and summary.json.
nlohmann::ordered_json run_pareto(const OptimizePlan& plan, const std::filesystem::path& out, bool quiet,
                                  const Evaluator& evaluator);

/// summary.json's figures of one search (best and baseline objective and variables, counts).
nlohmann::ordered_json optimize_summary(const OptimizeRun& run, double wall_seconds);

/// The SI unit of an objective's value ("" for a pure number), for the charts' axes.
inline std::string objective_unit(const std::string& name) {
  return name == "speed" ? "m/s" : name == "distance_per_cycle" || name == "reach" ? "m" : "";
}

/// Whether an objective is naturally maximised (distance_per_cycle, speed, efficiency).
bool maximised_objective(const std::string& name);

}  // namespace jellysim::experiments
