#include "jellysim/config/config.hpp"

#include "jellysim/core/errors.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace jellysim::config {

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

namespace {

std::string type_name(toml::node_type t) {
  switch (t) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "number";
    case toml::node_type::boolean: return "boolean";
    default: return "date/time";
  }
}

std::string value_text(const toml::node& node) {
  std::ostringstream s;
  node.visit([&](const auto& v) {
    if constexpr (toml::is_string<decltype(v)>) s << '"' << v.get() << '"';
    else s << v;
  });
  return s.str();
}

/// For a list given without brackets (--set jellyfish.position=0.5,0.1 reads as the string
/// "0.5,0.1"): ": write it as [0.5, 0.1]"; else "".
std::string array_hint(toml::node_type want, const toml::node& value) {
  if (want != toml::node_type::array || !value.is_string()) return {};
  std::string items, item;
  std::istringstream text(value.as_string()->get());
  while (std::getline(text, item, ',')) {
    const std::size_t first = item.find_first_not_of(" \t"), last = item.find_last_not_of(" \t");
    items += (items.empty() ? "" : ", ") + (first == std::string::npos ? "" : item.substr(first, last + 1 - first));
  }
  return ": write it as [" + items + "]";
}

std::string allowed_keys(const toml::table& table) {
  std::string keys;
  for (auto&& [k, v] : table) keys += (keys.empty() ? "" : ", ") + std::string(k.str());
  return keys;
}

std::string join_key(const std::string& prefix, std::string_view key) {
  return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
}

/// Copies `value` into `base` under `key`, checking that the default's type is kept.
void assign_checked(toml::table& base, std::string_view key, const toml::node& existing, const toml::node& value,
                    const std::string& path) {
  const auto want = existing.type();
  const auto got = value.type();
  if (want == toml::node_type::floating_point && got == toml::node_type::integer) {
    base.insert_or_assign(key, static_cast<double>(value.as_integer()->get()));
    return;
  }
  if (want != got) {
    throw InputError("field '" + path + "' = " + value_text(value) + " has the wrong type: expected " +
                     type_name(want) + ", got " + type_name(got) + array_hint(want, value));
  }
  value.visit([&](const auto& v) { base.insert_or_assign(key, v); });
}

void merge_table(toml::table& base, const toml::table& overlay, const std::string& prefix, bool allow_new = false) {
  for (auto&& [k, v] : overlay) {
    const std::string path = join_key(prefix, k.str());
    toml::node* existing = base.get(k.str());
    if (existing == nullptr) {
      if (allow_new) {
        base.insert(k.str(), v);
        continue;
      }
      throw InputError("unknown field '" + path + "' (allowed here: " + allowed_keys(base) + ")");
    }
    if (existing->is_table() && v.is_table()) {
      merge_table(*existing->as_table(), *v.as_table(), path, allow_new);
    } else {
      assign_checked(base, k.str(), *existing, v, path);
    }
  }
}

nlohmann::ordered_json node_to_json(const toml::node& node) {
  if (auto t = node.as_table()) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (auto&& [k, v] : *t) j[std::string(k.str())] = node_to_json(v);
    return j;
  }
  if (auto a = node.as_array()) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (auto&& v : *a) j.push_back(node_to_json(v));
    return j;
  }
  if (auto s = node.as_string()) return s->get();
  if (auto i = node.as_integer()) return i->get();
  if (auto f = node.as_floating_point()) return f->get();
  if (auto b = node.as_boolean()) return b->get();
  return value_text(node);
}

/// Parses the value part of `key=value` as TOML; a bare word that is not TOML becomes a string.
toml::table parse_override_value(std::string_view value) {
  try {
    return toml::parse("v = " + std::string(value));
  } catch (const toml::parse_error&) {
    toml::table t;
    t.insert("v", std::string(value));
    return t;
  }
}

}  // namespace

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;  // inf and nan are never valid settings
  const bool above = min_open ? v > min : v >= min;
  const bool below = max_open ? v < max : v <= max;
  return above && below;
}

std::string Range::describe() const {
  // An infinite bound is never allowed (contains() rejects it): its side is open.
  const bool low_open = min_open || !std::isfinite(min), high_open = max_open || !std::isfinite(max);
  return std::string(low_open ? "(" : "[") + format_number(min) + ", " + format_number(max) + (high_open ? ")" : "]");
}

struct Config::Impl {
  toml::table table;
  std::string source;

  const toml::node& node(std::string_view key) const {
    const toml::node* n = table.at_path(key).node();
    if (n == nullptr) throw InputError(source + ": missing field '" + std::string(key) + "'");
    return *n;
  }
  [[noreturn]] void wrong_type(std::string_view key, const toml::node& n, const std::string& want) const {
    throw InputError("field '" + std::string(key) + "' = " + value_text(n) + " has the wrong type: expected " + want);
  }
};

