// The jellysim command line: thin layer over the library (see docs/cli.md).
// Exit codes: 0 success, 1 failed run, 2 bad usage or input.
#include "jellysim/experiments/batch.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/experiments/optimize.hpp"
#include "jellysim/experiments/embedded_data.hpp"
#include "jellysim/experiments/progress.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/core/interrupt.hpp"
#include "jellysim/core/memory.hpp"
#include "jellysim/io/checkpoint.hpp"
#include "jellysim/io/ib2d_files.hpp"
#include "jellysim/jellyfish/hoover_miller.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/reference.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellysim/scene/resolve.hpp"

#include "jellysim/viewer/viewer.hpp"
#include "jellysim/viewer/viewer_3d.hpp"
#ifdef JELLYSIM_MPI
#include "mpi_backend.hpp"
#endif

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <fstream>
#include <sstream>
#include <iostream>
#include <optional>
#include <unistd.h>

namespace js = jellysim;

namespace {

constexpr int kExitFailedRun = 1;
constexpr int kExitBadInput = 2;

/// Options shared by every results-producing command.
struct RunOptions {
  std::string out;
  std::vector<std::string> sets;
  std::optional<double> duration;
  bool quiet = false;
  std::string progress = "bar";  ///< --progress: bar, json or none (progress_mode())
  /// Options that set a key some experiments have (e.g. driven-cavity): --solver, --re, --grid,
  /// --steady-tolerance: (option, key, value).
  std::vector<js::scene::Shorthand> shorthands;
  /// `simulate --checkpoint-every` / `--resume` (null: none); with `resume`, out is the run's directory.
  std::shared_ptr<const js::experiments::Checkpointing> checkpoints{};
  bool resume = false;
};

/// CLI::Range, which lets NaN through (`--checkpoint-every nan` never checkpointed): a number in
/// [lo, hi] (open_below: (lo, hi]).
CLI::Validator finite_range(double lo, double hi, bool open_below = false) {
  const std::string range = std::string(open_below ? "(" : "[") + js::config::format_number(lo) + ", " +
                            js::config::format_number(hi) + "]";
  return CLI::Validator(
      [lo, hi, open_below, range](std::string& text) -> std::string {
        double value = 0.0;
        std::size_t end = 0;
        try {
          value = std::stod(text, &end);
        } catch (const std::exception&) {
          end = 0;
        }
        if (end == text.size() && (open_below ? value > lo : value >= lo) && value <= hi) return {};
        return "'" + text + "' is not a number in " + range;
      },
      "NUMBER in " + range, "finite range");
}

/// --memory-limit SIZE: the memory budget of the run (core/memory.hpp), set when parsed.
void add_memory_limit_option(CLI::App& cmd) {
  cmd.add_option_function<std::string>(
         "--memory-limit",
         [](const std::string& size) { js::core::set_memory_budget_bytes(js::core::parse_byte_size(size)); },
         "Memory the run may use, e.g. 4G or 512M (default: half of this machine's, or less where ulimit or the "
         "cgroup leave less); a run estimated to need more is refused before it starts")
      ->type_name("SIZE")
      ->check(CLI::Validator(
          [](std::string& size) -> std::string {
            try {
              js::core::parse_byte_size(size);
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return {};
          },
          "SIZE", "memory size"));
}

/// --progress bar|json|none, of every long command (README, "Using it").
void add_progress_option(CLI::App& cmd, std::string& mode) {
  cmd.add_option("--progress", mode,
                 "Progress: bar (a line redrawn on a terminal; the default), json (one JSON object per line on stderr: "
                 "stage, time, duration, fraction, steps, eta_seconds, at most 5 a second, then a status line) or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"bar", "json", "none"}));
}

/// The progress display asked for: --quiet turns the default bar off (an explicit json stays).
std::string progress_mode(const std::string& progress, bool quiet) {
  return quiet && progress == "bar" ? "none" : progress;
}

/// `set_example` is a working example of --set for this command (the test
/// Cli.EverySetExampleInTheHelpRuns runs each one).
void add_run_options(CLI::App& cmd, RunOptions& o, const std::string& default_out, const std::string& set_example) {
  o.out = default_out;
  cmd.add_option("--out", o.out, "Directory for the results (created if missing)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& dir) -> std::string {
            if (dir.empty()) return "the directory name is empty";
            if (dir.front() == '-') return "'" + dir + "' looks like an option: give the directory after --out";
            return {};
          },
          "DIR", "output directory"));
  cmd.add_option("--set", o.sets,
                 "Override a parameter: --set key=value (dotted keys, e.g. " + set_example +
                     "). Repeatable. `jellysim scenes NAME` lists every key.")
      ->type_name("KEY=VALUE");
  cmd.add_option("--duration", o.duration, "Simulated seconds (same as --set duration=S)")
      ->type_name("S")
      ->check(CLI::Validator(
          [](std::string& value) -> std::string { return value.empty() ? "the duration is empty" : std::string(); },
          "S", "duration"));
  cmd.add_flag("--quiet", o.quiet, "No progress display");
  add_progress_option(cmd, o.progress);
  add_memory_limit_option(cmd);
}

/// `--checkpoint-every S` / `--resume DIR` of `simulate` and `run`.
struct CheckpointOptions {
  double every = 0.0;
  std::string resume_dir;
};

void add_checkpoint_options(CLI::App& cmd, CheckpointOptions& c, const std::string& more) {
  auto* every = cmd.add_option("--checkpoint-every", c.every,
                               "Write the whole state to OUT/checkpoint.jellysim at the first frame after every S "
                               "simulated seconds, (0, 1e9]; a killed run continues with --resume OUT (removed when "
                               "the run completes)" + more)
                    ->type_name("S")
                    ->check(finite_range(1e-9, 1e9));
  cmd.add_option("--resume", c.resume_dir,
                 "Continue the run whose checkpoint is in DIR, into DIR, as it was configured (no scene, --set, "
                 "--duration or --out): the outputs are those of the uninterrupted run, byte for byte")
      ->type_name("DIR")
      ->excludes(every)
      ->excludes("scene")
      ->excludes("--set")
      ->excludes("--duration")
      ->excludes("--out");
}

/// The shorthand options the experiments declare (experiments::shorthand_options(): driven-cavity's
/// --re, the SPH experiments' --threads, ...); each one given is recorded as (name, value) when parsed.
void add_shorthand_options(CLI::App& cmd, std::vector<std::pair<std::string, std::string>>& given) {
  for (const js::experiments::ShorthandOption& o : js::experiments::shorthand_options()) {
    const auto record = [&given, name = o.name](const std::string& value) { given.emplace_back(name, value); };
    if (o.max_count > 0) {
      cmd.add_option_function<int>("--" + o.name, [record](int n) { record(std::to_string(n)); }, o.help)
          ->check(CLI::Range(o.min_count, o.max_count));
    } else {
      CLI::Option* option = cmd.add_option_function<std::string>(
          "--" + o.name, [record](const std::string& value) { if (!value.empty()) record(value); }, o.help);
      if (!o.type_name.empty()) option->type_name(o.type_name);
    }
  }
}

/// `--progress json`: a stage's lines on stderr (experiments/progress.hpp).
js::sim::ProgressCallback json_progress(const std::string& stage) {
  auto tracker = std::make_shared<js::experiments::ProgressTracker>(stage);
  auto lock = std::make_shared<std::mutex>();  // an experiment may run several simulations at once
  return [tracker, lock](double t, double duration, std::int64_t steps) {
    const std::lock_guard<std::mutex> guard(*lock);
    if (auto line = tracker->simulation(t, duration, steps); !line.is_null()) js::experiments::write_progress_line(line);
  };
}

/// `--progress json`'s lines of a count (frames rendered, batch runs), safe to call from several threads.
std::function<void(std::size_t, std::size_t)> json_count_progress(const std::string& stage, const std::string& unit) {
  auto tracker = std::make_shared<js::experiments::ProgressTracker>(stage);
  auto lock = std::make_shared<std::mutex>();
  return [tracker, lock, unit](std::size_t done, std::size_t total) {
    const std::lock_guard<std::mutex> guard(*lock);
    if (auto line = tracker->count(done, total, unit); !line.is_null()) js::experiments::write_progress_line(line);
  };
}

/// `run`'s render stage: frames rendered of all, on a terminal (bar) or as JSON lines.
std::function<void(std::size_t, std::size_t)> make_render_progress(const std::string& mode) {
  if (mode == "json") return json_count_progress("render", "frames");
  if (mode != "bar" || !::isatty(STDOUT_FILENO)) return {};
  return [](std::size_t done, std::size_t total) {
    std::printf("\r  rendering frame %zu / %zu   ", done, total);
    if (done == total) std::printf("\n");
    std::fflush(stdout);
  };
}

/// With `--progress json`, the closing status line unless one was written; returns `exit_code`.
int report_status(const std::string& mode, int exit_code, const std::string& out, const std::string& message) {
  if (mode == "json" && !js::experiments::status_line_written())
    js::experiments::write_progress_line(js::experiments::progress_status(exit_code, out, message));
  return exit_code;
}

/// Progress of a simulation: the terminal display (bar: simulated time, steps and ETA, redrawn at
/// most five times a second), JSON lines (json), or none.
js::sim::ProgressCallback make_progress(const std::string& mode) {
  if (mode == "json") return json_progress("simulate");
  if (mode != "bar" || !::isatty(STDOUT_FILENO)) return {};
  using clock = std::chrono::steady_clock;
  auto start = std::make_shared<clock::time_point>(clock::now());
  auto last = std::make_shared<clock::time_point>(clock::time_point{});
  return [start, last](double t, double duration, std::int64_t steps) {
    const auto now = clock::now();
    if (now - *last < std::chrono::milliseconds(200) && t < duration) return;
    *last = now;
    const double elapsed = std::chrono::duration<double>(now - *start).count();
    const double eta = t > 0 ? elapsed * (duration - t) / t : 0.0;
    std::printf("\r  t = %.3f / %.3f s   steps %lld   elapsed %.1f s   ETA %.1f s   ", t, duration,
                static_cast<long long>(steps), elapsed, eta);
    if (t >= duration) std::printf("\n");
    std::fflush(stdout);
  };
}

/// A scene file given to a command: `path`'s configuration, and the kind it must be (none: any).
struct SceneFile {
  std::optional<js::config::Config> config;
  std::string path;
  std::string expected_kind{};
};

/// Resolves the configuration (defaults, scene file, --set, --duration: scene::resolve_config),
/// validates it, and only then creates the output directory and runs.
int run_experiment(const js::experiments::Experiment& e, const SceneFile& scene, const RunOptions& o) {
  const js::scene::ConfigSources sources{scene.config, scene.path, scene.expected_kind, false, o.sets, o.duration,
                                         o.shorthands};
  const std::string mode = progress_mode(o.progress, o.quiet);
  js::experiments::Context ctx{
      js::scene::resolve_config(js::experiments::default_config(e), sources, "experiment '" + e.name + "'"),
      make_progress(mode), o.checkpoints, make_render_progress(mode)};
  auto run = e.prepare(ctx);
  const js::io::OutputDir out =
      o.resume ? js::io::OutputDir::for_resumed_run(o.out, e.name) : js::io::OutputDir::for_run(o.out, e.name);
  js::core::install_interrupt_handlers();  // from here a first SIGINT/SIGTERM/SIGHUP stops at a step boundary
  const js::experiments::Outcome outcome = js::experiments::run_guarded(e, ctx, run, out);
  const bool resumable = o.checkpoints && std::filesystem::exists(out.file(js::io::kCheckpointName));
  out.finish_manifest(resumable);  // a resumable run keeps its id, which its checkpoint carries
  const std::string resume_hint =
      resumable ? "  (continue it with: jellysim " + o.checkpoints->how.command + " --resume " + out.path().string() + ")\n"
                : "";
  if (const int signal = js::core::interrupt_signal(); signal != 0 && !outcome.failure.empty()) {
    std::cerr << "jellysim: " << outcome.failure << "; results so far are in " << out.path().string() << "\n"
              << resume_hint;
    return report_status(mode, 128 + signal, out.path().string(), outcome.failure);
  }
  if (!outcome.failure.empty()) {
    std::cerr << "jellysim: run failed: " << outcome.failure << "\n  (results so far are in " << out.path().string()
              << ")\n";
    return report_status(mode, kExitFailedRun, out.path().string(), outcome.failure);
  }
  if (!o.quiet) std::cout << e.name << ": results in " << out.path().string() << "\n";
  return report_status(mode, 0, out.path().string(), e.name + ": results in " + out.path().string());
}

/// The experiment a checkpointed command runs: `simulate` the jellyfish scene, `run` its animation.
const js::experiments::Experiment& checkpointed_experiment(const std::string& command) {
  return js::experiments::find_experiment(command == "run" ? "animation" : "jellyfish");
}

/// `jellysim simulate|run --checkpoint-every S`: the configuration as it was given (scene text,
/// --set, --duration) travels in each checkpoint, so that --resume resolves it again exactly.
/// `run` keeps the checkpoint of the simulation's end until its animation is written.
int run_checkpointed_simulation(const std::string& command, const std::string& scene_path, RunOptions o,
                                double every_s) {
  auto checkpoints = std::make_shared<js::experiments::Checkpointing>();
  checkpoints->keep_when_whole = command == "run";
  js::io::Checkpoint& how = checkpoints->how;
  how.command = command;
  how.every_s = every_s;
  how.sets = o.sets;
  if (o.duration) how.duration = js::io::format_double(*o.duration);
  SceneFile scene{{}, scene_path};
  if (!scene_path.empty()) {
    how.scene_text = js::config::Config::read_scene_text(scene_path);
    how.scene_source = scene_path;
    scene.config = js::config::Config::parse(how.scene_text, scene_path);
    if (!scene.config->has("scene") || scene.config->string("scene") != "jellyfish")
      throw js::InputError("--checkpoint-every: " + scene_path + " is not a jellyfish scene (scene = \"jellyfish\"); "
                           "only jellyfish simulations write checkpoints");
  }
  o.checkpoints = std::move(checkpoints);
  return run_experiment(checkpointed_experiment(command), scene, o);
}

/// `jellysim simulate|run --resume DIR`: continues the run whose checkpoint is in DIR, into DIR
/// (`run`: the simulation from its checkpoint, then the whole animation, as the run would have).
int resume_simulation(const std::string& command, const std::string& dir, const RunOptions& given) {
  js::io::Checkpoint c = js::io::read_checkpoint(dir);
  if (c.command != command)
    throw js::InputError("--resume '" + dir + "': the checkpoint is of `jellysim " + c.command + "`, not `" + command +
                         "`");
  RunOptions o;
  o.out = dir;
  o.quiet = given.quiet;
  o.progress = given.progress;
  o.sets = c.sets;
  if (!c.duration.empty()) o.duration = std::strtod(c.duration.c_str(), nullptr);  // written by format_double: exact
  o.resume = true;
  SceneFile scene{{}, c.scene_source};
  if (!c.scene_text.empty()) scene.config = js::config::Config::parse(c.scene_text, c.scene_source);
  auto checkpoints = std::make_shared<js::experiments::Checkpointing>();
  checkpoints->how = std::move(c);
  checkpoints->resume = true;
  checkpoints->keep_when_whole = command == "run";
  o.checkpoints = std::move(checkpoints);
  return run_experiment(checkpointed_experiment(command), scene, o);
}

int run_scene(const std::string& scene_path, const RunOptions& o, const std::string& default_scene) {
  SceneFile scene{{}, scene_path};
  std::string name = default_scene;
  if (!scene_path.empty()) {
    scene.config = js::config::Config::load(scene_path);
    if (!scene.config->has("scene"))
      throw js::InputError(scene_path + ": missing field 'scene' (e.g. scene = \"swinging-bar\")");
    name = scene.config->string("scene");
    // `run` on a jellyfish scene renders it too: the animation job extends the jellyfish scene.
    if (default_scene == "animation" && name == "jellyfish") name = "animation";
  }
  return run_experiment(js::experiments::find_experiment(name), scene, o);
}

/// `jellysim ib2d-jellyfish`: the Hoover–Miller bell at IB2d's resolution N as IB2d's files.
int write_hoover_miller_files(int resolution, const std::string& stem) {
  if (resolution % 8 != 0)
    throw js::InputError("--resolution " + std::to_string(resolution) + " must be a multiple of 8 in [16, 4096]");
  if (stem.empty() || stem.back() == '/')
    throw js::InputError("--out '" + stem + "' needs a file stem after the directory, e.g. ib2d/jelly256");
  js::jellyfish::HooverMillerSpec spec;
  spec.resolution = resolution;
  const js::jellyfish::HooverMillerBell bell = js::jellyfish::hoover_miller_bell(spec);
  const std::filesystem::path path(stem);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  js::io::write_ib2d_structure(bell.structure, path);
  std::cout << "wrote " << stem << ".vertex (" << bell.structure.vertices.size() << " points: " << bell.bell_points
            << " bell, " << 2 * bell.muscle_points << " muscle, " << bell.target_points << " targets), .spring ("
            << bell.structure.springs.size() << "; muscles are rows " << bell.first_muscle_spring + 1 << "-"
            << bell.structure.springs.size() << "), .nonInv_beam (" << bell.structure.non_invariant_beams.size()
            << "), .target (" << bell.structure.targets.size() << ") for " << spec.cells_x() << " x "
            << spec.cells_y() << " cells\n";
  return 0;
}

int list_definitions(const std::string& name) {
  if (name.empty()) {
    for (const auto& e : js::experiments::all_experiments()) {
      std::cout << e.name << "\t" << e.description << "\t(" << e.definition_path << ")\n";
    }
    return 0;
  }
  // The commands that run a built-in definition print it under their own name too.
  const std::string definition = name == "run" ? "animation" : name == "simulate" ? "jellyfish" : name;
  const auto& e = js::experiments::find_experiment(definition);
  std::string text = js::experiments::definition_text(e.definition_path);
  if (e.renders) {
    // The definition's own [render] lines are folded into the full section below (one [render]
    // table, so the output is a scene file that loads).
    std::istringstream lines(text);
    std::string kept;
    bool in_render = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.starts_with("[")) in_render = line.starts_with("[render]") || line.starts_with("[render.");
      if (!in_render) kept += line + "\n";
    }
    const js::config::Config resolved = js::experiments::default_config(e);
    text = kept + "\n# The 3D pipeline's [render] section: every field with this scene's value (docs/parameters.md).\n" +
           js::scene::render_parameters().scene_toml(&resolved);
  }
  std::cout << text;
  return 0;
}

