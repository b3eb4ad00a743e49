// The whole animation-output pipeline on the stages experiment's [render] settings: settings read from
// the configuration with bad values naming their field, and every promised file written. Skipped (with
// the reason) where no EGL device exists.
#include <gtest/gtest.h>

#include <filesystem>
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

TEST(Pipeline, WritesEveryPromisedFile) {
  REQUIRE_OFFSCREEN_GL();
  PipelineSettings s = scene::read_render_settings(stages_config());
  s.width_px = 96;
  s.height_px = 72;
  s.geometry.latitude_samples = 21;
  s.geometry.disc_points = 24;
  s.video = !find_ffmpeg().empty();
  std::vector<jellyfish::SliceFrame> frames;
  for (int k = 0; k < 4; ++k) {
    geometry::SyntheticBell spec;
    spec.contraction = 0.25 * k;
    spec.time_s = k / 30.0;
    frames.push_back(geometry::synthetic_bell(spec));
  }
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
