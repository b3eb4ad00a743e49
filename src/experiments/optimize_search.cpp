// One NLopt search of `jellysim optimize` (docs/control.md): the baseline first, then NLopt's
// points; each evaluation a row written to evaluations.csv at once, so that a killed run resumes:
// NLopt given the same seed asks for the same points again, and those found in the earlier file
// are answered from it (not run), until the first point that differs.
#include "optimize_search.hpp"

#include "jellysim/core/errors.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

namespace jellysim::experiments {
namespace {

nlopt::algorithm nlopt_algorithm(const std::string& name) {
  if (name == "bobyqa") return nlopt::LN_BOBYQA;
  if (name == "cobyla") return nlopt::LN_COBYLA;
  if (name == "neldermead") return nlopt::LN_NELDERMEAD;
  if (name == "sbplx") return nlopt::LN_SBPLX;
  if (name == "crs2_lm") return nlopt::GN_CRS2_LM;
  if (name == "isres") return nlopt::GN_ISRES;
  if (name == "direct") return nlopt::GN_DIRECT;
  if (name == "direct_l") return nlopt::GN_DIRECT_L;
  if (name == "praxis") return nlopt::LN_PRAXIS;
  return nlopt::GN_ESCH;
}

std::string result_name(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "stopval_reached";
    case nlopt::FTOL_REACHED: return "ftol_reached";
    case nlopt::XTOL_REACHED: return "xtol_reached";
    case nlopt::MAXEVAL_REACHED: return "maxeval_reached";
    case nlopt::MAXTIME_REACHED: return "maxtime_reached";
    default: return "stopped (" + std::to_string(static_cast<int>(r)) + ")";
  }
}

/// Relative violation of [lo, hi] by v (0 inside).
double violation(double v, double lo, double hi) {
  if (std::isnan(v)) return 1.0;
  if (v < lo) return (lo - v) / std::max(std::abs(lo), 1e-12);
  if (v > hi) return (v - hi) / std::max(std::abs(hi), 1e-12);
  return 0.0;
}

struct ConstraintSide {
  OptimizeRun* run;
  std::size_t index;
  bool upper;
};

double nlopt_objective(unsigned n, const double* x, double* /*grad*/, void* data) {
  auto* run = static_cast<OptimizeRun*>(data);
  return run->evaluate(std::vector<double>(x, x + n)).minimised;
}

/// lower − v ≤ 0 or v − upper ≤ 0, relative to the bound; a failed evaluation violates it.
double nlopt_constraint(unsigned n, const double* x, double* /*grad*/, void* data) {
  const auto* side = static_cast<const ConstraintSide*>(data);
  const SearchRow& r = side->run->evaluate(std::vector<double>(x, x + n));
  const FigureBound& b = side->run->plan.constraints[side->index];
  const double v = r.failed ? NAN : r.constraints[side->index];
  if (std::isnan(v)) return 1.0;
  return side->upper ? (v - b.upper) / std::max(std::abs(b.upper), 1e-12)
                     : (b.lower - v) / std::max(std::abs(b.lower), 1e-12);
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
  return cells;
}

}  // namespace

bool maximised_objective(const std::string& name) {
  return name == "distance_per_cycle" || name == "speed" || name == "efficiency";
}

Evaluator swim_evaluator(const OptimizePlan& plan) {
  const std::optional<Vec2> target = plan.target;
  const double time = plan.target_time_s;
  return [target, time](const config::Config& c) { return evaluate_swim(c, target, time); };
}

std::vector<std::string> OptimizeRun::columns() const {
  std::vector<std::string> c{"evaluation"};
  if (plan.objectives.size() == 2) c.push_back("weight");
  for (const DesignVariable& v : plan.variables) c.push_back(v.key);
  if (plan.objectives.size() == 2) c.insert(c.end(), plan.objectives.begin(), plan.objectives.end());
  else c.push_back("objective");
  for (const FigureBound& b : plan.constraints) c.push_back(b.figure);
  c.push_back("failed");
  return c;
}

bool OptimizeRun::native_constraints() const {
  return plan.algorithm == "cobyla" || plan.algorithm == "isres";
}

