// The scene layer's rules over the experiments' definitions: the built-in jellyfish scene is the
// `jellyfish` experiment's defaults, each experiment declares exactly the shorthand options its
// configuration has, and the bar and particle experiments follow one set of rules. They read the
// experiments registry, so they live with the experiments' tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "../scene/scene_test_util.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "jellysim/scene/resolve.hpp"

namespace {

using namespace jellysim;
using jellysim::testing::error_of;
using scene::Parameter;
using scene::ParameterTable;

TEST(Resolve, TheBuiltInSceneIsTheSimulateExperimentsDefaults) {
  EXPECT_EQ(scene::builtin_jellyfish_scene().to_json(),
            experiments::default_config(experiments::find_experiment("jellyfish")).to_json());
  EXPECT_EQ(scene::builtin_jellyfish_scene().to_json(), scene::jellyfish_scene().defaults().to_json());
}

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

// The elastic-bar and particle-fluid scenes share one set of rules; every field each of them
// defines follows it, every rule is used by some scene, and a bound is the same in all of them.
TEST(SceneParameters, ParticleScenesFollowOneSetOfRules) {
  const ParameterTable& rules = scene::particle_scene_rules();
  std::set<std::string> used;
  for (const char* name : {"swinging-bar", "bar-hits-wall", "bar-hits-particle", "sph-stream", "mosquito-larva",
                           "integrator-cost"}) {
    const config::Config c = experiments::default_config(experiments::find_experiment(name));
    EXPECT_NO_THROW(scene::Reader(c, rules).validate_all()) << name;
    for (const Parameter& p : rules.parameters())
      if (c.has(p.key)) used.insert(p.key);
    if (c.has("bar.segments")) {
      config::Config bad = c;
      bad.set("bar.segments=10001");
      const std::string message = error_of([&] { scene::read_bar(bad); });
      EXPECT_NE(message.find("'bar.segments' = 10001 is out of range [1, 10000]"), std::string::npos) << name << ": " << message;
    }
  }
  for (const Parameter& p : rules.parameters()) EXPECT_TRUE(used.count(p.key)) << p.key << " is a rule no scene uses";
}

}  // namespace
