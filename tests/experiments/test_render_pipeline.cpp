// The whole animation-output pipeline on the stages experiment's [render] settings: settings read from
// the configuration with bad values naming their field, and every promised file written. Skipped (with
// the reason) where no EGL device exists.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <utility>
#include <string>
#include <vector>

#include "../render/render_test_util.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/render/video.hpp"
#include "jellysim/scene/render_settings.hpp"

namespace jellysim::render {
namespace {

namespace fs = std::filesystem;
using testing::scratch;

config::Config stages_config() { return experiments::default_config(experiments::find_experiment("stages")); }

/// The stages experiment's [render] settings at a small size and level of detail.
PipelineSettings small_settings(int width_px, int height_px) {
  PipelineSettings s = scene::read_render_settings(stages_config());
  s.width_px = width_px;
  s.height_px = height_px;
  s.geometry.latitude_samples = 21;
  s.geometry.disc_points = 24;
  return s;
}

TEST(Pipeline, SettingsComeFromTheConfigAndBadValuesNameTheField) {
  const PipelineSettings s = scene::read_render_settings(stages_config());
  EXPECT_EQ(s.width_px, 640);
  EXPECT_EQ(s.geometry.latitude_samples, 65);
  EXPECT_DOUBLE_EQ(s.geometry.noise.structural_weight, 0.01875);
  for (const char* bad : {"render.width=3", "render.latitude_samples=64", "render.noise.max_contraction=1.5",
                          "render.noise.unstructured_weight=-1", "render.interpolant=bezier"}) {
    config::Config c = stages_config();
    c.set(bad);
    const std::string field = std::string(bad).substr(0, std::string(bad).find('='));
    try {
      scene::read_render_settings(c);
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

TEST(Pipeline, LookControlsAreReadWithTheirRulesAndDefaultsKeepTheFormerLook) {
  const PipelineSettings d = scene::read_render_settings(stages_config());
  const RenderStyle former;  // the hard-wired look before issue 39
  EXPECT_EQ(d.style.umbrella, former.umbrella);  // with umbrella_opacity 0.35
  EXPECT_EQ(d.style.tentacles, former.tentacles);
  EXPECT_EQ(d.style.rim_colour, former.rim_colour);
  EXPECT_EQ(d.style.lights[0].colour, former.lights[0].colour);
  EXPECT_EQ(d.style.background, Background::water);
  EXPECT_EQ(d.style.transmission, 1.0);
  EXPECT_FALSE(d.exr);
  EXPECT_EQ(d.snow_density, 1.0);
  config::Config c = stages_config();
  for (const char* set : {"render.bell_color=[0.9, 0.5, 0.2]", "render.key_light_direction=[0, 2, 0]",
                          "render.key_light_color=[2, 2, 3]", "render.background=\"transparent\"",
                          "render.transmission=0.4", "render.attenuation_distance=0.002", "render.exr=true",
                          "render.snow_density=0.5", "render.camera_distance_m=0.3"})
    c.set(set);
  const PipelineSettings s = scene::read_render_settings(c);
  EXPECT_EQ(s.style.umbrella, (std::array<double, 4>{0.9, 0.5, 0.2, 0.35}));
  EXPECT_EQ(s.style.lights[0].direction.y, 2.0);  // normalised by the shader
  EXPECT_EQ(s.style.lights[0].colour, (std::array<double, 3>{2.0, 2.0, 3.0}));
  EXPECT_EQ(s.style.background, Background::transparent);
  EXPECT_EQ(s.style.transmission, 0.4);
  EXPECT_EQ(s.style.attenuation_distance_m, 0.002);
  EXPECT_TRUE(s.exr);
  EXPECT_EQ(s.snow_density, 0.5);
  EXPECT_EQ(s.camera_distance_m, 0.3);
  // Bad values: an InputError naming the field and what is allowed.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"render.bell_color=[1.5, 0, 0]", "[0, 1]"},           {"render.tentacle_color=[1, 1]", "3 entries"},
      {"render.key_light_direction=[0, 0, 0]", "zero"},     {"render.key_light_color=[101, 0, 0]", "[0, 100]"},
      {"render.background=\"black\"", "transparent"},       {"render.transmission=1.2", "[0, 1]"},
      {"render.attenuation_distance=0", "(0, inf)"},        {"render.snow_density=-0.1", "[0, 1]"},
      {"render.camera_distance_m=0", "(0, inf)"}};
  for (const auto& [set, allowed] : bad) {
    config::Config b = stages_config();
    b.set(set);
    const std::string field = set.substr(0, set.find('='));
    try {
      scene::read_render_settings(b);
      ADD_FAILURE() << set << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(allowed), std::string::npos) << e.what();
    }
  }
}

TEST(Pipeline, TransparentFramesAreRgbaAndExrFramesHoldThePasses) {
  REQUIRE_OFFSCREEN_GL();
  PipelineSettings s = small_settings(64, 48);
  s.video = s.glb = s.viewer = s.pc2 = false;
  s.style.background = Background::transparent;
  s.exr = true;
  s.camera_distance_m = 0.12;
  const std::vector<jellyfish::SliceFrame> frames = testing::synthetic_stroke(2, 0.0, {0.0, 0.004});  // up 4 mm a frame
  const fs::path dir = scratch("rgba_exr");
  write_animation_outputs(frames, s, io::OutputDir(dir));
  const RgbaImage png = read_png_rgba(dir / "frames/frame_0001.png");
  EXPECT_EQ(png.at(0, 0)[3], 0);            // the background
  EXPECT_GT(png.at(32, 24)[3], 80);         // the bell
  EXPECT_GT(fs::file_size(dir / "frames/frame_0001.exr"), 1000u);
  fs::remove_all(dir.parent_path());
}

TEST(Pipeline, WritesEveryPromisedFile) {
  REQUIRE_OFFSCREEN_GL();
  PipelineSettings s = small_settings(96, 72);
  s.video = !find_ffmpeg().empty();
  const std::vector<jellyfish::SliceFrame> frames = testing::synthetic_stroke(4, 0.25);
  const fs::path dir = scratch("pipeline");
  std::size_t calls = 0;
  const AnimationOutputs out =
      write_animation_outputs(frames, s, io::OutputDir(dir), [&](std::size_t, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 4u);
  EXPECT_EQ(out.frames, 4u);
  for (const char* f : {"frames/frame_0000.png", "frames/frame_0003.png", "meshes/frame_0000.obj",
                        "meshes/frame_0003.ply", "jellyfish.glb", "viewer.html", "caches/jellyfish_1.obj",
                        "caches/jellyfish_1.pc2"})
    EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;
  // The page loads jellyfish.glb beside it; the base64 copy only with render.page_embed.
  EXPECT_FALSE(fs::exists(dir / "jellyfish.glb.js"));
  if (s.video) {
    EXPECT_GT(fs::file_size(dir / "jellyfish.mp4"), 1000u);
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  EXPECT_EQ(out.figures()["frames"], 4);
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace jellysim::render
