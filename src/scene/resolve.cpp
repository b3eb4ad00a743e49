#include "jellysim/scene/resolve.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace jellysim::scene {
namespace {

/// A scene file of another kind than the one expected (or without one, where it is required).
void check_kind(const config::Config& file, const ConfigSources& s) {
  if (s.expected_kind.empty()) return;
  const std::string example = "(scene = \"" + s.expected_kind + "\")";
  if (!file.has("scene")) {
    if (s.kind_required) throw InputError(s.scene_name + ": missing field 'scene' " + example);
    return;
  }
  const std::string kind = file.string("scene");
  if (kind != s.expected_kind)
    throw InputError(s.scene_name + ": expected a " + s.expected_kind + " scene " + example + ", not '" + kind + "'");
}

/// `--set key=value`s: the kind picks the parameter table, so it comes from the file, never --set.
void apply_sets(config::Config& config, const ConfigSources& s) {
  for (const std::string& assignment : s.sets) {
    const std::string key = assignment.substr(0, assignment.find('='));
    if (key == "scene")
      throw InputError("--set scene: the scene kind cannot be changed by --set; give a scene file instead");
    if (s.duration && key == "duration")
      throw InputError("--duration and --set duration both give the duration: give it once");
    config.set(assignment);
  }
}

}  // namespace

config::Config resolve_config(config::Config defaults, const ConfigSources& sources, const std::string& subject) {
  config::Config config = std::move(defaults);
  if (sources.scene_file) {
    check_kind(*sources.scene_file, sources);
    config.merge(*sources.scene_file);
  }
  apply_sets(config, sources);
  if (sources.duration) {
    if (!config.has("duration")) throw InputError("--duration: " + subject + " has no duration");
    config.set("duration=" + io::format_double(*sources.duration));
  }
  for (const auto& [option, key, value] : sources.shorthands) {
    if (!config.has(key)) throw InputError("--" + option + ": " + subject + " has no " + key);
    config.set(key + "=" + value);
  }
  return config;
}

config::Config builtin_jellyfish_scene() {
  return config::Config::parse(jellyfish_scene().scene_toml(), "built-in scenes/jellyfish.toml");
}

}  // namespace jellysim::scene
