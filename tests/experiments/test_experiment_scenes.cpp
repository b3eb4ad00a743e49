// The experiments' own fields follow parameter tables: integrator-order's and stages' definitions
// are their tables, the jellyfish studies and the particle scenes follow their rules, and every
// reader rejects a bad value with the field and the allowed range named.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "../scene/scene_test_util.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "jellysim/scene/study_scenes.hpp"

namespace {

using namespace jellysim;
using jellysim::testing::error_of;
using jellysim::testing::read_source_file;
using scene::Parameter;
using scene::ParameterTable;
using scene::Type;

config::Config experiment_config(const std::string& name) {
  return experiments::default_config(experiments::find_experiment(name));
}

/// `name`'s default configuration with `assignment` applied.
config::Config with(const std::string& name, const std::string& assignment) {
  config::Config c = experiment_config(name);
  c.set(assignment);
  return c;
}

/// The message names the field and `allowed`.
void expect_rejected(const std::string& message, const std::string& key, const std::string& allowed) {
  EXPECT_NE(message.find("'" + key + "'"), std::string::npos) << message;
  EXPECT_NE(message.find(allowed), std::string::npos) << message;
}

/// A TOML value just outside each finite bound of a number or integer parameter (integers' ranges
/// are closed; their bounds may be too large for a double to hold the next integer).
std::vector<std::string> values_outside(const Parameter& p) {
  std::vector<std::string> text;
  if (p.type == Type::integer) {
    if (std::isfinite(p.range.min)) text.push_back(std::to_string(std::llround(p.range.min) - 1));
    if (std::isfinite(p.range.max)) text.push_back(std::to_string(std::llround(p.range.max) + 1));
    return text;
  }
  auto step = [](double bound) { return std::max(1e-9, 1e-6 * std::abs(bound)); };
  std::vector<double> outside;
  if (std::isfinite(p.range.min)) outside.push_back(p.range.min_open ? p.range.min : p.range.min - step(p.range.min));
  if (std::isfinite(p.range.max)) outside.push_back(p.range.max_open ? p.range.max : p.range.max + step(p.range.max));
  for (double v : outside) {
    std::ostringstream value;
    value.precision(17);
    value << v;
    if (value.str().find_first_of(".e") == std::string::npos) value << ".0";
    text.push_back(value.str());
  }
  return text;
}

/// Every finite bound of every number and integer rule that `name` sets is enforced; returns how
/// many were checked.
int check_bounds(const ParameterTable& rules, const std::string& name) {
  int checked = 0;
  for (const Parameter& p : rules.parameters()) {
    if ((p.type != Type::number && p.type != Type::integer) || !experiment_config(name).has(p.key)) continue;
    for (const std::string& v : values_outside(p)) {
      const config::Config c = with(name, p.key + "=" + v);
      const scene::Reader r(c, rules);
      const std::string message = error_of([&] { p.type == Type::number ? (void)r.number(p.key) : (void)r.integer(p.key); });
      // Integers' bounds are named as integers ("[0, 4611686018427387904]", not "4.6e+18").
      const std::string allowed = p.type == Type::number ? p.range.describe()
                                                          : "[" + std::to_string(std::llround(p.range.min)) + ", " +
                                                                std::to_string(std::llround(p.range.max)) + "]";
      expect_rejected(message, p.key, allowed);
      ++checked;
    }
  }
  return checked;
}

// `jellysim scenes stages` prints the definition with the whole [render] section folded in, so the
// file's expected text is written next to the test for copying when it is stale.
TEST(ExperimentScenes, StagesDefinitionIsItsTable) {
  const ParameterTable* table = scene::table_for_definition("experiments/stages.toml");
  ASSERT_EQ(table, &scene::stages_scene());
  const std::string expected = table->scene_toml();
  if (read_source_file("experiments/stages.toml") != expected) {
    const std::filesystem::path fresh = std::filesystem::absolute("stages.toml.expected");
    std::ofstream(fresh, std::ios::binary) << expected;
    ADD_FAILURE() << "experiments/stages.toml is stale: cp " << fresh.string() << " experiments/stages.toml";
  }
}

TEST(ExperimentScenes, IntegratorOrderReadsItsTable) {
  const scene::IntegratorOrderScene s = scene::read_integrator_order(experiment_config("integrator-order"));
  EXPECT_EQ(s.stiffness, 50.0);
  EXPECT_EQ(s.refinements, 4);
  const std::vector<std::pair<std::string, int>> steps{{"forward-euler", 4000}, {"predictor-corrector", 4000},
                                                       {"leapfrog", 200},       {"rk2", 200},
                                                       {"rk4", 100},            {"dopri5", 80},
                                                       {"backward-euler", 4000}};
  EXPECT_EQ(s.coarsest_steps, steps);
  expect_rejected(error_of([] { scene::read_integrator_order(with("integrator-order", "study.refinements=13")); }),
                  "study.refinements", "[1, 12]");
  expect_rejected(error_of([] { scene::read_integrator_order(with("integrator-order", "problem.amplitude=-0.1")); }),
                  "problem.amplitude", "[0, inf)");
  expect_rejected(
      error_of([] { scene::read_integrator_order(with("integrator-order", "study.coarsest_steps.rk4=0")); }),
      "study.coarsest_steps.rk4", "[1, 10000000]");
}

TEST(ExperimentScenes, StagesReadsItsTableAndTheRenderSection) {
  const scene::StagesScene s = scene::read_stages_scene(experiment_config("stages"));
  EXPECT_TRUE(s.simulated);
  EXPECT_EQ(s.bell.umbrella_points, 21);
  EXPECT_EQ(s.panel_width, 360);
  EXPECT_TRUE(s.pipeline.obj);
  EXPECT_TRUE(s.pipeline.ply);
  expect_rejected(error_of([] { scene::read_stages_scene(with("stages", "bell.contracted=1.5")); }), "bell.contracted",
                  "[0, 1]");
  expect_rejected(error_of([] { scene::read_stages_scene(with("stages", "output.panel_width=4096")); }),
                  "output.panel_width", "[64, 2048]");
  expect_rejected(error_of([] { scene::read_stages_scene(with("stages", "bell.umbrella_points=20")); }),
                  "bell.umbrella_points", "must be odd");
}

// The jellyfish studies' own fields follow one set of rules; every study's definition does, every
// rule is used by some study, and every bound is enforced.
TEST(ExperimentScenes, JellyfishStudiesFollowTheirRules) {
  const ParameterTable& rules = scene::jellyfish_study_rules();
  std::set<std::string> used;
  int checked = 0;
  for (const char* name : {"structural-instability", "numerical-instability", "frequency-sweep", "sweep", "fluidless",
                           "coupling-stability", "steering", "resonance"}) {
    const config::Config c = experiment_config(name);
    EXPECT_NO_THROW(scene::Reader(c, rules).validate_all()) << name;
    for (const Parameter& p : rules.parameters())
      if (c.has(p.key)) used.insert(p.key);
    checked += check_bounds(rules, name);
  }
  for (const Parameter& p : rules.parameters()) EXPECT_TRUE(used.count(p.key)) << p.key << " is a rule no study uses";
  EXPECT_GT(checked, 15);
}

TEST(ExperimentScenes, JellyfishStudyReadersRejectBadValues) {
  EXPECT_EQ(scene::read_instability_figure(experiment_config("structural-instability")).panels, 6);
  expect_rejected(error_of([] { scene::read_instability_figure(with("structural-instability", "figure.panels=25")); }),
                  "figure.panels", "[1, 24]");
  expect_rejected(
      error_of([] { scene::read_instability_figure(with("numerical-instability", "figure.expected=\"both\"")); }),
      "figure.expected", "structural, numerical");
  expect_rejected(
      error_of([] { scene::read_instability_figure(with("numerical-instability", "output.picture_zoom=-1.0")); }),
      "output.picture_zoom", "[0, 1000]");
  EXPECT_EQ(scene::read_sweep(experiment_config("frequency-sweep")).placements, 8);
  expect_rejected(error_of([] { scene::read_sweep(with("frequency-sweep", "sweep.placements=65")); }), "sweep.placements",
                  "[1, 64]");
  expect_rejected(error_of([] { scene::read_sweep(with("sweep", "sweep.frequencies=[0.5, 6.0]")); }),
                  "sweep.frequencies", "(0, 5]");
  const scene::FluidlessScene f = scene::read_fluidless(experiment_config("fluidless"));
  EXPECT_EQ(f.time.integrator, "dopri5");
  EXPECT_EQ(f.model.pressure_factor, 200.0);
  expect_rejected(error_of([] { scene::read_fluidless(with("fluidless", "fluidless.dt=0.0")); }), "fluidless.dt",
                  "(0, inf)");
  expect_rejected(error_of([] { scene::read_coupling_stability_steps(with("coupling-stability", "study.time_steps=[0.01, -1.0]")); }),
                  "study.time_steps", "(0, inf)");
  EXPECT_EQ(scene::read_steering(experiment_config("steering")).settle_cycles, 4.0);
  expect_rejected(error_of([] { scene::read_steering(with("steering", "steering.settle_cycles=-1.0")); }),
                  "steering.settle_cycles", "[0, inf)");
  expect_rejected(error_of([] { scene::read_steering(with("steering", "steering.target_offset=[-0.3, 0.1]")); }),
                  "steering.target_offset", "x > 0");
}

TEST(ExperimentScenes, ParticleScenesOwnFieldsAreEnforced) {
  int checked = 0;
  for (const char* name : {"swinging-bar", "bar-hits-wall", "bar-hits-particle", "sph-stream", "mosquito-larva",
                           "integrator-cost"})
    checked += check_bounds(scene::particle_scene_rules(), name);
  EXPECT_GT(checked, 100);
  expect_rejected(error_of([] { scene::read_strip_output(with("swinging-bar", "output.strip_frames=65")); }),
                  "output.strip_frames", "[1, 64]");
  expect_rejected(error_of([] { scene::read_wall_gap(with("bar-hits-wall", "wall.gap=0.0")); }), "wall.gap", "(0, inf)");
  expect_rejected(error_of([] { scene::read_strip_output(with("bar-hits-wall", "output.strip_window=0.0")); }),
                  "output.strip_window", "(0, inf)");
  EXPECT_EQ(scene::read_point_particle(experiment_config("bar-hits-particle")).position.x, -0.48);
  expect_rejected(error_of([] { scene::read_point_particle(with("bar-hits-particle", "particle.mass=0.0")); }),
                  "particle.mass", "(0, inf)");
  const auto emitter = [](const config::Config& c) { scene::read_emitter(c, scene::read_box(c)); };
  expect_rejected(error_of([&] { emitter(with("sph-stream", "emitter.interval=0.0")); }), "emitter.interval", "(0, inf)");
  expect_rejected(error_of([&] { emitter(with("sph-stream", "emitter.max_count=100001")); }), "emitter.max_count",
                  "[0, 100000]");
  expect_rejected(error_of([&] { emitter(with("sph-stream", "emitter.offset=[2.0, -0.2]")); }), "emitter.offset",
                  "outside the box");
  const scene::StripOutput strip = scene::read_strip_output(experiment_config("mosquito-larva"));
  EXPECT_EQ(strip.start_s, 2.0);
  EXPECT_EQ(strip.velocity_scale_s, 0.05);
  expect_rejected(error_of([] { scene::read_strip_output(with("mosquito-larva", "output.strip_start=-1.0")); }),
                  "output.strip_start", "[0, inf)");
  expect_rejected(error_of([] { scene::build_larva_scene(with("mosquito-larva", "fluid.gas_constant=-1.0")); }),
                  "fluid.gas_constant", "[0, inf)");
  EXPECT_EQ(scene::read_cost_study(experiment_config("integrator-cost")).gas_constants.size(), 4u);
  expect_rejected(error_of([] { scene::read_cost_study(with("integrator-cost", "study.gas_constants=[0.04, 0.0]")); }),
                  "study.gas_constants", "(0, inf)");
  expect_rejected(error_of([] { scene::read_cost_study(with("integrator-cost", "study.error_controls=[\"none\"]")); }),
                  "study.error_controls", "embedded, step-doubling");
}

}  // namespace