/// What NLopt minimises: the objective with its sense (the Pareto sweep: the weighted sum of both,
/// each over its baseline magnitude); a failed evaluation gets a penalty worse than any row so far;
/// algorithms without constraints get 10 × |baseline| per unit of relative violation.
double OptimizeRun::minimised(const SearchRow& r) const {
  double worst = 0.0;
  for (const SearchRow& p : rows) worst = std::max(worst, p.minimised);
  if (r.failed || !std::isfinite(r.objective)) return worst + std::abs(worst) + 1.0;
  double g = r.objective;
  if (weight >= 0) {
    const double s0 = maximised_objective(plan.objectives[0]) ? -1.0 : 1.0;
    const double s1 = maximised_objective(plan.objectives[1]) ? -1.0 : 1.0;
    g = weight * s0 * r.objectives[0] / scales[0] + (1.0 - weight) * s1 * r.objectives[1] / scales[1];
  } else if (plan.maximize) {
    g = -g;
  }
  if (native_constraints()) return g;
  double v = 0.0;
  for (std::size_t i = 0; i < plan.constraints.size(); ++i)
    v += violation(r.constraints[i], plan.constraints[i].lower, plan.constraints[i].upper);
  const double scale = rows.empty() ? std::abs(g) : std::abs(rows[0].minimised);
  return g + 10.0 * std::max(scale, 1e-12) * v;
}

SearchRow OptimizeRun::make_row(const std::vector<double>& x, const Evaluation& e) const {
  SearchRow r;
  r.evaluation = static_cast<int>(rows.size());
  r.weight = weight;
  r.x = x;
  r.failed = e.failed;
  const auto figure = [&](const std::string& name) {
    const auto it = e.figures.find(name);
    return e.failed || it == e.figures.end() ? NAN : it->second;
  };
  for (const std::string& o : plan.objectives) r.objectives.push_back(figure(o));
  for (const FigureBound& b : plan.constraints) r.constraints.push_back(figure(b.figure));
  r.objective = r.objectives[0];
  return r;
}

const SearchRow& OptimizeRun::evaluate(const std::vector<double>& x) {
  for (const SearchRow& r : rows)
    if (r.x == x) return r;  // NLopt asking again (a constraint after the objective)
  const int total = budget > 0 ? budget : plan.evaluations;
  if (!rows.empty() && static_cast<int>(rows.size()) >= total) throw nlopt::forced_stop();  // the budget is spent
  SearchRow row;
  if (replayed < previous.size() && previous[replayed].x == x) {
    row = previous[replayed++];
    row.evaluation = static_cast<int>(rows.size());
  } else {
    previous.clear();  // the path left the earlier run's: everything from here is new
    Evaluation e;
    try {
      e = evaluator_(evaluation_config(plan, x));
    } catch (const std::exception& ex) {
      if (!quiet_) std::cerr << "optimize: evaluation " << rows.size() << " failed: " << ex.what() << "\n";
      e.failed = true;
    }
    row = make_row(x, e);
  }
  append(row);
  if (on_evaluation) on_evaluation(rows.size(), static_cast<std::size_t>(total));
  if (on_row) on_row();
  else if (out) out->write_text("evaluations.csv", csv_text(columns(), [&] {
    std::vector<const SearchRow*> all;
    for (const SearchRow& r : rows) all.push_back(&r);
    return all;
  }()));
  if (!quiet_) {
    std::cout << "evaluation " << row.evaluation << ":";
    for (double v : x) std::cout << " " << io::format_double(v);
    std::cout << " -> " << io::format_double(row.objective) << (row.failed ? " (failed)" : row.feasible ? "" : " (infeasible)") << std::endl;
  }
  return rows.back();
}

void OptimizeRun::append(SearchRow row) {
  row.feasible = !row.failed && std::isfinite(row.objective);
  for (std::size_t i = 0; i < plan.constraints.size(); ++i)
    row.feasible = row.feasible && violation(row.constraints[i], plan.constraints[i].lower, plan.constraints[i].upper) == 0;
  row.minimised = minimised(row);
  rows.push_back(std::move(row));
}

void OptimizeRun::adopt(const std::vector<SearchRow>& solved) {
  rows.clear();
  for (const SearchRow& r : solved) append(r);
}

