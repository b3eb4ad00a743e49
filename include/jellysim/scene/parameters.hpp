#pragma once
// Self-describing scene parameters: one table per scene kind, each entry a key, a type, a default,
// a unit, an allowed range and a one-line description. The table alone drives the built-in scene
// file (its TOML text is generated from it), validation and its error messages, `--set`, `jellysim
// scenes`, the viewer's live-parameter ranges and docs/parameters.md.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::scene {

enum class Type {
  number,    ///< a float (an integer is accepted), within `range`
  integer,   ///< within `range`
  boolean,
  text,      ///< a free string
  choice,    ///< one of `choices`
  vec2,      ///< [x, y], each within `range`
  integers,  ///< `length` integers (0: any non-empty count), each within `range`
  numbers,   ///< `length` numbers (0: any count, possibly none), each within `range`
  choices,   ///< `length` strings (0: any non-empty count), each one of `choices`
  tables,    ///< an array of tables (e.g. [[objects]]), validated by the scene's reader
};

/// The range a live control (the viewer's slider) offers: inside the allowed range, and finite.
struct Slider {
  double min = 0.0, max = 0.0;
  bool logarithmic = false;
  bool defined() const { return max > min; }
};

struct Parameter {
  std::string key;          ///< dotted path, e.g. "jellyfish.frequency"
  Type type = Type::number;
  std::string value;        ///< the default as a TOML value, e.g. "0.7", "[96, 128]", "\"fft\""; empty in a
                            ///< table of rules whose defaults are each scene's own
  std::string unit;         ///< SI unit ("m", "Hz", "m²/s"); empty: dimensionless or not a number
  config::Range range{};        ///< numbers, integers, vec2 and integers' elements
  std::vector<std::string> choices{};  ///< choice and choices
  int length = 0;           ///< integers, numbers and choices: the required count (0: any)
  std::string description;  ///< one line
  Slider slider{};          ///< for parameters the viewer changes live
};

/// Shorthands for table entries.
namespace param {
Parameter number(std::string key, std::string value, std::string unit, config::Range range, std::string description,
                 Slider slider = {});
Parameter integer(std::string key, std::string value, double min, double max, std::string description);
Parameter boolean(std::string key, std::string value, std::string description);
/// `value` without quotes.
Parameter choice(std::string key, std::string value, std::vector<std::string> choices, std::string description);
Parameter vec2(std::string key, std::string value, std::string unit, config::Range range, std::string description);
/// [x, y, z] or [r, g, b]: three numbers, each within `range` (Type::numbers of length 3).
Parameter vec3(std::string key, std::string value, std::string unit, config::Range range, std::string description);
}  // namespace param

/// A scene kind's parameters, in the order the scene file lists them; tables ([tank], …) follow
/// the top-level keys in order of first appearance.
class ParameterTable {
 public:
  /// `no_default`: what the reference page shows for a parameter without a default (a table of
  /// rules: "per scene"; the [[objects]] fields: "none").
  ParameterTable(std::string name, std::string preamble, std::vector<Parameter> parameters,
                 std::string no_default = "per scene");

  const std::string& name() const { return name_; }
  const std::vector<Parameter>& parameters() const { return parameters_; }
  /// The parameter `key`; throws std::logic_error when the table has none (a programming error).
  const Parameter& at(std::string_view key) const;
  const Parameter* find(std::string_view key) const;

  /// The built-in scene as TOML: the preamble, then every parameter with its default and a comment
  /// giving its description, unit and allowed values. With `values`, each parameter's value is
  /// taken from there instead (a resolved configuration).
  std::string scene_toml(const config::Config* values = nullptr) const;
  /// The reference page (docs/parameters.md's section for this table): a Markdown table per TOML
  /// table with key, default, unit, allowed values and description.
  std::string reference_markdown() const;
  /// The built-in scene, parsed ("built-in <name> scene" in messages); only for tables with defaults.
  config::Config defaults() const;

 private:
  std::string name_;
  std::string preamble_;
  std::vector<Parameter> parameters_;
  std::string no_default_;
};

/// "(0, 5]", "[2, 1000]", "one of: fft, direct", "true or false": the allowed values in words.
std::string allowed_values(const Parameter& p);

/// Typed reads of a scene configuration, checked against the table: the type and range come from
/// the parameter, so every reader of a key applies the same rule. Errors are InputErrors naming the
/// field, its value and what is allowed.
class Reader {
 public:
  Reader(const config::Config& config, const ParameterTable& table) : config_(config), table_(table) {}

  double number(std::string_view key) const;
  std::int64_t integer(std::string_view key) const;
  bool boolean(std::string_view key) const;
  std::string text(std::string_view key) const;
  std::string choice(std::string_view key) const;
  Vec2 vec2(std::string_view key) const;
  std::vector<std::int64_t> integers(std::string_view key) const;
  std::vector<double> numbers(std::string_view key) const;
  std::vector<std::string> choices(std::string_view key) const;

  /// Checks every parameter of the table present in the configuration by its type and range.
  void validate_all() const;
  /// Whether `key` holds the table's default (numbers compared as numbers, [[tables]] by count);
  /// for fields a mode ignores or refuses unless left alone.
  bool holds_default(std::string_view key) const;

  const config::Config& config() const { return config_; }
  const ParameterTable& table() const { return table_; }

 private:
  const Parameter& expect(std::string_view key, Type type) const;
  const config::Config& config_;
  const ParameterTable& table_;
};

}  // namespace jellysim::scene
