#pragma once
// Scene and experiment configuration: a TOML document whose built-in default (compiled in) is also
// its schema. User files and `--set key=value` overrides may only change fields that the default
// has, with a value of the same type; typed getters check ranges. Every error is an InputError
// naming the field, the value and what is allowed.
#include "jellysim/math/vec2.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace jellysim::config {

/// A number as error messages write it (10 significant digits).
std::string format_number(double v);

/// A closed or open interval used in range checks and error messages.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  bool contains(double v) const;
  std::string describe() const;  ///< e.g. "(0, inf)" or "[1, 10000]"
};

class Config {
 public:
  Config();
  ~Config();
  Config(const Config&);
  Config& operator=(const Config&);
  Config(Config&&) noexcept;
  Config& operator=(Config&&) noexcept;

  /// Parses TOML text; `source` names it in error messages (a file path or "built-in scene").
  static Config parse(std::string_view text, const std::string& source);
  /// Reads and parses a TOML file: a regular file of at most kMaxSceneFileBytes (else InputError).
  static Config load(const std::filesystem::path& path);
  /// The text load() parses, with its checks.
  static std::string read_scene_text(const std::filesystem::path& path);
  static constexpr std::uintmax_t kMaxSceneFileBytes = 1u << 20;

  /// Overlays every field of `overlay` onto this configuration. Fields must exist here and have
  /// the same type (an integer is accepted where a float is expected).
  void merge(const Config& overlay);
  /// Like merge, but fields absent here are added (builds an experiment's schema from a base scene
  /// plus the experiment's own fields). Existing fields keep their type checks.
  void extend(const Config& overlay);
  /// Applies one `key=value` override; the value is read as a TOML value (number, boolean,
  /// string with or without quotes, or array such as [0, -0.05]).
  void set(std::string_view assignment);

  bool has(std::string_view key) const;
  /// Number of entries of an array field (e.g. the [[objects]] of a scene).
  std::size_t array_size(std::string_view key) const;
  /// Entry `index` of an array of tables as a configuration of its own, named "key[index]" in
  /// messages; it has no schema, so read its fields with has() and the typed getters.
  Config element(std::string_view key, std::size_t index) const;
  /// This configuration as the table `key` of an otherwise empty one (to merge as an overlay).
  Config nested_under(std::string_view key) const;
  /// The names of the top-level fields.
  std::vector<std::string> keys() const;
  /// Removes a top-level field if present.
  void erase(std::string_view key);
  /// Where the configuration came from (a file path, "built-in scene", "objects[2]").
  const std::string& source() const;
  double number(std::string_view key, Range range = {}) const;
  std::int64_t integer(std::string_view key, std::int64_t min, std::int64_t max) const;
  bool boolean(std::string_view key) const;
  std::string string(std::string_view key) const;
  /// A string that must be one of `allowed`.
  std::string choice(std::string_view key, const std::vector<std::string>& allowed) const;
  Vec2 vec2(std::string_view key) const;
  /// A non-empty array of integers, each in [min, max].
  std::vector<std::int64_t> integers(std::string_view key, std::int64_t min, std::int64_t max) const;
  /// A non-empty array of strings, each one of `allowed`.
  std::vector<std::string> choices(std::string_view key, const std::vector<std::string>& allowed) const;
  std::vector<double> numbers(std::string_view key, Range range = {}) const;

  /// The value of `key` as TOML text (e.g. 0.7, "fft", [96, 128]); throws InputError when absent.
  std::string literal(std::string_view key) const;
  /// The resolved configuration as JSON (for summary.json).
  nlohmann::ordered_json to_json() const;
  /// The resolved configuration as TOML text (can be fed back to `jellysim run`).
  std::string to_toml() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace jellysim::config
