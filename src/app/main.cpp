// The jellysim command line: thin layer over the library (see docs/cli.md).
// Exit codes: 0 success, 1 failed run, 2 bad usage or input.
#include "experiments/experiment.hpp"
#include "io/embedded_data.hpp"
#include "io/errors.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
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
  /// Shorthands for top-level keys some experiments have (e.g. driven-cavity): --solver, --re, --grid.
  std::vector<std::pair<std::string, std::string>> shorthands;
};

void add_run_options(CLI::App& cmd, RunOptions& o, const std::string& default_out) {
  o.out = default_out;
  cmd.add_option("--out", o.out, "Directory for the results (created if missing)")->capture_default_str();
  cmd.add_option("--set", o.sets,
                 "Override a parameter: --set key=value (dotted keys, e.g. --set bar.point_mass=12 "
                 "--set time.integrator=rk4). Repeatable. `jellysim scenes NAME` lists every key.")
      ->type_name("KEY=VALUE");
  cmd.add_option("--duration", o.duration, "Simulated seconds (same as --set duration=S)")->type_name("S");
  cmd.add_flag("--quiet", o.quiet, "No progress display");
}

/// Terminal progress: simulated time, steps and ETA, redrawn at most five times a second.
js::sim::ProgressCallback make_progress(bool enabled) {
  if (!enabled || !::isatty(STDOUT_FILENO)) return {};
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

/// Resolves the configuration (defaults, scene file, --set, --duration), validates it, and only
/// then creates the output directory and runs.
int run_experiment(const js::experiments::Experiment& e, const std::optional<js::io::Config>& scene_file,
                   const RunOptions& o) {
  js::experiments::Context ctx{js::experiments::default_config(e), make_progress(!o.quiet)};
  if (scene_file) ctx.config.merge(*scene_file);
  for (const std::string& s : o.sets) ctx.config.set(s);
  if (o.duration) {
    if (!ctx.config.has("duration")) throw js::InputError("--duration: experiment '" + e.name + "' has no duration");
    ctx.config.set("duration=" + js::io::format_double(*o.duration));
  }
  for (const auto& [key, value] : o.shorthands) {
    if (!ctx.config.has(key)) throw js::InputError("--" + key + ": experiment '" + e.name + "' has no " + key);
    ctx.config.set(key + "=" + value);
  }
  auto run = e.prepare(ctx);
  const js::io::OutputDir out(o.out);
  const js::experiments::Outcome outcome = run(out);
  if (!outcome.failure.empty()) {
    std::cerr << "jellysim: run failed: " << outcome.failure << "\n  (results so far are in " << out.path().string()
              << ")\n";
    return kExitFailedRun;
  }
  if (!o.quiet) std::cout << e.name << ": results in " << out.path().string() << "\n";
  return 0;
}

int run_scene(const std::string& scene_path, const RunOptions& o, const std::string& default_scene) {
  std::optional<js::io::Config> scene;
  std::string name = default_scene;
  if (!scene_path.empty()) {
    scene = js::io::Config::load(scene_path);
    if (!scene->has("scene")) throw js::InputError(scene_path + ": missing field 'scene' (e.g. scene = \"swinging-bar\")");
    name = scene->string("scene");
    // `run` on a jellyfish scene renders it too: the animation job extends the jellyfish scene.
    if (default_scene == "animation" && name == "jellyfish") name = "animation";
  }
  return run_experiment(js::experiments::find_experiment(name), scene, o);
}

int list_definitions(const std::string& name) {
  if (name.empty()) {
    for (const auto& e : js::experiments::all_experiments()) {
      std::cout << e.name << "\t" << e.description << "\t(" << e.definition_path << ")\n";
    }
    return 0;
  }
  std::cout << js::experiments::embedded_text(js::experiments::find_experiment(name).definition_path);
  return 0;
}

std::string experiment_list() {
  std::string text;
  for (const auto& e : js::experiments::all_experiments()) text += "\n  " + e.name + ": " + e.description;
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"jellysim " JELLYSIM_VERSION " - physically simulated jellyfish (and the methods they need)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", JELLYSIM_VERSION);

  RunOptions run_opts;
  std::string scene_path;
  auto* run = app.add_subcommand("run", "The main job: simulate a scene (default: the built-in jellyfish, thesis Fig. 8.21) and write its "
      "outputs; for a jellyfish: jellyfish.mp4, jellyfish.glb, frames/*.png, meshes, viewer.html, metrics.csv, summary.json");
  run->add_option("scene", scene_path, "Scene file (TOML); omitted: the built-in default scene")->check(CLI::ExistingFile);
  add_run_options(*run, run_opts, "out");

  RunOptions sim_opts;
  std::string sim_scene_path;
  auto* simulate = app.add_subcommand(
      "simulate", "Simulate a 2D jellyfish scene alone (default: thesis Fig. 8.21's scene): metrics.csv, "
                  "slices.csv, plots, a picture and VTK fields per frame, summary.json");
  simulate->add_option("scene", sim_scene_path, "Scene file (TOML, scene = \"jellyfish\"); omitted: the built-in scene")
      ->check(CLI::ExistingFile);
  add_run_options(*simulate, sim_opts, "out/simulate");

  RunOptions sweep_opts;
  std::string sweep_scene_path;
  std::vector<double> sweep_frequencies;
  auto* sweep = app.add_subcommand(
      "sweep", "Distance travelled versus contraction frequency (thesis Figs 8.13/8.14), one simulation per "
               "frequency on every core: sweep.csv, sweep.png, trajectories.png, summary.json");
  sweep->add_option("scene", sweep_scene_path, "Jellyfish scene file (TOML); omitted: the built-in scene")
      ->check(CLI::ExistingFile);
  sweep->add_option("--frequencies", sweep_frequencies, "Contraction frequencies in Hz (default 0.3 ... 1.3)")
      ->delimiter(',');
  add_run_options(*sweep, sweep_opts, "out/sweep");

  RunOptions exp_opts;
  std::string exp_name;
  auto* exp = app.add_subcommand("experiment", "Reproduce an experiment; writes summary.json, CSV files and pictures." +
                                                   experiment_list());
  exp->add_option("name", exp_name, "Experiment name")->required();
  add_run_options(*exp, exp_opts, "");
  std::string solver, re, grid;
  exp->add_option("--solver", solver, "Fluid solver: eulerian or semi-lagrangian (driven-cavity)");
  exp->add_option("--re", re, "Reynolds number (driven-cavity)");
  exp->add_option("--grid", grid, "Cells per side (driven-cavity)");

  std::string show_name;
  auto* scenes = app.add_subcommand("scenes", "List built-in scenes and experiments, or print one's definition "
                                              "(every parameter, its default and meaning)");
  scenes->add_option("name", show_name, "Scene or experiment to print");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  try {
    if (run->parsed()) return run_scene(scene_path, run_opts, "animation");
    if (simulate->parsed()) return run_scene(sim_scene_path, sim_opts, "jellyfish");
    if (sweep->parsed()) {
      if (!sweep_frequencies.empty()) {
        std::string list;
        for (double f : sweep_frequencies) list += (list.empty() ? "" : ", ") + js::io::format_double(f);
        sweep_opts.sets.push_back("sweep.frequencies=[" + list + "]");
      }
      std::optional<js::io::Config> scene;
      if (!sweep_scene_path.empty()) scene = js::io::Config::load(sweep_scene_path);
      return run_experiment(js::experiments::find_experiment("frequency-sweep"), scene, sweep_opts);
    }
    if (exp->parsed()) {
      if (exp_opts.out.empty()) exp_opts.out = "out/" + exp_name;
      for (auto [key, value] : {std::pair{"solver", solver}, {"re", re}, {"grid", grid}}) {
        if (!value.empty()) exp_opts.shorthands.emplace_back(key, value);
      }
      return run_experiment(js::experiments::find_experiment(exp_name), std::nullopt, exp_opts);
    }
    return list_definitions(show_name);
  } catch (const js::InputError& e) {
    std::cerr << "jellysim: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "jellysim: run failed: " << e.what() << "\n";
    return kExitFailedRun;
  }
}