Config::Config() : impl_(std::make_unique<Impl>()) {}
Config::~Config() = default;
Config::Config(const Config& o) : impl_(std::make_unique<Impl>(*o.impl_)) {}
Config& Config::operator=(const Config& o) {
  if (this != &o) impl_ = std::make_unique<Impl>(*o.impl_);
  return *this;
}
Config::Config(Config&&) noexcept = default;
Config& Config::operator=(Config&&) noexcept = default;

Config Config::parse(std::string_view text, const std::string& source) {
  Config c;
  c.impl_->source = source;
  try {
    c.impl_->table = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError(source + ":" + std::to_string(e.source().begin.line) + ": invalid TOML: " +
                     std::string(e.description()));
  }
  return c;
}

Config Config::load(const std::filesystem::path& path) { return parse(read_scene_text(path), path.string()); }

std::string Config::read_scene_text(const std::filesystem::path& path) {
  // A scene is a small regular file: refuse devices (/dev/zero never ends), directories and
  // anything above kMaxSceneFileBytes before reading.
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError("cannot read scene file '" + path.string() + "': " + (ec ? ec.message() : "no such file"));
  if (!std::filesystem::is_regular_file(status))
    throw InputError("scene file '" + path.string() + "' is not a regular file (a directory or a device)");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes > kMaxSceneFileBytes)
    throw InputError("scene file '" + path.string() + "' is " + std::to_string(bytes) + " bytes; at most " +
                     std::to_string(kMaxSceneFileBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read scene file '" + path.string() + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void Config::merge(const Config& overlay) {
  try {
    merge_table(impl_->table, overlay.impl_->table, "");
  } catch (const InputError& e) {
    throw InputError(overlay.impl_->source + ": " + e.what());
  }
}

void Config::extend(const Config& overlay) {
  try {
    merge_table(impl_->table, overlay.impl_->table, "", true);
  } catch (const InputError& e) {
    throw InputError(overlay.impl_->source + ": " + e.what());
  }
}

void Config::set(std::string_view assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw InputError("--set '" + std::string(assignment) + "': expected key=value, e.g. --set duration=10");
  }
  // One assignment is one line: a line break (or NUL) would let TOML read more keys than the one
  // named, or drop the rest.
  if (assignment.find_first_of(std::string_view("\n\r\0", 3)) != std::string_view::npos)
    throw InputError("--set '" + std::string(assignment.substr(0, eq)) +
                     "=...': the value contains a line break; one --set sets one key");
  const std::string key(assignment.substr(0, eq));
  for (std::string_view rest = key;;) {  // a.b.c: no empty part
    const auto dot = rest.find('.');
    if (rest.substr(0, dot).empty())
      throw InputError("--set '" + std::string(assignment) + "': the key '" + key + "' has an empty part");
    if (dot == std::string_view::npos) break;
    rest = rest.substr(dot + 1);
  }
  const toml::table parsed = parse_override_value(assignment.substr(eq + 1));
  // Build the nested overlay {a = {b = value}} for key "a.b" and merge it.
  toml::table overlay;
  toml::table* cursor = &overlay;
  std::string_view rest = key;
  for (auto dot = rest.find('.'); dot != std::string_view::npos; dot = rest.find('.')) {
    auto [it, inserted] = cursor->insert(rest.substr(0, dot), toml::table{});
    cursor = it->second.as_table();
    rest = rest.substr(dot + 1);
  }
  parsed.get("v")->visit([&](const auto& v) { cursor->insert_or_assign(rest, v); });
  try {
    merge_table(impl_->table, overlay, "");
  } catch (const InputError& e) {
    throw InputError("--set " + std::string(assignment) + ": " + e.what());
  }
}

std::size_t Config::array_size(std::string_view key) const {
  const toml::node& n = impl_->node(key);
  auto a = n.as_array();
  if (a == nullptr) impl_->wrong_type(key, n, "array");
  return a->size();
}

Config Config::element(std::string_view key, std::size_t index) const {
  const std::string path = std::string(key) + "[" + std::to_string(index) + "]";
  const toml::node& n = impl_->node(path);
  auto t = n.as_table();
  if (t == nullptr) impl_->wrong_type(path, n, "table");
  Config c;
  c.impl_->table = *t;
  c.impl_->source = path;
  return c;
}

Config Config::nested_under(std::string_view key) const {
  Config c;
  c.impl_->table.insert(key, impl_->table);
  c.impl_->source = impl_->source;
  return c;
}

std::vector<std::string> Config::keys() const {
  std::vector<std::string> k;
  for (auto&& [name, value] : impl_->table) k.emplace_back(name.str());
  return k;
}

