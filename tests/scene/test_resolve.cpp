// scene::resolve_config, the one resolution of a configuration (issue 36): the order of its
// sources, its rules and their messages, and the built-in jellyfish scene it starts from.
#include <gtest/gtest.h>

#include <algorithm>

#include "scene_test_util.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/resolve.hpp"

namespace {

using namespace jellysim;
using jellysim::testing::error_of;

config::Config resolve(const scene::ConfigSources& sources) {
  return scene::resolve_config(scene::builtin_jellyfish_scene(), sources, "the jellyfish scene");
}

TEST(Resolve, TheBuiltInSceneIsTheSimulateExperimentsDefaults) {
  EXPECT_EQ(scene::builtin_jellyfish_scene().to_json(),
            experiments::default_config(experiments::find_experiment("jellyfish")).to_json());
  EXPECT_EQ(scene::builtin_jellyfish_scene().to_json(), scene::jellyfish_scene().defaults().to_json());
}

TEST(Resolve, SceneFileThenSetsThenDurationThenShorthands) {
  scene::ConfigSources s{config::Config::parse("[jellyfish]\nfrequency = 0.6\n", "a.toml"), "a.toml", "jellyfish"};
  s.sets = {"jellyfish.frequency=0.7", "tank.viscosity=2e-5"};
  s.duration = 0.25;
  s.shorthands = {{"cycles", "tank.viscosity", "3e-5"}};
  const config::Config c = resolve(s);
  EXPECT_DOUBLE_EQ(c.number("jellyfish.frequency"), 0.7);
  EXPECT_DOUBLE_EQ(c.number("duration"), 0.25);
  EXPECT_DOUBLE_EQ(c.number("tank.viscosity"), 3e-5);
}

TEST(Resolve, RulesAndTheirMessages) {
  scene::ConfigSources set_scene{};
  set_scene.sets = {"scene=\"driven-cavity\""};
  EXPECT_EQ(error_of([&] { resolve(set_scene); }),
            "--set scene: the scene kind cannot be changed by --set; give a scene file instead");
  scene::ConfigSources twice{};
  twice.sets = {"duration=1"};
  twice.duration = 2.0;
  EXPECT_NE(error_of([&] { resolve(twice); }).find("give it once"), std::string::npos);
  const config::Config bar = config::Config::parse("scene = \"swinging-bar\"\n", "bar.toml");
  EXPECT_EQ(error_of([&] { resolve({bar, "bar.toml", "jellyfish"}); }),
            "bar.toml: expected a jellyfish scene (scene = \"jellyfish\"), not 'swinging-bar'");
  const config::Config kindless = config::Config::parse("duration = 1.0\n", "plain.toml");
  EXPECT_DOUBLE_EQ(resolve({kindless, "plain.toml", "jellyfish"}).number("duration"), 1.0);
  EXPECT_EQ(error_of([&] { resolve({kindless, "plain.toml", "jellyfish", true}); }),
            "plain.toml: missing field 'scene' (scene = \"jellyfish\")");
  scene::ConfigSources shorthand{};
  shorthand.shorthands = {{"re", "re", "100"}};
  EXPECT_EQ(error_of([&] { resolve(shorthand); }), "--re: the jellyfish scene has no re");
  const config::Config durationless = config::Config::parse("x = 1\n", "built-in");
  scene::ConfigSources duration{};
  duration.duration = 1.0;
  EXPECT_EQ(error_of([&] { scene::resolve_config(durationless, duration, "experiment 'x'"); }),
            "--duration: experiment 'x' has no duration");
}

}  // namespace

namespace {

// Issue 36: the shorthand options of `jellysim experiment` (--re, --threads, ...) are declared by
// the experiments that take them: exactly those whose configuration has the option's key.
TEST(Resolve, EachExperimentDeclaresTheShorthandOptionsItsConfigurationHas) {
  for (const experiments::Experiment& e : experiments::all_experiments()) {
    const config::Config defaults = experiments::default_config(e);
    for (const experiments::ShorthandOption& o : experiments::shorthand_options()) {
      const bool declared = std::find(e.shorthands.begin(), e.shorthands.end(), o.name) != e.shorthands.end();
      EXPECT_EQ(declared, defaults.has(o.key)) << e.name << " --" << o.name;
    }
  }
  const experiments::Experiment& bar = experiments::find_experiment("swinging-bar");
  EXPECT_EQ(error_of([&] { experiments::shorthands_for(bar, {{"re", "100"}}); }),
            "--re: experiment 'swinging-bar' has no re");
  const auto grids = experiments::shorthands_for(experiments::find_experiment("convergence"), {{"grids", "24x32"}});
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0].key + "=" + grids[0].value, "grids=\"24x32\"");
}

}  // namespace
