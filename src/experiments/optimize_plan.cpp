// The plan file of `jellysim optimize` (docs/control.md, "The plan"), read strictly: every field's
// type and range checked, unknown fields refused, errors naming the file, the line and the field.
#include "jellysim/experiments/optimize.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"
#include "plan_values.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace jellysim::experiments {
namespace {

/// The algorithms a plan may name (NLopt's names in lower case, derivative-free ones).
const std::vector<std::string> kAlgorithms = {"bobyqa", "cobyla", "neldermead", "sbplx", "crs2_lm", "isres", "direct",
                                              "direct_l", "praxis", "esch"};

std::string list_text(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

std::string at(const std::string& file, const toml::node& n) {
  return file + ":" + std::to_string(n.source().begin.line) + ": ";
}

double number_in(const toml::node& n, const std::string& file, const std::string& field, double lo, double hi) {
  const std::optional<double> v = n.value<double>();
  if (!v || !(*v >= lo && *v <= hi))
    throw InputError(at(file, n) + "field '" + field + "' must be a number in [" + config::format_number(lo) + ", " +
                     config::format_number(hi) + "]");
  return *v;
}

int integer_in(const toml::node& n, const std::string& file, const std::string& field, int lo, int hi) {
  const std::optional<std::int64_t> v = n.value_exact<std::int64_t>();
  if (!v || *v < lo || *v > hi)
    throw InputError(at(file, n) + "field '" + field + "' must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  return static_cast<int>(*v);
}

std::string choice_in(const toml::node& n, const std::string& file, const std::string& field,
                      const std::vector<std::string>& allowed) {
  const auto* s = n.as_string();
  if (!s || std::find(allowed.begin(), allowed.end(), s->get()) == allowed.end())
    throw InputError(at(file, n) + "field '" + field + "' must be one of " + list_text(allowed));
  return s->get();
}

/// `[lo, hi]` with lo < hi, both finite unless `open_ends` (constraints may leave one side open).
std::pair<double, double> bounds(const toml::node& n, const std::string& file, const std::string& field, bool open_ends) {
  const toml::array* a = n.as_array();
  const double inf = std::numeric_limits<double>::infinity();
  std::optional<double> lo, hi;
  if (a && a->size() == 2) {
    lo = a->get(0)->value<double>();
    hi = a->get(1)->value<double>();
  }
  const auto ok = [&](const std::optional<double>& v) { return v && (open_ends ? !std::isnan(*v) : std::isfinite(*v)); };
  if (!ok(lo) || !ok(hi) || !(*lo < *hi))
    throw InputError(at(file, n) + "field '" + field + "' must be [lower, upper] with lower < upper" +
                     (open_ends ? " (inf allowed)" : ", both finite"));
  return {std::max(*lo, -inf), std::min(*hi, inf)};
}

void read_objectives(const toml::node& n, const std::string& file, OptimizePlan& plan) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2)
    throw InputError(at(file, n) + "field 'objectives' must be two objectives, e.g. [\"speed\", \"cost_of_transport\"]");
  plan.objectives.clear();
  for (const toml::node& o : *a) plan.objectives.push_back(choice_in(o, file, "objectives", objective_names()));
  if (plan.objectives[0] == plan.objectives[1])
    throw InputError(at(file, n) + "field 'objectives' names '" + plan.objectives[0] + "' twice");
}

void read_variables(const toml::node& n, const std::string& file, OptimizePlan& plan) {
  const toml::table* t = n.as_table();
  if (!t || t->empty()) throw InputError(file + ": field 'variables' must be a table of \"key\" = [lower, upper]");
  for (const PlanLeaf& l : plan_leaves(*t)) {  // in the file's order
    const std::string& key = l.key;
    const toml::node& v = *l.node;
    if (key == "scene" || key == "duration")
      throw InputError(at(file, v) + "variables." + key + ": not a design variable (a numeric scene key)");
    const auto [lo, hi] = bounds(v, file, "variables." + key, false);
    plan.variables.push_back({key, lo, hi});
  }
}

void read_constraints(const toml::node& n, const std::string& file, OptimizePlan& plan) {
  const toml::table* t = n.as_table();
  if (!t) throw InputError(file + ": field 'constraints' must be a table of figure = [lower, upper]");
  for (const PlanLeaf& l : plan_leaves(*t)) {  // in the file's order
    const std::string& figure = l.key;
    const toml::node& v = *l.node;
    if (std::find(stroke_figure_names().begin(), stroke_figure_names().end(), figure) == stroke_figure_names().end())
      throw InputError(at(file, v) + "constraints." + figure + ": unknown figure; one of " + list_text(stroke_figure_names()));
    const auto [lo, hi] = bounds(v, file, "constraints." + figure, true);
    plan.constraints.push_back({figure, lo, hi});
  }
}

void read_target(const toml::node& n, const std::string& file, OptimizePlan& plan) {
  const toml::table* t = n.as_table();
  if (!t) throw InputError(file + ": field 'target' must be a table with position = [x, y] and time = seconds");
  for (auto&& [k, v] : *t) {
    const std::string key(k.str());
    if (key == "position") {
      const auto* a = v.as_array();
      const std::optional<double> x = a && a->size() == 2 ? a->get(0)->value<double>() : std::nullopt;
      const std::optional<double> y = a && a->size() == 2 ? a->get(1)->value<double>() : std::nullopt;
      if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y))
        throw InputError(at(file, v) + "field 'target.position' must be [x, y] in metres");
      plan.target = Vec2{*x, *y};
    } else if (key == "time") {
      plan.target_time_s = number_in(v, file, "target.time", 1e-6, 1e6);
    } else {
      throw InputError(at(file, v) + "unknown field 'target." + key + "' (position, time)");
    }
  }
  if (!plan.target || !(plan.target_time_s > 0))
    throw InputError(file + ": [target] needs both position = [x, y] (m) and time = seconds");
}

