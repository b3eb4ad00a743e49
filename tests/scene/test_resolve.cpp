// scene::resolve_config, the one resolution of a configuration (issue 36): the order of its
// sources, its rules and their messages (the built-in scene and the experiments' shorthand options:
// tests/experiments/test_scene_experiments.cpp).
#include <gtest/gtest.h>

#include "scene_test_util.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/resolve.hpp"

namespace {

using namespace jellysim;
using jellysim::testing::error_of;

config::Config resolve(const scene::ConfigSources& sources) {
  return scene::resolve_config(scene::builtin_jellyfish_scene(), sources, "the jellyfish scene");
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
