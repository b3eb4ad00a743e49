#include "jellysim/experiments/experiment.hpp"

#include "jellysim/core/interrupt.hpp"
#include "jellysim/core/memory.hpp"

#include "jellysim/experiments/embedded_data.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellysim/scene/study_scenes.hpp"

#include <algorithm>
#include <stdexcept>

namespace jellysim::experiments {

// Defined in one source file per experiment.
Experiment swinging_bar_experiment();
Experiment integrator_order_experiment();
Experiment driven_cavity_experiment();
Experiment taylor_green_experiment();
Experiment solver_cost_experiment();
Experiment jellyfish_experiment();
Experiment animation_experiment();
Experiment oval_membrane_experiment();
Experiment kinematics_experiment();
Experiment morphology_experiment();
Experiment structural_instability_experiment();
Experiment numerical_instability_experiment();
Experiment frequency_sweep_experiment();
Experiment sweep_experiment();
Experiment fluidless_experiment();
Experiment coupling_stability_experiment();
Experiment bar_hits_wall_experiment();
Experiment bar_hits_particle_experiment();
Experiment sph_stream_experiment();
Experiment mosquito_larva_experiment();
Experiment integrator_cost_experiment();
Experiment stages_experiment();
Experiment steering_experiment();
Experiment obstacle_flow_experiment();
Experiment hoover_miller_experiment();
Experiment axisymmetric_vs_planar_experiment();
Experiment convergence_experiment();
Experiment resonance_experiment();
Experiment three_d_vs_axisymmetric_experiment();

const std::vector<Experiment>& all_experiments() {
  static const std::vector<Experiment> list = {swinging_bar_experiment(), integrator_order_experiment(),
                                               driven_cavity_experiment(), taylor_green_experiment(),
                                               solver_cost_experiment(), jellyfish_experiment(), animation_experiment(), oval_membrane_experiment(), kinematics_experiment(),
                                               morphology_experiment(), structural_instability_experiment(),
                                               numerical_instability_experiment(), frequency_sweep_experiment(), sweep_experiment(),
                                               fluidless_experiment(), coupling_stability_experiment(), bar_hits_wall_experiment(),
                                               bar_hits_particle_experiment(), sph_stream_experiment(),
                                               mosquito_larva_experiment(), integrator_cost_experiment(), stages_experiment(),
                                               steering_experiment(), obstacle_flow_experiment(),
                                               hoover_miller_experiment(), axisymmetric_vs_planar_experiment(),
                                               convergence_experiment(), resonance_experiment(),
                                               three_d_vs_axisymmetric_experiment()};
  return list;
}

const Experiment& find_experiment(const std::string& name) {
  std::string names;
  for (const Experiment& e : all_experiments()) {
    if (e.name == name) return e;
    names += (names.empty() ? "" : ", ") + e.name;
  }
  throw InputError("unknown experiment '" + name + "' (known: " + names + ")");
}

const std::vector<ShorthandOption>& shorthand_options() {
  static const std::vector<ShorthandOption> options = {
      {"solver", "solver", "Fluid solver: eulerian or semi-lagrangian (driven-cavity)"},
      {"re", "re", "Reynolds number (driven-cavity)"},
      {"grid", "grid", "Cells per side (driven-cavity)"},
      {"grids", "grids", "Grids of a convergence study, coarsest first: NXxNY,... (convergence)", "LIST", true},
      {"cycles", "cycles", "Contraction cycles per run (convergence, hoover-miller, axisymmetric-vs-planar)", "N"},
      {"steady-tolerance", "cavity.steady_tolerance",
       "Stop when max|du/dt| L/U^2 falls below this (driven-cavity: cavity.steady_tolerance)"},
      {"threads", "run.threads", "Threads for the SPH experiments (run.threads; default: one per core)", "", false, 1,
       64},
  };
  return options;
}

namespace {

/// A command-line value as a TOML basic string (quotes and backslashes escaped).
std::string toml_string(const std::string& text) {
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

const ShorthandOption& shorthand_option(const std::string& name) {
  for (const ShorthandOption& o : shorthand_options())
    if (o.name == name) return o;
  throw std::logic_error("no shorthand option --" + name);
}

}  // namespace

std::vector<scene::Shorthand> shorthands_for(const Experiment& e,
                                             const std::vector<std::pair<std::string, std::string>>& given) {
  std::vector<scene::Shorthand> sets;
  for (const auto& [name, value] : given) {
    const ShorthandOption& o = shorthand_option(name);
    if (std::find(e.shorthands.begin(), e.shorthands.end(), name) == e.shorthands.end())
      throw InputError("--" + name + ": experiment '" + e.name + "' has no " + o.key);
    sets.push_back({name, o.key, o.quoted ? toml_string(value) : value});
  }
  return sets;
}

std::string_view embedded_text(std::string_view path) {
  for (const io::EmbeddedFile& f : io::embedded_files()) {
    if (f.path == path) return f.content;
  }
  throw std::logic_error("embedded file missing from the build: " + std::string(path));
}

std::string definition_text(std::string_view path) {
  // Definitions that are parameter tables (scenes/jellyfish.toml and others are generated from them).
  if (const scene::ParameterTable* table = scene::table_for_definition(path)) return table->scene_toml();
  return std::string(embedded_text(path));
}

config::Config default_config(const Experiment& experiment) {
  auto parse = [](const std::string& path) { return config::Config::parse(definition_text(path), "built-in " + path); };
  config::Config own = parse(experiment.definition_path);
  if (experiment.base_path.empty() && !experiment.renders) return own;
  config::Config base = experiment.base_path.empty() ? scene::render_parameters().defaults() : parse(experiment.base_path);
  if (!experiment.base_overlay_path.empty()) base.merge(parse(experiment.base_overlay_path));
  if (experiment.renders && !experiment.base_path.empty()) base.extend(scene::render_parameters().defaults());
  base.extend(own);
  return base;
}

void write_timings(const io::OutputDir& out, const nlohmann::ordered_json& timings) {
  nlohmann::ordered_json t;
  t["units"] = {{"time", "s"}};
  for (const auto& [key, value] : timings.items()) t[key] = value;
  out.write_json("timings.json", t);
}

namespace {

/// summary.json of a run that threw `failure` (no key figures); false when it cannot be written
/// either (the disk that failed the run), so that the run's own error is the one reported.
bool write_failure_summary(const Experiment& e, const Context& ctx, const io::OutputDir& out,
                           const std::string& failure) {
  const std::string command = e.name == "jellyfish" ? "simulate" : e.name == "animation" ? "run" : "experiment " + e.name;
  try {
    write_summary(out, command, ctx.config, nlohmann::ordered_json::object(), failure);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

Outcome run_guarded(const Experiment& e, const Context& ctx, const std::function<Outcome(const io::OutputDir&)>& run,
                    const io::OutputDir& out) {
  try {
    return run(out);
  } catch (const std::bad_alloc&) {
    const std::string failure = core::out_of_memory_message();
    write_failure_summary(e, ctx, out, failure);
    return {failure};
  } catch (const RunError& error) {  // e.g. an output that could not be drawn or written
    if (!write_failure_summary(e, ctx, out, error.what())) throw;
    return {error.what()};
  }
}

void write_summary(const io::OutputDir& out, const std::string& command, const config::Config& config,
                   const nlohmann::ordered_json& figures, const std::string& failure) {
  nlohmann::ordered_json summary;
  summary["jellysim_version"] = JELLYSIM_VERSION;
  summary["command"] = command;
  // A stop request (SIGINT/SIGTERM) ends a run early through its failure path: "interrupted".
  summary["status"] = failure.empty() ? "ok" : core::interrupt_signal() != 0 ? "interrupted" : "failed";
  if (!failure.empty()) summary["failure"] = failure;
  for (const auto& [key, value] : figures.items()) summary[key] = value;
  summary["config"] = config.to_json();
  out.write_json("summary.json", summary);
}

}  // namespace jellysim::experiments
