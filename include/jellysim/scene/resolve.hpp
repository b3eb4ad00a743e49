#pragma once
// The one resolution of a run's configuration (issue 36): the defaults of an experiment or a
// built-in scene, a scene file laid over them, the `--set` overrides, `--duration` and an
// experiment's shorthand options (e.g. driven-cavity's --re), with one set of rules and errors.
// Used by the CLI (every command, `view` included), `jellysim batch` and the Python module.
#include "jellysim/config/config.hpp"

#include <optional>
#include <string>
#include <vector>

namespace jellysim::scene {

/// A command-line option that sets one key of the configuration: `--option value` is `key=value`.
struct Shorthand {
  std::string option, key, value;
};

/// What is laid over the defaults, in this order.
struct ConfigSources {
  std::optional<config::Config> scene_file;  ///< a scene file (or scene text), when one is given
  std::string scene_name;                ///< its path (or "scene text"), for messages
  /// When not empty: the kind the scene file must be (its `scene` field); a file without the field
  /// is accepted unless `kind_required`.
  std::string expected_kind{};
  bool kind_required = false;
  std::vector<std::string> sets{};   ///< `--set key=value`, applied in order; `scene` is refused
  std::optional<double> duration{};  ///< `--duration S`; refused together with `--set duration`
  std::vector<Shorthand> shorthands{};
};

/// The defaults, then the scene file, the `--set` overrides, `--duration` and the shorthands.
/// `subject` names what is resolved in messages, e.g. "experiment 'driven-cavity'". Throws
/// InputError naming the option or field at fault; the result is not yet validated by a reader.
config::Config resolve_config(config::Config defaults, const ConfigSources& sources, const std::string& subject);

/// The built-in jellyfish scene (scenes/jellyfish.toml, the text generated from jellyfish_scene()),
/// what `simulate`, `view`, `batch` and `jellysim.Simulation` start from.
config::Config builtin_jellyfish_scene();

}  // namespace jellysim::scene