void read_field(const std::string& key, const toml::node& v, const std::string& file, OptimizePlan& plan) {
  if (key == "scene") {
    const auto* s = v.as_string();
    if (!s || s->get().empty()) throw InputError(at(file, v) + "field 'scene' must be the path of a scene file");
    plan.scene = plan.file.parent_path() / s->get();
  } else if (key == "cycles") {
    plan.cycles = number_in(v, file, "cycles", 2.0, 1000.0);
  } else if (key == "duration") {
    plan.duration = number_in(v, file, "duration", 1e-3, 1e6);
  } else if (key == "objective") {
    plan.objectives = {choice_in(v, file, "objective", objective_names())};
  } else if (key == "objectives") {
    read_objectives(v, file, plan);
  } else if (key == "sense") {
    plan.maximize = choice_in(v, file, "sense", {"maximize", "minimize"}) == "maximize";
  } else if (key == "algorithm") {
    plan.algorithm = choice_in(v, file, "algorithm", kAlgorithms);
  } else if (key == "evaluations") {
    plan.evaluations = integer_in(v, file, "evaluations", 1, 100000);
  } else if (key == "seed") {
    plan.seed = integer_in(v, file, "seed", 0, 2147483647);
  } else if (key == "threads") {
    plan.threads = integer_in(v, file, "threads", 0, 64);
  } else if (key == "pareto_points") {
    plan.pareto_points = integer_in(v, file, "pareto_points", 2, 50);
  } else if (key == "set") {
    plan.shared = read_plan_set(v, file);
  } else if (key == "variables") {
    read_variables(v, file, plan);
  } else if (key == "constraints") {
    read_constraints(v, file, plan);
  } else if (key == "target") {
    read_target(v, file, plan);
  } else {
    throw InputError(at(file, v) + "unknown field '" + key +
                     "' (a plan has scene, cycles or duration, objective(s), sense, algorithm, evaluations, seed, "
                     "threads, pareto_points, [set], [variables], [constraints], [target])");
  }
}

/// The checks across fields.
void check_plan(const OptimizePlan& plan, const std::string& file, bool had_objective) {
  if (!had_objective) throw InputError(file + ": missing field 'objective' (one of " + list_text(objective_names()) + ")");
  if (plan.variables.empty()) throw InputError(file + ": missing table [variables] (\"key\" = [lower, upper])");
  if (plan.cycles && plan.duration) throw InputError(file + ": give 'cycles' or 'duration', not both");
  const bool reach = std::find(plan.objectives.begin(), plan.objectives.end(), "reach") != plan.objectives.end();
  if (reach && !plan.target) throw InputError(file + ": objective 'reach' needs a [target] table (position, time)");
  if (!reach && plan.target) throw InputError(file + ": [target] is for objective 'reach' only");
  if (reach && (plan.cycles || plan.duration))
    throw InputError(file + ": objective 'reach' runs to target.time: give neither 'cycles' nor 'duration'");
  if (!reach && !plan.cycles && !plan.duration) throw InputError(file + ": missing field 'cycles' (or 'duration')");
}

}  // namespace

const std::vector<std::string>& objective_names() {
  static const std::vector<std::string> names = {"distance_per_cycle", "speed", "cost_of_transport", "efficiency", "reach"};
  return names;
}

const std::vector<std::string>& stroke_figure_names() {
  static const std::vector<std::string> names = {
      "distance_per_cycle", "speed", "cost_of_transport", "efficiency", "reach", "muscle_work",
      "peak_muscle_tension", "min_volume_ratio", "min_aperture_ratio", "distance_travelled"};
  return names;
}

OptimizePlan parse_optimize_plan(std::string_view text, const std::filesystem::path& file) {
  const std::string name = file.string();
  const toml::table table = parse_plan_toml(text, name);
  OptimizePlan plan;
  plan.file = file;
  bool had_objective = false;
  for (auto&& [k, v] : table) {
    const std::string key(k.str());
    if (key == "objective" || key == "objectives") {
      if (had_objective) throw InputError(at(name, v) + "give 'objective' or 'objectives', not both");
      had_objective = true;
    }
    read_field(key, v, name, plan);
  }
  check_plan(plan, name, had_objective);
  return plan;
}

OptimizePlan read_optimize_plan(const std::filesystem::path& file) {
  std::string text;
  try {
    text = io::read_regular_file(file, config::Config::kMaxSceneFileBytes, true);
  } catch (const InputError& e) {
    throw InputError("plan file: " + std::string(e.what()));
  }
  return parse_optimize_plan(text, file);
}

}  // namespace jellysim::experiments
