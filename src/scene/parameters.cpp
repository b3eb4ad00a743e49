#include "jellysim/scene/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "jellysim/core/errors.hpp"

namespace jellysim::scene {
namespace {

/// "tank" for "tank.width", "render.noise" for "render.noise.seed", "" for "duration".
std::string table_of(const std::string& key) {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string leaf_of(const std::string& key) {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

/// The table names in order of first appearance, top level ("") first.
std::vector<std::string> table_order(const std::vector<Parameter>& parameters) {
  std::vector<std::string> order{""};
  for (const Parameter& p : parameters)
    if (const std::string t = table_of(p.key); std::find(order.begin(), order.end(), t) == order.end())
      order.push_back(t);
  return order;
}

std::string join(const std::vector<std::string>& words, const std::string& separator) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : separator) + w;
  return s;
}

/// The smallest (direction −1) or largest (+1) integer the bound v allows, clamped to ±2^62.
std::int64_t integer_bound(double v, bool open, int direction) {
  constexpr double kLimit = 4611686018427387904.0;  // 2^62: exact in a double, far from overflow
  if (!(std::abs(v) < kLimit)) return static_cast<std::int64_t>(std::copysign(kLimit, v));
  double i = direction < 0 ? std::ceil(v) : std::floor(v);
  if (open && i == v) i -= direction;
  return static_cast<std::int64_t>(i);
}

/// The line's comment: unit and allowed values, then the description.
std::string comment(const Parameter& p) {
  std::string head = p.unit;
  if (p.type != Type::boolean) {
    const std::string allowed = p.type == Type::choice ? join(p.choices, " | ") : allowed_values(p);
    if (!allowed.empty()) head += (head.empty() ? "" : ", ") + allowed;
  }
  return head.empty() ? p.description : head + ": " + p.description;
}

/// `text` in lines of at most `width` characters, broken at spaces.
std::vector<std::string> wrap(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream words(text);
  for (std::string w; words >> w;) {
    if (!line.empty() && line.size() + 1 + w.size() > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string markdown_cell(std::string s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

namespace param {

Parameter number(std::string key, std::string value, std::string unit, config::Range range, std::string description,
                 Slider slider) {
  return {std::move(key), Type::number, std::move(value), std::move(unit), range, {}, 0, std::move(description), slider};
}
Parameter integer(std::string key, std::string value, double min, double max, std::string description) {
  return {std::move(key), Type::integer, std::move(value), "", config::Range::closed(min, max), {}, 0, std::move(description)};
}
Parameter boolean(std::string key, std::string value, std::string description) {
  return {std::move(key), Type::boolean, std::move(value), "", {}, {}, 0, std::move(description)};
}
Parameter choice(std::string key, std::string value, std::vector<std::string> choices, std::string description) {
  return {std::move(key), Type::choice, "\"" + value + "\"", "", {}, std::move(choices), 0, std::move(description)};
}
Parameter vec2(std::string key, std::string value, std::string unit, config::Range range, std::string description) {
  return {std::move(key), Type::vec2, std::move(value), std::move(unit), range, {}, 0, std::move(description)};
}
Parameter vec3(std::string key, std::string value, std::string unit, config::Range range, std::string description) {
  return {std::move(key), Type::numbers, std::move(value), std::move(unit), range, {}, 3, std::move(description)};
}

}  // namespace param

std::string allowed_values(const Parameter& p) {
  switch (p.type) {
    case Type::boolean: return "true or false";
    case Type::choice: return "one of " + join(p.choices, ", ");
    case Type::choices:
      return (p.length > 0 ? std::to_string(p.length) + " of " : "each one of ") + join(p.choices, ", ");
    case Type::integers:
      return (p.length > 0 ? std::to_string(p.length) + " integers, each in " : "integers, each in ") +
             p.range.describe();
    case Type::numbers:
      return (p.length > 0 ? std::to_string(p.length) + " numbers, each in " : "numbers, each in ") + p.range.describe();
    case Type::vec2: {
      const bool any = !std::isfinite(p.range.min) && !std::isfinite(p.range.max);
      return any ? "[x, y]" : "[x, y], each in " + p.range.describe();
    }
    case Type::number:
    case Type::integer: return p.range.describe();
    case Type::text:
    case Type::tables: return "";
  }
  return "";
}

ParameterTable::ParameterTable(std::string name, std::string preamble, std::vector<Parameter> parameters,
                               std::string no_default)
    : name_(std::move(name)),
      preamble_(std::move(preamble)),
      parameters_(std::move(parameters)),
      no_default_(std::move(no_default)) {
  for (std::size_t a = 0; a < parameters_.size(); ++a)
    for (std::size_t b = a + 1; b < parameters_.size(); ++b)
      if (parameters_[a].key == parameters_[b].key)
        throw std::logic_error("parameter table " + name_ + ": '" + parameters_[a].key + "' twice");
}

const Parameter* ParameterTable::find(std::string_view key) const {
  for (const Parameter& p : parameters_)
    if (p.key == key) return &p;
  return nullptr;
}

const Parameter& ParameterTable::at(std::string_view key) const {
  if (const Parameter* p = find(key)) return *p;
  throw std::logic_error("parameter table " + name_ + " has no '" + std::string(key) + "'");
}

std::string ParameterTable::scene_toml(const config::Config* values) const {
  constexpr std::size_t kCommentColumn = 31, kLineWidth = 110;
  std::ostringstream s;
  s << preamble_;
  bool first = true;
  for (const std::string& table : table_order(parameters_)) {
    if (!table.empty()) s << (first ? "" : "\n") << '[' << table << "]\n";
    first = false;
    for (const Parameter& p : parameters_) {
      if (table_of(p.key) != table) continue;
      std::string line = leaf_of(p.key) + " = " + (values ? values->literal(p.key) : p.value);
      line.resize(std::max(line.size() + 1, kCommentColumn), ' ');
      const std::size_t width = kLineWidth - std::min(line.size(), kLineWidth - 40) - 2;
      const std::vector<std::string> lines = wrap(comment(p), width);
      for (std::size_t k = 0; k < lines.size(); ++k)
        s << (k == 0 ? line : std::string(line.size(), ' ')) << "# " << lines[k] << '\n';
    }
  }
  return s.str();
}

std::string ParameterTable::reference_markdown() const {
  std::ostringstream s;
  for (const std::string& table : table_order(parameters_)) {
    s << "\n### " << (table.empty() ? "Top level" : "[" + table + "]") << "\n\n";
    s << "| key | default | unit | allowed | description |\n|---|---|---|---|---|\n";
    for (const Parameter& p : parameters_) {
      if (table_of(p.key) != table) continue;
      const std::string value = p.value.empty() ? no_default_ : "`" + markdown_cell(p.value) + "`";
      s << "| `" << p.key << "` | " << value << " | " << markdown_cell(p.unit) << " | "
        << markdown_cell(allowed_values(p)) << " | " << markdown_cell(p.description) << " |\n";
    }
  }
  return s.str();
}

config::Config ParameterTable::defaults() const { return config::Config::parse(scene_toml(), "built-in " + name_ + " scene"); }

const Parameter& Reader::expect(std::string_view key, Type type) const {
  const Parameter& p = table_.at(key);
  if (p.type != type) throw std::logic_error("parameter '" + std::string(key) + "' read with the wrong type");
  return p;
}

double Reader::number(std::string_view key) const { return config_.number(key, expect(key, Type::number).range); }

std::int64_t Reader::integer(std::string_view key) const {
  const Parameter& p = expect(key, Type::integer);
  return config_.integer(key, integer_bound(p.range.min, p.range.min_open, -1),
                         integer_bound(p.range.max, p.range.max_open, 1));
}

bool Reader::boolean(std::string_view key) const {
  expect(key, Type::boolean);
  return config_.boolean(key);
}

std::string Reader::text(std::string_view key) const {
  expect(key, Type::text);
  return config_.string(key);
}

std::string Reader::choice(std::string_view key) const { return config_.choice(key, expect(key, Type::choice).choices); }

Vec2 Reader::vec2(std::string_view key) const {
  const Parameter& p = expect(key, Type::vec2);
  const Vec2 v = config_.vec2(key);
  for (double x : {v.x, v.y})
    if (!p.range.contains(x))
      throw InputError("field '" + std::string(key) + "' has element " + config::format_number(x) + " out of range " +
                       p.range.describe());
  return v;
}

std::vector<std::int64_t> Reader::integers(std::string_view key) const {
  const Parameter& p = expect(key, Type::integers);
  const std::int64_t lo = integer_bound(p.range.min, p.range.min_open, -1);
  const std::int64_t hi = integer_bound(p.range.max, p.range.max_open, 1);
  std::vector<std::int64_t> v = config_.integers(key, lo, hi);
  if (p.length > 0 && v.size() != static_cast<std::size_t>(p.length))
    throw InputError("field '" + std::string(key) + "' must have " + std::to_string(p.length) + " entries, each in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

std::vector<double> Reader::numbers(std::string_view key) const {
  const Parameter& p = expect(key, Type::numbers);
  std::vector<double> v = config_.numbers(key, p.range);
  if (p.length > 0 && v.size() != static_cast<std::size_t>(p.length))
    throw InputError("field '" + std::string(key) + "' must have " + std::to_string(p.length) + " entries, each in " +
                     p.range.describe());
  return v;
}

std::vector<std::string> Reader::choices(std::string_view key) const {
  const Parameter& p = expect(key, Type::choices);
  std::vector<std::string> v = config_.choices(key, p.choices);
  if (p.length > 0 && v.size() != static_cast<std::size_t>(p.length))
    throw InputError("field '" + std::string(key) + "' must list " + std::to_string(p.length) + " entries (" +
                     p.description + ")");
  return v;
}

bool Reader::holds_default(std::string_view key) const {
  const Parameter& p = table_.at(key);
  if (p.value.empty()) throw std::logic_error("parameter '" + std::string(key) + "' has no default");
  const config::Config d = config::Config::parse("x = " + p.value, "the default of " + std::string(key));
  switch (p.type) {
    case Type::number: return config_.number(key) == d.number("x");
    case Type::vec2:
    case Type::numbers: return config_.numbers(key) == d.numbers("x");
    case Type::tables: return config_.array_size(key) == d.array_size("x");
    default: return config_.literal(key) == d.literal("x");
  }
}

void Reader::validate_all() const {
  for (const Parameter& p : table_.parameters()) {
    if (!config_.has(p.key)) continue;
    switch (p.type) {
      case Type::number: number(p.key); break;
      case Type::integer: integer(p.key); break;
      case Type::boolean: boolean(p.key); break;
      case Type::text: text(p.key); break;
      case Type::choice: choice(p.key); break;
      case Type::vec2: vec2(p.key); break;
      case Type::integers: integers(p.key); break;
      case Type::numbers: numbers(p.key); break;
      case Type::choices: choices(p.key); break;
      case Type::tables: config_.array_size(p.key); break;
    }
  }
}

}  // namespace jellysim::scene
