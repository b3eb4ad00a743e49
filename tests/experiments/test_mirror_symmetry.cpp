// Keeping the mirror symmetry of a mirror-symmetric scene (tank.symmetry, fluid/flow_mirror.hpp):
// which scenes qualify, and which live edits end it. That it changes nothing but the round-off
// asymmetry, and the ten-cycle swim it gives, are tested in test_swim.cpp.
#include <gtest/gtest.h>

#include <string>

#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/core/errors.hpp"
#include "jellyfish_test_util.hpp"

namespace jellysim::experiments {
namespace {

jellyfish::SwimSettings scene(const std::string& overlay) { return read_swim_settings(testing::scene_with(overlay)); }

bool kept(const std::string& overlay, std::string* note = nullptr) {
  const jellyfish::SwimSimulation sim(scene(overlay));
  if (note) *note = sim.mirror_symmetry_note();
  return sim.mirror_symmetric();
}

const char* kTwoAlike = R"(
[jellyfish]
position = [0.34, 0.3]
[[objects]]
type = "jellyfish"
position = [0.46, 0.3]
)";

TEST(MirrorSymmetry, KeptForScenesThatAreTheirOwnMirrorImage) {
  EXPECT_TRUE(kept(""));         // the default: one centred bell, free-slip walls
  EXPECT_TRUE(kept(kTwoAlike));  // two alike, placed as mirror images
  EXPECT_TRUE(kept(R"(
[[objects]]
type = "box"
centre = [0.4, 0.6]
size = [0.06, 0.02]
)"));  // a fixed box on the axis ahead of the bell
  EXPECT_TRUE(kept(R"(
[[objects]]
type = "circle"
centre = [0.4, 0.6]
radius = 0.03
)"));  // a circle (29 markers by spacing, rounded up to an even 30)
  EXPECT_TRUE(kept(R"(
tank.current = [0.0, 0.02]
tank.boundaries = ["free-slip", "free-slip", "inflow", "outflow"]
tank.inflow_velocity = [0.0, 0.02]
)"));  // a current along the axis
  EXPECT_FALSE(kept("tank.symmetry = \"none\""));
}

TEST(MirrorSymmetry, AutoSaysWhyAnAsymmetricSceneIsNotKeptSymmetric) {
  std::string note;
  EXPECT_FALSE(kept("[jellyfish]\nposition = [0.41, 0.3]\n", &note));
  EXPECT_NE(note.find("not mirror images"), std::string::npos) << note;
  EXPECT_FALSE(kept("[jellyfish]\ntilt_deg = 10.0\n", &note));
  EXPECT_FALSE(kept(std::string(kTwoAlike) + "phase = 0.5\n", &note));
  EXPECT_NE(note.find("jellyfish 1 and its mirror image, jellyfish 2, contract differently"), std::string::npos) << note;
  EXPECT_FALSE(kept("[jellyfish]\nsteering = true\n", &note));
  EXPECT_NE(note.find("jellyfish 1 steers"), std::string::npos) << note;
  EXPECT_FALSE(kept("tank.current = [0.01, 0.0]\ntank.boundaries = [\"periodic\", \"periodic\", \"free-slip\", \"free-slip\"]\n", &note));
  EXPECT_NE(note.find("sideways"), std::string::npos) << note;
  EXPECT_FALSE(kept("tank.boundaries = [\"no-slip\", \"free-slip\", \"free-slip\", \"free-slip\"]\n", &note));
  EXPECT_NE(note.find("west and east"), std::string::npos) << note;
}

TEST(MirrorSymmetry, InsistingOnItRejectsAnAsymmetricScene) {
  try {
    scene("tank.symmetry = \"mirror\"\n[jellyfish]\ntilt_deg = 10.0\n");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("field 'tank.symmetry'"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(kept("tank.symmetry = \"mirror\""));
  EXPECT_THROW(scene("tank.symmetry = \"half\""), InputError);
}

TEST(MirrorSymmetry, LiveEditsThatBreakItEndIt) {
  {
    jellyfish::SwimSimulation sim(scene(""));
    EXPECT_TRUE(sim.solving_half_tank());
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(sim.step().failure.empty());
    sim.set_frequency(0, 0.9);  // one centred bell stays its own mirror image
    sim.set_gamma(0, 0.6);
    sim.move_jellyfish(0, {0.0, 0.01});
    EXPECT_TRUE(sim.mirror_symmetric());
    EXPECT_TRUE(sim.solving_half_tank());
    const fluid::FlowState before = sim.flow();  // unfolded from the half tank
    const double t = sim.time_s();
    const long steps = sim.steps();
    sim.stir({0.3, 0.5}, {0.01, 0.0}, 0.02);
    EXPECT_FALSE(sim.mirror_symmetric());
    EXPECT_NE(sim.mirror_symmetry_note().find("stirred"), std::string::npos) << sim.mirror_symmetry_note();
    // The run goes on in the whole tank from the unfolded flow, on the same clock.
    EXPECT_FALSE(sim.solving_half_tank());
    EXPECT_EQ(sim.flow().grid.nx, before.grid.nx);
    EXPECT_EQ(sim.time_s(), t);
    EXPECT_EQ(sim.steps(), steps);
    EXPECT_EQ(sim.flow().velocity.v(45, 20), before.velocity.v(45, 20));  // far from the stirring
    EXPECT_EQ(sim.flow().velocity.v(14, 20), before.velocity.v(14, 20));
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(sim.step().failure.empty());
    EXPECT_EQ(sim.steps(), steps + 5);
  }
  {
    jellyfish::SwimSimulation sim(scene(kTwoAlike));
    sim.set_frequency(1, 0.9);  // one of a mirror pair
    EXPECT_FALSE(sim.mirror_symmetric());
    EXPECT_NE(sim.mirror_symmetry_note().find("jellyfish 2"), std::string::npos) << sim.mirror_symmetry_note();
  }
  {
    jellyfish::SwimSimulation sim(scene(""));
    sim.move_jellyfish(0, {0.01, 0.0});
    EXPECT_FALSE(sim.mirror_symmetric());
  }
}

}  // namespace
}  // namespace jellysim::experiments
