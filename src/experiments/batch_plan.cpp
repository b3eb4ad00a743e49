// The plan file of `jellysim batch` (docs/batch.md): scene, duration, [set], and the runs as a
// [product] of --set values or a list of [[runs]] tables, read strictly (unknown fields, empty
// lists and values that cannot be a --set value are InputErrors naming the file and the field).
#include "jellysim/experiments/batch.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"
#include "plan_values.hpp"

#include <algorithm>
#include <stdexcept>

namespace jellysim::experiments {
constexpr std::size_t kMaxRuns = 100000;

/// The values of a table with dotted keys ([product] jellyfish.frequency = ..., "jellyfish.frequency"
/// = ... and [product.jellyfish] frequency = ... are the same key), in the order of the file.
std::vector<PlanLeaf> plan_leaves(const toml::table& table, const std::string& prefix) {
  std::vector<PlanLeaf> out;
  for (auto&& [k, v] : table) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const toml::table* sub = v.as_table()) {
      for (PlanLeaf& l : plan_leaves(*sub, key)) out.push_back(std::move(l));
    } else {
      out.push_back({key, &v, v.source().begin});
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const PlanLeaf& a, const PlanLeaf& b) {
    return a.at.line != b.at.line ? a.at.line < b.at.line : a.at.column < b.at.column;
  });
  return out;
}

namespace {

std::string toml_string(std::string_view text) {
  std::string q = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

}  // namespace

std::string plan_literal(const toml::node& n, const std::string& where) {
  if (const auto* s = n.as_string()) return toml_string(s->get());
  if (const auto* i = n.as_integer()) return std::to_string(i->get());
  if (const auto* f = n.as_floating_point()) return io::format_double(f->get());
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = n.as_array()) {
    std::string text = "[";
    for (std::size_t k = 0; k < a->size(); ++k) text += (k ? ", " : "") + plan_literal(*a->get(k), where);
    return text + "]";
  }
  throw InputError(where + ": a table or a date is not a --set value");
}

namespace {

void check_key(const std::string& key, const std::string& where) {
  if (key == "scene")
    throw InputError(where + ": the scene kind cannot be overridden; give `scene = \"FILE\"` at the top of the plan");
}

}  // namespace

toml::table parse_plan_toml(std::string_view text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw InputError(file + ":" + std::to_string(e.source().begin.line) + ": invalid TOML: " + std::string(e.description()));
  }
}

std::vector<std::string> read_plan_set(const toml::node& node, const std::string& file) {
  const toml::table* table = node.as_table();
  if (!table) throw InputError(file + ": field 'set' must be a table of key = value");
  std::vector<std::string> shared;
  for (const PlanLeaf& l : plan_leaves(*table)) {
    const std::string where = file + ": set." + l.key;
    check_key(l.key, where);
    shared.push_back(l.key + "=" + plan_literal(*l.node, where));
  }
  return shared;
}