void OptimizeRun::search(const std::vector<double>& x0) {
  const unsigned n = static_cast<unsigned>(plan.variables.size());
  std::vector<double> lo, hi, start;
  for (std::size_t i = 0; i < n; ++i) {
    lo.push_back(plan.variables[i].lower);
    hi.push_back(plan.variables[i].upper);
    start.push_back(std::clamp(x0[i], lo[i], hi[i]));
  }
  evaluate(x0);  // the baseline: the scene's own stroke
  const int total = budget > 0 ? budget : plan.evaluations;
  if (total <= 1) return;
  nlopt::srand(static_cast<unsigned long>(plan.seed));
  nlopt::opt opt(nlopt_algorithm(plan.algorithm), n);
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_min_objective(nlopt_objective, this);
  std::vector<ConstraintSide> sides;
  for (std::size_t i = 0; i < plan.constraints.size(); ++i)
    for (bool upper : {false, true})
      if (std::isfinite(upper ? plan.constraints[i].upper : plan.constraints[i].lower)) sides.push_back({this, i, upper});
  if (native_constraints())
    for (ConstraintSide& s : sides) opt.add_inequality_constraint(nlopt_constraint, &s, 0.0);
  std::vector<double> step;
  for (std::size_t i = 0; i < n; ++i) step.push_back(0.25 * (hi[i] - lo[i]));
  opt.set_initial_step(step);
  opt.set_maxeval(2 * total);  // NLopt asks for the baseline again and constraints' points twice: evaluate() counts
  opt.set_xtol_rel(1e-6);
  if (opt.get_algorithm() == nlopt::GN_CRS2_LM || opt.get_algorithm() == nlopt::GN_ISRES)
    opt.set_population(std::max(10u, 2 * (n + 1)));
  double value = 0.0;
  try {
    result = result_name(opt.optimize(start, value));
  } catch (const nlopt::forced_stop&) {
    result = "budget_spent";
  } catch (const std::exception& e) {
    result = std::string("stopped: ") + e.what();
  }
}

const SearchRow* OptimizeRun::best() const {
  const SearchRow* best = nullptr;
  for (const SearchRow& r : rows) {
    if (!r.feasible) continue;
    if (!best || (weight >= 0 ? r.minimised < best->minimised : better(r.objective, best->objective))) best = &r;
  }
  if (best) return best;
  for (const SearchRow& r : rows)
    if (!r.failed && (!best || r.minimised < best->minimised)) best = &r;
  return best;
}

std::string OptimizeRun::csv_text(const std::vector<std::string>& columns, const std::vector<const SearchRow*>& rows) {
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) text += (i ? "," : "") + columns[i];
  text += "\n";
  for (const SearchRow* r : rows) {
    text += std::to_string(r->evaluation);
    if (r->weight >= 0) text += "," + io::format_double(r->weight);
    for (double v : r->x) text += "," + io::format_double(v);
    for (double v : r->objectives) text += "," + io::format_double(v);
    for (double v : r->constraints) text += "," + io::format_double(v);
    text += r->failed ? ",1\n" : ",0\n";
  }
  return text;
}

std::vector<SearchRow> read_evaluations_csv(const std::filesystem::path& path, const std::vector<std::string>& columns,
                                           std::size_t variables) {
  std::string text;
  try {
    text = io::read_regular_file(path, 64u << 20, false);
  } catch (const std::exception&) {
    return {};
  }
  return parse_evaluations_csv(text, columns, variables);
}

std::vector<SearchRow> parse_evaluations_csv(const std::string& text, const std::vector<std::string>& columns,
                                            std::size_t variables) {
  std::vector<SearchRow> rows;
  std::stringstream lines(text);
  std::string line;
  if (!std::getline(lines, line) || split_csv(line) != columns) return rows;
  const bool pareto = std::find(columns.begin(), columns.end(), "weight") != columns.end();
  const std::size_t objectives = pareto ? 2 : 1;
  while (std::getline(lines, line)) {
    const std::vector<std::string> cells = split_csv(line);
    if (cells.size() != columns.size()) break;  // a line cut short by the kill
    std::vector<double> v;
    for (std::size_t i = 1; i + 1 < cells.size(); ++i) v.push_back(std::strtod(cells[i].c_str(), nullptr));
    SearchRow r;
    r.evaluation = std::atoi(cells[0].c_str());
    std::size_t k = 0;
    if (pareto) r.weight = v[k++];
    const std::size_t first_var = k;
    r.x.assign(v.begin() + static_cast<std::ptrdiff_t>(first_var), v.begin() + static_cast<std::ptrdiff_t>(first_var + variables));
    k = first_var + r.x.size();
    r.objectives.assign(v.begin() + static_cast<std::ptrdiff_t>(k), v.begin() + static_cast<std::ptrdiff_t>(k + objectives));
    r.constraints.assign(v.begin() + static_cast<std::ptrdiff_t>(k + objectives), v.end());
    r.failed = cells.back() == "1";
    r.objective = r.objectives[0];
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace jellysim::experiments
