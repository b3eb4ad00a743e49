#pragma once
// Experiments and scenes are data (a TOML file each, compiled in) run by one generic command.
// Each experiment is a function from its resolved configuration to files in an output directory.
#include "jellysim/config/config.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/scene/resolve.hpp"
#include "jellysim/sim/time_stepping.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace jellysim::experiments {

/// What an experiment gets: its configuration (defaults + scene file + --set), where to write, and
/// a progress callback for long runs (may be empty).
struct Checkpointing;  // jellyfish_runs.hpp

struct Context {
  config::Config config;
  sim::ProgressCallback progress;
  /// `jellysim simulate --checkpoint-every` / `--resume` (null: no checkpoints).
  std::shared_ptr<const Checkpointing> checkpoints{};
  /// The 3D frames rendered so far of all (`jellysim run`'s render stage; may be empty).
  std::function<void(std::size_t done, std::size_t total)> render_progress{};
};

/// Result of an experiment run. `failure` non-empty means the run failed (exit code 1) after
/// writing what it had.
struct Outcome {
  std::string failure;
};

/// An experiment validates its whole configuration in `prepare` (throwing InputError) before
/// anything is written, then `run` writes its outputs.
struct Experiment {
  std::string name;
  std::string description;
  std::string definition_path;  ///< embedded TOML file with the defaults, e.g. "scenes/swinging-bar.toml"
  std::function<std::function<Outcome(const io::OutputDir&)>(const Context&)> prepare;
  /// Optional embedded scene whose fields the definition extends (e.g. "scenes/jellyfish.toml"): the
  /// defaults are the base scene's, overridden and extended by the definition file.
  std::string base_path{};
  /// Optional embedded scene file laid over the base before the definition (like a user's scene
  /// file), e.g. "scenes/jellyfish-thesis.toml": the chapter 8 studies run on the thesis's tank.
  std::string base_overlay_path{};
  /// The definition also has the [render] section of the 3D pipeline (scene/render_settings.hpp),
  /// whose defaults come from its parameter table.
  bool renders = false;
  /// The shorthand options of `jellysim experiment` this experiment takes (shorthand_options()'s
  /// names, e.g. "re" for driven-cavity's --re); each sets a key its configuration has.
  std::vector<std::string> shorthands{};
};

/// A command-line option of `jellysim experiment` that sets one key of the experiments declaring it
/// (Experiment::shorthands): `--NAME VALUE` is `--set KEY=VALUE`.
struct ShorthandOption {
  std::string name;             ///< without the "--"
  std::string key;              ///< the configuration key it sets
  std::string help;             ///< the command line's help text
  std::string type_name{};      ///< the value's name in the help, e.g. N (empty: the parser's own)
  bool quoted = false;          ///< the value is text, set as a TOML string (e.g. --grids 24x32,48x64)
  int min_count = 0, max_count = 0;  ///< max_count > 0: an integer in [min_count, max_count]
};

/// Every shorthand option, in the order `jellysim experiment --help` lists them.
const std::vector<ShorthandOption>& shorthand_options();
/// The --set assignments of the shorthand options given on the command line ((name, value), value
/// as typed) for `e`; an option `e` does not declare is an InputError naming it (exit 2).
std::vector<scene::Shorthand> shorthands_for(const Experiment& e,
                                             const std::vector<std::pair<std::string, std::string>>& given);

const std::vector<Experiment>& all_experiments();
/// Finds an experiment by name; throws InputError listing the known names.
const Experiment& find_experiment(const std::string& name);
/// The experiment's default configuration, parsed from its embedded definition file.
config::Config default_config(const Experiment& experiment);
/// Text of an embedded file; throws std::logic_error when absent (a build error).
std::string_view embedded_text(std::string_view path);
/// The text of a scene or experiment definition: the embedded file, or for a definition that is a
/// parameter table (the jellyfish scene, driven-cavity, oval-membrane) the text generated from it.
std::string definition_text(std::string_view path);

/// Writes timings.json: the run's wall-clock (and CPU) measurements, which differ from run to run.
/// They live here (and in summary.json's wall_seconds), never in a CSV, so that every CSV of a
/// command is byte-identical for the same inputs.
void write_timings(const io::OutputDir& out, const nlohmann::ordered_json& timings);

/// Runs `run` into `out`; an allocation that fails (std::bad_alloc) anywhere in it, or a RunError
/// it throws (an output that could not be written), becomes the run's failure, the first saying in
/// which stage (core::MemoryStage), with summary.json written (status "failed"; issue 35).
Outcome run_guarded(const Experiment& e, const Context& ctx, const std::function<Outcome(const io::OutputDir&)>& run,
                    const io::OutputDir& out);

/// Writes summary.json: status, version, command, key figures and the resolved configuration.
void write_summary(const io::OutputDir& out, const std::string& command, const config::Config& config,
                   const nlohmann::ordered_json& figures, const std::string& failure);

}  // namespace jellysim::experiments
