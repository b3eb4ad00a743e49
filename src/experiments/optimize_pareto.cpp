// The two-objective mode of `jellysim optimize` (docs/control.md, "Pareto front"): a weighted-sum
// sweep, weight w_k = k/(K−1) of the first objective and 1 − w_k of the second, each over the
// magnitude of the baseline's value, signed so that both are minimised. The K sub-problems are
// independent optimisations from the scene's stroke, run on threads (WorkerPool::run_tasks) or, under
// mpirun, on MPI ranks (src/app/mpi_backend.cpp); their rows go to evaluations.csv in sub-problem
// order whatever the backend. pareto.csv holds the
// non-dominated feasible evaluations of all of them.
#include "optimize_search.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/render/plot.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

namespace jellysim::experiments {
namespace {

/// a dominates b: no worse in both objectives (in their senses), better in one.
bool dominates(const SearchRow& a, const SearchRow& b, const OptimizePlan& plan) {
  bool strictly = false;
  for (std::size_t i = 0; i < 2; ++i) {
    const double s = maximised_objective(plan.objectives[i]) ? -1.0 : 1.0;
    if (s * a.objectives[i] > s * b.objectives[i]) return false;
    strictly = strictly || s * a.objectives[i] < s * b.objectives[i];
  }
  return strictly;
}

bool usable(const SearchRow* r) { return r->feasible && std::isfinite(r->objectives[0]) && std::isfinite(r->objectives[1]); }

std::vector<const SearchRow*> front(const std::vector<const SearchRow*>& all, const OptimizePlan& plan) {
  std::vector<const SearchRow*> kept;
  for (const SearchRow* r : all) {
    if (!usable(r)) continue;
    const bool dominated =
        std::any_of(all.begin(), all.end(), [&](const SearchRow* o) { return usable(o) && dominates(*o, *r, plan); });
    const bool repeated = std::any_of(kept.begin(), kept.end(), [&](const SearchRow* o) { return o->objectives == r->objectives; });
    if (!dominated && !repeated) kept.push_back(r);
  }
  std::sort(kept.begin(), kept.end(), [](const SearchRow* a, const SearchRow* b) { return a->objectives[0] < b->objectives[0]; });
  return kept;
}

void write_pareto_files(const io::OutputDir& out, const OptimizePlan& plan, const std::vector<const SearchRow*>& all) {
  const std::vector<const SearchRow*> kept = front(all, plan);
  std::string text = "evaluation,weight";
  for (const DesignVariable& v : plan.variables) text += "," + v.key;
  text += "," + plan.objectives[0] + "," + plan.objectives[1] + "\n";
  render::Series everything{"evaluations", {}, {}, true, false};
  render::Series line{"Pareto front", {}, {}, true, true};
  for (const SearchRow* r : all)
    if (usable(r)) {
      everything.x.push_back(r->objectives[0]);
      everything.y.push_back(r->objectives[1]);
    }
  for (const SearchRow* r : kept) {
    text += std::to_string(r->evaluation) + "," + io::format_double(r->weight);
    for (double v : r->x) text += "," + io::format_double(v);
    text += "," + io::format_double(r->objectives[0]) + "," + io::format_double(r->objectives[1]) + "\n";
    line.x.push_back(r->objectives[0]);
    line.y.push_back(r->objectives[1]);
  }
  out.write_text("pareto.csv", text);
  render::ChartSpec chart;
  chart.title = "optimize: Pareto front (" + plan.algorithm + ", weighted sums)";
  chart.x_label = plan.objectives[0];
  chart.y_label = plan.objectives[1];
  chart.x_unit = objective_unit(plan.objectives[0]);
  chart.y_unit = objective_unit(plan.objectives[1]);
  chart.series = {everything, line};
  out.write_text("pareto.png", render::chart_png(chart));  // listed in the manifest: a rerun resumes
}

/// The sub-problems, each given its rows of an earlier run (or the baseline row to replay).
std::vector<std::unique_ptr<OptimizeRun>> sub_problems(const OptimizePlan& plan, const Evaluator& evaluator, bool quiet,
                                                       const std::vector<SearchRow>& previous, const SearchRow& base) {
  const std::vector<double> scales{std::max(std::abs(base.objectives[0]), 1e-30), std::max(std::abs(base.objectives[1]), 1e-30)};
  std::vector<std::unique_ptr<OptimizeRun>> runs;
  for (int k = 0; k < plan.pareto_points; ++k) {
    auto run = std::make_unique<OptimizeRun>(plan, evaluator, quiet);
    run->weight = static_cast<double>(k) / static_cast<double>(plan.pareto_points - 1);
    run->budget = std::max(2, plan.evaluations / plan.pareto_points);
    run->scales = scales;
    for (const SearchRow& p : previous)
      if (p.weight == run->weight) run->previous.push_back(p);
    if (run->previous.empty()) {  // a new sweep: each sub-problem's baseline row is the probe's
      run->previous.push_back(base);
      run->previous.back().weight = run->weight;
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace

struct ParetoSweep::State {
  const OptimizePlan& plan;
  std::filesystem::path out_path;
  std::unique_ptr<OptimizeRun> probe;  // the baseline, once: it scales both terms of every weight
  SearchRow base;
  std::vector<std::unique_ptr<OptimizeRun>> runs;
  std::optional<io::OutputDir> out;
  std::mutex mutex;

  std::vector<const SearchRow*> all_rows() const {
    std::vector<const SearchRow*> all;
    for (const auto& r : runs)
      for (const SearchRow& row : r->rows) all.push_back(&row);
    return all;
  }
  /// evaluations.csv of every sub-problem's rows so far, in sub-problem order.
  void write_evaluations() {
    const std::lock_guard<std::mutex> lock(mutex);
    if (out) out->write_text("evaluations.csv", OptimizeRun::csv_text(probe->columns(), all_rows()));
  }
};

ParetoSweep::ParetoSweep(const OptimizePlan& plan, const std::filesystem::path& out, bool quiet, const Evaluator& evaluator)
    : state_(new State{plan, out, {}, {}, {}, {}, {}}) {
  const Evaluator e = evaluator ? evaluator : swim_evaluator(plan);
  state_->probe = std::make_unique<OptimizeRun>(plan, e, true);
  state_->base = state_->probe->evaluate(scene_values(plan));
  if (state_->base.failed) throw RunError("optimize: the baseline evaluation (the scene's own stroke) failed");
  const std::vector<SearchRow> previous =
      read_evaluations_csv(out / "evaluations.csv", state_->probe->columns(), plan.variables.size());
  state_->runs = sub_problems(plan, e, quiet, previous, state_->base);
  for (auto& r : state_->runs) r->on_row = [s = state_.get()] { s->write_evaluations(); };
}

ParetoSweep::~ParetoSweep() = default;

std::size_t ParetoSweep::size() const { return state_->runs.size(); }
double ParetoSweep::weight(std::size_t k) const { return state_->runs.at(k)->weight; }
std::size_t ParetoSweep::evaluations(std::size_t k) const { return state_->runs.at(k)->rows.size(); }

void ParetoSweep::open_output() { state_->out.emplace(io::OutputDir::for_run(state_->out_path, "optimize")); }

std::string ParetoSweep::solve(std::size_t k) {
  OptimizeRun& run = *state_->runs.at(k);
  run.search(scene_values(state_->plan));
  std::vector<const SearchRow*> rows;
  for (const SearchRow& r : run.rows) rows.push_back(&r);
  return OptimizeRun::csv_text(run.columns(), rows);
}

void ParetoSweep::accept(std::size_t k, const std::string& rows) {
  OptimizeRun& run = *state_->runs.at(k);
  run.adopt(parse_evaluations_csv(rows, run.columns(), state_->plan.variables.size()));
  state_->write_evaluations();
}

nlohmann::ordered_json ParetoSweep::finish(const std::string& engine, double wall_seconds) {
  State& s = *state_;
  if (!s.out) open_output();
  s.write_evaluations();
  write_pareto_files(*s.out, s.plan, s.all_rows());
  nlohmann::ordered_json j;
  j["objectives"] = s.plan.objectives;
  j["algorithm"] = s.plan.algorithm;
  j["weights"] = s.plan.pareto_points;
  j["baseline_objectives"] = s.base.objectives;
  j["pareto_points"] = front(s.all_rows(), s.plan).size();
  j["evaluations"] = s.all_rows().size();
  j["engine"] = engine;
  j["wall_seconds"] = wall_seconds;
  write_summary(*s.out, "optimize", evaluation_config(s.plan, scene_values(s.plan)), j, "");
  s.out->finish_manifest();
  return j;
}

nlohmann::ordered_json run_pareto(const OptimizePlan& plan, const std::filesystem::path& out_path, bool quiet,
                                  const Evaluator& evaluator) {
  const auto start = std::chrono::steady_clock::now();
  ParetoSweep sweep(plan, out_path, quiet, evaluator);
  sweep.open_output();
  const int threads = std::max(1, std::min(resolve_threads(plan.threads), plan.pareto_points));
  WorkerPool pool(threads);
  pool.run_tasks(sweep.size(), [&](std::size_t k) {
    const SerialThreadsScope serial;  // each sub-problem on one core
    sweep.solve(k);
  });
  return sweep.finish("threads: " + std::to_string(threads),
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace jellysim::experiments