std::string experiment_list() {
  std::string text;
  for (const auto& e : js::experiments::all_experiments()) text += "\n  " + e.name + ": " + e.description;
  return text;
}


/// Options of `jellysim view` beyond the viewer's own (scene, overrides, script sources).
struct ViewCommand {
  std::string scene_path;
  std::vector<std::string> sets;
  std::string script_path;
  std::string inject;
  std::string field = "vorticity";
  bool no_png = false, no_mp4 = false;
  js::viewer::ViewerOptions options;
};

void add_view_options(CLI::App& cmd, ViewCommand& v) {
  auto& o = v.options;
  cmd.add_option("scene", v.scene_path, "Jellyfish scene file (TOML); omitted: the built-in scene")->check(CLI::ExistingFile);
  cmd.add_option("--set", v.sets, "Override a scene parameter: --set key=value (as for `simulate`). Repeatable.")
      ->type_name("KEY=VALUE");
  cmd.add_option("--width", o.width_px, "Window width in pixels, [320, 8192]")->capture_default_str()->check(CLI::Range(320, 8192));
  cmd.add_option("--height", o.height_px, "Window height in pixels, [240, 8192]")->capture_default_str()->check(CLI::Range(240, 8192));
  cmd.add_option("--fps", o.target_fps, "Frame rate to pace to, [0, 240]; 0: as fast as possible")
      ->capture_default_str()->check(CLI::Range(0.0, 240.0));
  cmd.add_option("--speed", o.speed, "Simulated seconds wanted per wall second, (0, 10]")
      ->capture_default_str()->check(CLI::Range(1e-6, 10.0));
  cmd.add_option("--min-fps", o.min_fps, "Lowest frame rate the simulation may slow the viewer to while keeping up, "
                                         "[1, 240]")->capture_default_str()->check(CLI::Range(1.0, 240.0));
  cmd.add_option("--3d-scale", o.render_scale, "Resolution of the 3D panel relative to the window, (0, 1]")
      ->capture_default_str()->check(CLI::Range(0.05, 1.0));
  cmd.add_option("--frames", o.frames, "Quit after this many frames (0: when the window is closed)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd.add_flag("--paused", o.start_paused, "Start paused (space runs, s steps)");
  add_memory_limit_option(cmd);
  cmd.add_option("--field", v.field, "Fluid quantity shown: vorticity or speed")
      ->capture_default_str()->check(CLI::IsMember({"vorticity", "speed"}));
  cmd.add_option("--script", v.script_path, "File of timed input events (frame, event; see docs/viewer.md)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--inject", v.inject, "Timed input events inline, ';'-separated, e.g. \"10 pause; 20 drag 200 300 260 300\"");
  cmd.add_option("--screenshot", o.screenshot, "Save the last frame as this PNG at exit")->type_name("FILE");
  cmd.add_option("--record", o.record_dir, "Record every frame into DIR: frame_NNNNN.png and view.mp4")->type_name("DIR");
  cmd.add_flag("--no-png", v.no_png, "With --record: no PNG per frame");
  cmd.add_flag("--no-mp4", v.no_mp4, "With --record: no MP4");
  cmd.add_option("--stats", o.stats, "Write JSON at exit: fps, sim_rate, frames, steps, the state and a timeline of the "
                                     "scripted events")->type_name("FILE");
  cmd.add_flag("--vsync", o.vsync, "Wait for the display's vertical sync");
  cmd.add_flag("--profile", o.profile, "Finish OpenGL work after each stage so --stats' ms_per_frame is exact (slower)");
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw js::InputError("--script: cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Loads the scene like `simulate` does (built-in jellyfish scene, scene file, --set) and runs the viewer.
int run_view(ViewCommand& v) {
  js::scene::ConfigSources sources{{}, v.scene_path, "jellyfish", false, v.sets};
  if (!v.scene_path.empty()) sources.scene_file = js::config::Config::load(v.scene_path);
  const js::config::Config config =
      js::scene::resolve_config(js::scene::builtin_jellyfish_scene(), sources, "the jellyfish scene");
  const std::string name = v.scene_path.empty() ? "built-in jellyfish" : v.scene_path;
  auto& o = v.options;
  o.scene_name = name;
  o.field = v.field == "speed" ? js::viewer::FieldShown::speed : js::viewer::FieldShown::vorticity;
  o.record_png = !v.no_png;
  o.record_mp4 = !v.no_mp4;
  o.geometry = js::viewer::interactive_geometry(js::geometry::NoiseSettings{});
  if (!v.script_path.empty()) {
    o.script_text = read_text_file(v.script_path);
    o.script_source = v.script_path;
  }
  if (!v.inject.empty()) {
    o.script_text += (o.script_text.empty() ? "" : "\n") + v.inject;
    o.script_source = v.script_path.empty() ? "--inject" : "--script/--inject";
  }
  if (js::scene::is_3d_scene(config)) return js::viewer::run_viewer_3d(js::scene::read_swim3d_settings(config), o);
  return js::viewer::run_viewer(js::scene::read_swim_settings(config), o);
}

/// Options of `jellysim batch`.
struct BatchCommand {
  std::string plan;
  std::string out = "out/batch";
  std::vector<std::string> sets;
  int threads = 0;
  bool quiet = false;
  std::string progress = "bar";  ///< bar: a line per run (stdout); json: JSON lines (stderr); none
};

void add_batch_options(CLI::App& cmd, BatchCommand& b) {
  cmd.add_option("plan", b.plan, "Plan file (TOML): scene, duration, [set], and [product] or [[runs]] (docs/batch.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd.add_option("--out", b.out, "Directory for the runs (runs/NNNN/) and batch.csv; a finished batch's runs in it are "
                                 "kept (resume)")
      ->capture_default_str();
  cmd.add_option("--set", b.sets, "Override a parameter in every run: --set key=value. Repeatable.")
      ->type_name("KEY=VALUE");
  cmd.add_option("--threads", b.threads, "Runs at a time on this machine (default: one per core); under mpirun with "
                                         "more than one rank, one run per worker rank")
      ->check(CLI::Range(1, 64));
  cmd.add_flag("--quiet", b.quiet, "No line per run");
  add_progress_option(cmd, b.progress);
  add_memory_limit_option(cmd);
}

/// How many processes an MPI launcher started alongside this one (its environment; 1 when none).
long mpi_ranks_from_environment() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* n = std::getenv(v)) return std::max(1L, std::strtol(n, nullptr, 10));
  return 1;
}

/// Every command but `batch` (and, with the MPI backend, `optimize`) is one process: N ranks of it
/// would write the same files at once.
void refuse_several_ranks(const std::string& command) {
  const long ranks = mpi_ranks_from_environment();
  if (ranks <= 1) return;
  throw js::InputError("`jellysim " + command + "` was started as " + std::to_string(ranks) +
                       " MPI ranks: only `jellysim batch` and `optimize`'s Pareto sweep spread work over ranks (the others "
                       "would write the same files at once). A frequency sweep on MPI is a batch plan with [product] "
                       "\"jellyfish.frequency\" = [...] (docs/batch.md)");
}

/// The commands with an MPI backend.
bool spreads_over_ranks(const std::string& command) {
#ifdef JELLYSIM_MPI
  return command == "batch" || command == "optimize";
#else
  return command == "batch";
#endif
}

/// `jellysim batch`: over MPI when an MPI launcher started this process, else on threads.
int run_batch(const BatchCommand& b) {
  if (b.out.empty() || b.out.front() == '-')
    throw js::InputError("--out '" + b.out + "': give the batch's directory after --out");
  const std::string mode = progress_mode(b.progress, b.quiet);
  const bool quiet = mode == "none" || b.quiet;
  int code = 0;
#ifdef JELLYSIM_MPI
  if (jellysim::app::launched_by_mpi()) {  // over MPI, --progress json writes the status line only
    code = jellysim::app::run_batch_mpi(b.plan, b.sets, b.out, b.threads, quiet);
    return report_status(mode, code, b.out, "batch: " + b.out + "/batch.csv");
  }
#endif
  js::experiments::Batch batch(js::experiments::read_batch_plan(b.plan), b.sets, b.out);
  code = js::experiments::run_batch_threaded(batch, b.threads, quiet,
                                             mode == "json" ? json_count_progress("batch", "runs")
                                                            : std::function<void(std::size_t, std::size_t)>{});
  return report_status(mode, code, b.out, code == 0 ? "batch: " + b.out + "/batch.csv" : "batch interrupted");
}

/// Options of `jellysim optimize`.
struct OptimizeCommand {
  std::string plan;
  std::string out = "out/optimize";
  bool quiet = false;
  std::string progress = "bar";  ///< bar: a line per evaluation (stdout); json: JSON lines (stderr); none
};

void add_optimize_options(CLI::App& cmd, OptimizeCommand& o) {
  cmd.add_option("plan", o.plan, "Plan file (TOML): scene, cycles, objective, sense, algorithm, evaluations, seed, "
                                 "[set], [variables], [constraints], [target] (docs/control.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd.add_option("--out", o.out, "Directory for evaluations.csv, best.toml, progress.png, summary.json; an earlier "
                                 "run's evaluations.csv there is replayed (resume)")
      ->capture_default_str();
  cmd.add_flag("--quiet", o.quiet, "No line per evaluation");
  add_progress_option(cmd, o.progress);
  add_memory_limit_option(cmd);
}

int run_optimize_command(const OptimizeCommand& o) {
  if (o.out.empty() || o.out.front() == '-') throw js::InputError("--out '" + o.out + "': give a directory after --out");
  const std::string mode = progress_mode(o.progress, o.quiet);
#ifdef JELLYSIM_MPI
  if (jellysim::app::launched_by_mpi()) {  // a Pareto sweep's sub-problems over the ranks
    const int code = jellysim::app::run_optimize_mpi(o.plan, o.out, o.quiet || mode == "none");
    return report_status(mode, code, o.out, code == 0 ? "optimize: " + o.out + "/summary.json" : "optimize stopped");
  }
#endif
  js::experiments::run_optimize(js::experiments::read_optimize_plan(o.plan), o.out, o.quiet || mode == "none", {},
                                mode == "json" ? json_count_progress("optimize", "evaluations")
                                               : js::experiments::EvaluationProgress{});
  if (!o.quiet) std::cout << "optimize: results in " << o.out << "\n";
  return report_status(mode, 0, o.out, "optimize: " + o.out + "/summary.json");
}

/// A command of `jellysim`: its name and help, `define` adds its options to its subcommand and
/// returns what runs it once parsed. A new command is a row of commands().
struct Command {
  std::string name;
  std::string help;
  std::function<std::function<int()>(CLI::App&)> define;
};

/// `run` and `simulate`: a scene (default: their built-in experiment), checkpoints, resume.
std::function<int()> define_scene_command(CLI::App& cmd, const std::string& command, const std::string& scene_help,
                                          const std::string& default_out, const std::string& set_example,
                                          const std::string& checkpoint_more) {
  struct State {
    RunOptions options;
    std::string scene_path;
    CheckpointOptions checkpoints;
    std::optional<double> fps;
    std::optional<int> loop_cycles;  ///< run --loop CYCLES
  };
  auto s = std::make_shared<State>();
  cmd.add_option("scene", s->scene_path, scene_help)->check(CLI::ExistingFile);
  add_run_options(cmd, s->options, default_out, set_example);
  cmd.add_option("--fps", s->fps,
                 "Frames per second, (0, 1000]: frame k at k / N s exactly, e.g. 24 (the scene key output.fps; "
                 "not with output.frame_interval)")
      ->type_name("N")
      ->check(finite_range(0.0, 1000.0, true));
  if (command == "run")
    cmd.add_option("--loop", s->loop_cycles,
                   "A seamless loop of CYCLES whole contraction cycles, [1, 100], from where the stroke is periodic "
                   "(render.loop = true, render.loop_cycles = CYCLES; docs/rendering.md)")
        ->type_name("CYCLES")
        ->check(CLI::Range(1, 100));
  add_checkpoint_options(cmd, s->checkpoints, checkpoint_more);
  cmd.get_option("--fps")->excludes("--resume");
  if (command == "run") cmd.get_option("--loop")->excludes("--resume");
  return [s, command] {
    if (s->fps) s->options.sets.push_back("output.fps=" + js::io::format_double(*s->fps));  // in checkpoints as a --set
    if (s->loop_cycles) {
      s->options.sets.push_back("render.loop=true");
      s->options.sets.push_back("render.loop_cycles=" + std::to_string(*s->loop_cycles));
    }
    if (!s->checkpoints.resume_dir.empty()) return resume_simulation(command, s->checkpoints.resume_dir, s->options);
    if (s->checkpoints.every > 0)
      return run_checkpointed_simulation(command, s->scene_path, s->options, s->checkpoints.every);
    return run_scene(s->scene_path, s->options, checkpointed_experiment(command).name);
  };
}

std::function<int()> define_sweep(CLI::App& cmd) {
  struct State {
    RunOptions options;
    std::string scene_path;
    std::vector<double> frequencies;
  };
  auto s = std::make_shared<State>();
  cmd.add_option("scene", s->scene_path, "Jellyfish scene file (TOML); omitted: the built-in scene")
      ->check(CLI::ExistingFile);
  cmd.add_option("--frequencies", s->frequencies, "Contraction frequencies in Hz (default 0.3 ... 1.3)")->delimiter(',');
  add_run_options(cmd, s->options, "out/sweep", "--set sweep.frequencies=[0.5,0.9] --set tank.viscosity=2e-5");
  return [s] {
    if (!s->frequencies.empty()) {
      std::string list;
      for (double f : s->frequencies) list += (list.empty() ? "" : ", ") + js::io::format_double(f);
      s->options.sets.push_back("sweep.frequencies=[" + list + "]");
    }
    SceneFile scene{{}, s->scene_path};
    if (!s->scene_path.empty()) scene.config = js::config::Config::load(s->scene_path);
    return run_experiment(js::experiments::find_experiment("sweep"), scene, s->options);
  };
}

std::function<int()> define_experiment(CLI::App& cmd) {
  struct State {
    RunOptions options;
    std::string name, scene_path;
    std::vector<std::pair<std::string, std::string>> shorthands;  // the experiments' own options, as given
  };
  auto s = std::make_shared<State>();
  cmd.add_option("name", s->name, "Experiment name")->required();
  cmd.add_option("scene", s->scene_path,
                 "Jellyfish scene file laid over the experiment's scene (experiments that extend the jellyfish scene, "
                 "e.g. convergence)")
      ->check(CLI::ExistingFile);
  add_run_options(cmd, s->options, "", "for swinging-bar: --set bar.point_mass=12 --set time.integrator=rk4");
  add_shorthand_options(cmd, s->shorthands);
  return [s] {
    if (s->options.out.empty()) s->options.out = "out/" + s->name;
    const js::experiments::Experiment& e = js::experiments::find_experiment(s->name);
    s->options.shorthands = js::experiments::shorthands_for(e, s->shorthands);
    SceneFile scene{{}, s->scene_path, "jellyfish"};
    if (!s->scene_path.empty()) {
      if (e.base_path != "scenes/jellyfish.toml")
        throw js::InputError("experiment '" + s->name + "' takes no scene file ('" + s->scene_path +
                             "'): only experiments on the jellyfish scene do");
      scene.config = js::config::Config::load(s->scene_path);
    }
    return run_experiment(e, scene, s->options);
  };
}

std::function<int()> define_scenes(CLI::App& cmd) {
  struct State {
    std::string name;
    bool reference = false;
  };
  auto s = std::make_shared<State>();
  cmd.add_option("name", s->name, "Scene or experiment to print (`run` and `simulate`: their built-in scenes)");
  cmd.add_flag("--reference", s->reference, "Print the scene parameter reference (docs/parameters.md) as Markdown");
  return [s] {
    if (!s->reference) return list_definitions(s->name);
    std::cout << js::scene::parameters_reference();
    return 0;
  };
}

std::function<int()> define_ib2d(CLI::App& cmd) {
  struct State {
    int resolution = 256;
    std::string stem;
  };
  auto s = std::make_shared<State>();
  cmd.add_option("--resolution", s->resolution, "IB2d's N, a multiple of 8 in [16, 4096]: 0.375 N x 1.25 N cells")
      ->capture_default_str()
      ->check(CLI::Range(16, 4096));
  cmd.add_option("--out", s->stem, "Path and stem of the files, e.g. scenes/hoover-miller/jelly256")->required();
  return [s] { return write_hoover_miller_files(s->resolution, s->stem); };
}

/// A command whose options are one struct: `add` adds them, `run` runs the command with them.
template <class Options, class Add, class Run>
std::function<int()> define_with(CLI::App& cmd, Add add, Run run) {
  auto options = std::make_shared<Options>();
  add(cmd, *options);
  return [options, run] { return run(*options); };
}

/// Every command, in the order `jellysim --help` lists them.
std::vector<Command> commands() {
  return {
      {"run",
       "The main job: simulate a scene (default: the built-in jellyfish, thesis Fig. 8.21) and write its outputs; for "
       "a jellyfish: jellyfish.mp4, jellyfish.glb, frames/*.png, meshes, viewer.html, metrics.csv, summary.json",
       [](CLI::App& cmd) {
         return define_scene_command(cmd, "run", "Scene file (TOML); omitted: the built-in default scene", "out",
                                     "--set jellyfish.frequency=0.9 --set render.width=320",
                                     " (jellyfish scenes; kept until the animation is written too: a run stopped "
                                     "while rendering renders again on --resume)");
       }},
      {"simulate",
       "Simulate a 2D jellyfish scene alone (default: thesis Fig. 8.21's scene): metrics.csv, slices.csv, plots, a "
       "picture and VTK fields per frame, summary.json; or a 3D one (tank.geometry = \"3d\", "
       "scenes/jellyfish-3d.toml): metrics.csv, summary.json, the flow per frame",
       [](CLI::App& cmd) {
         return define_scene_command(cmd, "simulate",
                                     "Scene file (TOML, scene = \"jellyfish\"); omitted: the built-in scene",
                                     "out/simulate", "--set jellyfish.frequency=0.9 --set output.vtk=false", "");
       }},
      {"sweep",
       "Distance travelled versus contraction frequency (thesis Figs 8.13/8.14) on every core, on the built-in scene "
       "or a scene file, each frequency at sweep.placements sub-cell positions of the bell (default 1; 8 for the "
       "thesis's chaotic coarse tank): sweep.csv (mean and spread), sweep_runs.csv, sweep.png, trajectories.png, "
       "summary.json",
       define_sweep},
      {"experiment", "Reproduce an experiment; writes summary.json, CSV files and pictures." + experiment_list(),
       define_experiment},
      {"batch",
       "Many jellyfish runs from a plan file (a product or list of --set overrides), each into DIR/runs/NNNN/ as "
       "`simulate` writes it, and one combined DIR/batch.csv; on threads, or over MPI under mpirun; rerun to resume "
       "a killed batch (docs/batch.md)",
       [](CLI::App& cmd) { return define_with<BatchCommand>(cmd, add_batch_options, run_batch); }},
      {"optimize",
       "Search the muscle control with NLopt (BOBYQA, COBYLA, CRS2, ISRES, DIRECT, ...): a plan's design variables "
       "(scene keys with bounds) for an objective (distance_per_cycle, speed, cost_of_transport, efficiency, reach) "
       "under constraints: evaluations.csv, best.toml, progress.png, summary.json; two objectives: pareto.csv, "
       "pareto.png; rerun to resume (docs/control.md)",
       [](CLI::App& cmd) { return define_with<OptimizeCommand>(cmd, add_optimize_options, run_optimize_command); }},
      {"view",
       "Real-time viewer: the 2D slice in its fluid beside the 3D jellyfish; pause, step, live parameters, drag "
       "jellyfish and obstacles, stir the water, record PNG/MP4 (docs/viewer.md). Needs a display (or xvfb-run -a)",
       [](CLI::App& cmd) { return define_with<ViewCommand>(cmd, add_view_options, run_view); }},
      {"scenes", "List built-in scenes and experiments, or print one's definition (every parameter, its default and "
                 "meaning)",
       define_scenes},
      {"ib2d-jellyfish", "Write the Hoover-Miller jellyfish bell (IB2d's convergence example) as IB2d structure files "
                         "STEM.vertex, .spring, .nonInv_beam, .target (docs/ib2d.md)",
       define_ib2d},
  };
}

/// Runs the parsed command; a usage or input error is exit 2, a failed run exit 1.
int run_parsed(const std::vector<std::pair<CLI::App*, std::function<int()>>>& runs) {
  std::string mode, out;  // a command's --progress and --out, for the status line of an error
  try {
    for (const auto& [command, run] : runs) {
      if (!command->parsed()) continue;
      if (const CLI::Option* p = command->get_option_no_throw("--progress"); p != nullptr) mode = p->as<std::string>();
      if (const CLI::Option* d = command->get_option_no_throw("--out"); d != nullptr && d->count() > 0)
        out = d->as<std::string>();
      if (!spreads_over_ranks(command->get_name())) refuse_several_ranks(command->get_name());
      const int code = run();
      // A command that writes no status line of its own (a new one) still ends --progress json with one.
      return report_status(mode, code, out, command->get_name() + (code == 0 ? ": done" : ": exit " + std::to_string(code)));
    }
    return kExitBadInput;  // CLI11 requires one command: not reached
  } catch (const js::InputError& e) {
    std::cerr << "jellysim: error: " << e.what() << "\n";
    return report_status(mode, kExitBadInput, out, e.what());
  } catch (const std::bad_alloc&) {  // before the run's own guard (experiments::run_guarded)
    std::cerr << "jellysim: run failed: " << js::core::out_of_memory_message() << "\n";
    return report_status(mode, kExitFailedRun, out, js::core::out_of_memory_message());
  } catch (const std::exception& e) {
    std::cerr << "jellysim: run failed: " << e.what() << "\n";
    return report_status(mode, kExitFailedRun, out, e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  // A closed standard output (`jellysim ... | head -1`) makes writes to it fail (EPIPE), and the
  // stream stops printing, instead of SIGPIPE killing the process in the middle of its work.
  std::signal(SIGPIPE, SIG_IGN);
  CLI::App app{"jellysim " JELLYSIM_VERSION " - physically simulated jellyfish (and the methods they need)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", JELLYSIM_VERSION);
  std::vector<std::pair<CLI::App*, std::function<int()>>> runs;
  for (const Command& c : commands()) {
    CLI::App* command = app.add_subcommand(c.name, c.help);
    runs.emplace_back(command, c.define(*command));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  return run_parsed(runs);
}