namespace {

/// [product]: every combination, the last key varying fastest.
void read_product(const toml::node& node, const std::string& file, BatchPlan& plan) {
  const toml::table* table = node.as_table();
  if (!table) throw InputError(file + ": field 'product' must be a table of key = [values]");
  std::vector<std::vector<std::string>> values;
  std::size_t count = 1;
  for (const PlanLeaf& l : plan_leaves(*table)) {
    const std::string where = file + ": product." + l.key;
    check_key(l.key, where);
    const toml::array* list = l.node->as_array();
    if (!list) throw InputError(where + ": expected a list of values, e.g. [0.5, 0.7]");
    if (list->empty()) throw InputError(where + ": the list is empty (a product with it would have no runs)");
    plan.keys.push_back(l.key);
    values.emplace_back();
    for (const toml::node& v : *list) values.back().push_back(plan_literal(v, where));
    count *= list->size();
    if (count > kMaxRuns) throw InputError(where + ": the product has more than " + std::to_string(kMaxRuns) + " runs");
  }
  if (plan.keys.empty()) throw InputError(file + ": field 'product' is empty: give at least one key = [values]");
  plan.product = std::move(values);
}

/// [[runs]]: one table per run; the columns are every key in order of first appearance.
void read_runs(const toml::node& node, const std::string& file, BatchPlan& plan) {
  const toml::array* list = node.as_array();
  if (!list || !list->is_array_of_tables() || list->empty())
    throw InputError(file + ": field 'runs' must be one or more [[runs]] tables of key = value");
  if (list->size() > kMaxRuns) throw InputError(file + ": more than " + std::to_string(kMaxRuns) + " [[runs]]");
  std::vector<std::vector<std::pair<std::string, std::string>>> given;
  for (std::size_t r = 0; r < list->size(); ++r) {
    given.emplace_back();
    for (const PlanLeaf& l : plan_leaves(*list->get(r)->as_table())) {
      const std::string where = file + ": runs[" + std::to_string(r) + "]." + l.key;
      check_key(l.key, where);
      given.back().emplace_back(l.key, plan_literal(*l.node, where));
      if (std::find(plan.keys.begin(), plan.keys.end(), l.key) == plan.keys.end()) plan.keys.push_back(l.key);
    }
  }
  for (const auto& run : given) {
    std::vector<std::optional<std::string>> cells(plan.keys.size());
    for (const auto& [key, value] : run)
      cells[static_cast<std::size_t>(std::find(plan.keys.begin(), plan.keys.end(), key) - plan.keys.begin())] = value;
    plan.listed.push_back(std::move(cells));
  }
}

void read_top_level(const toml::table& table, const std::string& file, BatchPlan& plan) {
  for (auto&& [k, v] : table) {
    const std::string key(k.str());
    if (key == "scene") {
      const auto* s = v.as_string();
      if (!s || s->get().empty()) throw InputError(file + ": field 'scene' must be the path of a scene file");
      plan.scene = plan.file.parent_path() / s->get();
    } else if (key == "duration") {
      const std::optional<double> d = v.value<double>();
      if (!d || !(*d > 0.0)) throw InputError(file + ": field 'duration' must be a positive number of seconds");
      plan.duration = *d;
    } else if (key == "set") {
      plan.shared = read_plan_set(v, file);
    } else if (key != "product" && key != "runs") {
      throw InputError(file + ": unknown field '" + key + "' (a plan has scene, duration, [set], [product] or [[runs]])");
    }
  }
}

}  // namespace

std::size_t BatchPlan::run_count() const {
  if (product.empty()) return listed.size();
  std::size_t count = 1;
  for (const auto& values : product) count *= values.size();
  return count;
}

std::vector<std::optional<std::string>> BatchPlan::run(std::size_t k) const {
  if (product.empty()) return listed.at(k);
  if (k >= run_count()) throw std::out_of_range("batch plan: no run " + std::to_string(k));
  std::vector<std::optional<std::string>> cells(product.size());
  for (std::size_t i = product.size(); i-- > 0;) {
    cells[i] = product[i][k % product[i].size()];
    k /= product[i].size();
  }
  return cells;
}

BatchPlan parse_batch_plan(std::string_view text, const std::filesystem::path& file) {
  const std::string name = file.string();
  const toml::table table = parse_plan_toml(text, name);
  BatchPlan plan;
  plan.file = file;
  read_top_level(table, name, plan);
  const toml::node* product = table.get("product");
  const toml::node* runs = table.get("runs");
  if (product && runs) throw InputError(name + ": give either [product] or [[runs]], not both");
  if (!product && !runs) throw InputError(name + ": the plan has no runs: give a [product] table or [[runs]] tables");
  if (product) read_product(*product, name, plan);
  if (runs) read_runs(*runs, name, plan);
  return plan;
}

BatchPlan read_batch_plan(const std::filesystem::path& file) {
  // A plan is a small regular file, like a scene file (never a pipe or a device; at most 1 MiB).
  std::string text;
  try {
    text = io::read_regular_file(file, config::Config::kMaxSceneFileBytes, true);
  } catch (const InputError& e) {
    throw InputError("plan file: " + std::string(e.what()) + " (a plan is a regular file, like a scene file)");
  }
  return parse_batch_plan(text, file);
}

}  // namespace jellysim::experiments