void Config::erase(std::string_view key) { impl_->table.erase(key); }

const std::string& Config::source() const { return impl_->source; }

bool Config::has(std::string_view key) const { return impl_->table.at_path(key).node() != nullptr; }

double Config::number(std::string_view key, Range range) const {
  const toml::node& n = impl_->node(key);
  double v = 0.0;
  if (auto f = n.as_floating_point()) v = f->get();
  else if (auto i = n.as_integer()) v = static_cast<double>(i->get());
  else impl_->wrong_type(key, n, "number");
  if (!range.contains(v)) {
    throw InputError("field '" + std::string(key) + "' = " + format_number(v) + " is out of range " + range.describe());
  }
  return v;
}

std::int64_t Config::integer(std::string_view key, std::int64_t min, std::int64_t max) const {
  const toml::node& n = impl_->node(key);
  auto i = n.as_integer();
  if (i == nullptr) impl_->wrong_type(key, n, "integer");
  const std::int64_t v = i->get();
  if (v < min || v > max) {
    throw InputError("field '" + std::string(key) + "' = " + std::to_string(v) + " is out of range [" +
                     std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return v;
}

bool Config::boolean(std::string_view key) const {
  const toml::node& n = impl_->node(key);
  auto b = n.as_boolean();
  if (b == nullptr) impl_->wrong_type(key, n, "boolean (true or false)");
  return b->get();
}

std::string Config::string(std::string_view key) const {
  const toml::node& n = impl_->node(key);
  auto s = n.as_string();
  if (s == nullptr) impl_->wrong_type(key, n, "string");
  return s->get();
}

std::string Config::choice(std::string_view key, const std::vector<std::string>& allowed) const {
  std::string v = string(key);
  std::string list;
  for (const auto& a : allowed) {
    if (a == v) return v;
    list += (list.empty() ? "" : ", ") + a;
  }
  throw InputError("field '" + std::string(key) + "' = \"" + v + "\" is not one of: " + list);
}

std::vector<double> Config::numbers(std::string_view key, Range range) const {
  const toml::node& n = impl_->node(key);
  auto a = n.as_array();
  if (a == nullptr) impl_->wrong_type(key, n, "array of numbers");
  std::vector<double> out;
  for (const auto& e : *a) {
    std::optional<double> v = e.value<double>();
    if (!v) impl_->wrong_type(key, n, "array of numbers");
    if (!range.contains(*v)) {
      throw InputError("field '" + std::string(key) + "' has element " + format_number(*v) + " out of range " +
                       range.describe());
    }
    out.push_back(*v);
  }
  return out;
}

Vec2 Config::vec2(std::string_view key) const {
  std::vector<double> v = numbers(key);
  if (v.size() != 2) {
    throw InputError("field '" + std::string(key) + "' must be an array of 2 numbers, got " + std::to_string(v.size()));
  }
  return {v[0], v[1]};
}

std::vector<std::int64_t> Config::integers(std::string_view key, std::int64_t min, std::int64_t max) const {
  const toml::node& n = impl_->node(key);
  auto a = n.as_array();
  if (a == nullptr || a->empty()) impl_->wrong_type(key, n, "non-empty array of integers");
  std::vector<std::int64_t> out;
  for (const auto& e : *a) {
    auto i = e.as_integer();
    if (i == nullptr) impl_->wrong_type(key, n, "non-empty array of integers");
    if (i->get() < min || i->get() > max) {
      throw InputError("field '" + std::string(key) + "' has element " + std::to_string(i->get()) +
                       " out of range [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    out.push_back(i->get());
  }
  return out;
}

std::vector<std::string> Config::choices(std::string_view key, const std::vector<std::string>& allowed) const {
  const toml::node& n = impl_->node(key);
  auto a = n.as_array();
  if (a == nullptr || a->empty()) impl_->wrong_type(key, n, "non-empty array of strings");
  std::vector<std::string> out;
  std::string list;
  for (const auto& name : allowed) list += (list.empty() ? "" : ", ") + name;
  for (const auto& e : *a) {
    auto v = e.as_string();
    if (v == nullptr) impl_->wrong_type(key, n, "non-empty array of strings");
    if (std::find(allowed.begin(), allowed.end(), v->get()) == allowed.end()) {
      throw InputError("field '" + std::string(key) + "' has element \"" + v->get() + "\", not one of: " + list);
    }
    out.push_back(v->get());
  }
  return out;
}

std::string Config::literal(std::string_view key) const { return value_text(impl_->node(key)); }

nlohmann::ordered_json Config::to_json() const { return node_to_json(impl_->table); }

std::string Config::to_toml() const {
  std::ostringstream s;
  s << impl_->table << '\n';
  return s.str();
}

}  // namespace jellysim::config