// One place for the Figure 8.1 bar: the bar scenes extend scenes/bar.toml, whose [bar] is
// elastic::BarSpec's defaults (and swinging-bar's extra [bar] fields are BarSpec's too).
TEST(ExperimentScenes, BarScenesExtendOneBarWhoseDefaultsAreBarSpecs) {
  const elastic::BarSpec spec{};
  const config::Config base = config::Config::parse(experiments::definition_text("scenes/bar.toml"), "scenes/bar.toml");
  const elastic::BarSpec read = scene::read_bar(base);
  const config::Config swinging = experiment_config("swinging-bar");
  const scene::Reader r(swinging, scene::particle_scene_rules());
  const std::pair<double, double> read_and_default[] = {
      {read.length, spec.length},         {read.width, spec.width},
      {read.segments, spec.segments},     {read.point_mass, spec.point_mass},
      {read.stiffness, spec.stiffness},   {read.pivot.x, spec.pivot.x},
      {read.pivot.y, spec.pivot.y},       {read.gravity.x, spec.gravity.x},
      {read.gravity.y, spec.gravity.y},   {r.number("bar.angular_stiffness"), spec.angular_stiffness},
      {r.number("bar.angle_deg"), spec.angle_rad}, {r.number("bar.drag"), spec.drag}};
  for (std::size_t k = 0; k < std::size(read_and_default); ++k)
    EXPECT_EQ(read_and_default[k].first, read_and_default[k].second) << "field " << k;
  for (const char* name : {"swinging-bar", "bar-hits-wall", "bar-hits-particle", "sph-stream"}) {
    EXPECT_EQ(experiments::find_experiment(name).base_path, "scenes/bar.toml") << name;
    const std::string own(experiments::definition_text(experiments::find_experiment(name).definition_path));
    for (const char* field : {"length", "width", "segments", "point_mass", "stiffness", "pivot", "gravity"})
      EXPECT_FALSE(config::Config::parse(own, name).has(std::string("bar.") + field)) << name << " repeats bar." << field;
  }
}
