// The simulated 3D bell's files (render::write_surface_animation_outputs): the slice pipeline's
// outputs from a triangulated surface instead of extrapolated slices. The synthetic bell's slice
// revolved (geometry::revolved_synthetic_bell) is the same bell as the slice pipeline draws from the
// slice itself, so the two pictures are compared.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/io/mesh_files.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/render/video.hpp"
#include "render_test_util.hpp"

namespace jellysim::render {
namespace {

constexpr int kRingPoints = 48, kFrames = 4;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The synthetic bell contracting by 0.2 a frame at 30 frames/s (as testing::synthetic_stroke).
std::vector<geometry::SyntheticBell> stroke_specs() {
  std::vector<geometry::SyntheticBell> specs(kFrames);
  for (int k = 0; k < kFrames; ++k) {
    specs[static_cast<std::size_t>(k)].contraction = 0.2 * k;
    specs[static_cast<std::size_t>(k)].time_s = k / 30.0;
  }
  return specs;
}

/// Small frames over a transparent background (the bell's coverage is its alpha), no noise, the
/// slice's two tentacles drawn as two strands (σ = 0 and π: where the surface's strands hang).
PipelineSettings small_settings() {
  PipelineSettings s;
  s.width_px = 160;
  s.height_px = 120;
  s.style.background = Background::transparent;
  s.geometry.noise.structural_weight = s.geometry.noise.compression_weight = s.geometry.noise.unstructured_weight = 0.0;
  s.geometry.tentacle_count = 2;
  s.video = false;
  s.glb = s.obj = s.ply = s.viewer = s.pc2 = false;
  return s;
}

std::int32_t int_at(const std::string& bytes, std::size_t at) {
  std::int32_t v;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

/// Pixels with alpha > 0, and the mean |Δ| of the colour channels of two frames of one size.
std::size_t covered(const RgbaImage& image) {
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.at(x, y)[3] > 0 ? 1 : 0;
  return n;
}
double mean_difference(const RgbaImage& a, const RgbaImage& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 4; ++c) sum += std::abs(a.at(x, y)[static_cast<std::size_t>(c)] - b.at(x, y)[static_cast<std::size_t>(c)]);
  return sum / (4.0 * a.width * a.height);
}

TEST(SurfaceOutputs, TheSimulatedBellGetsEveryFileOfTheSlicePipeline) {
  const geometry::SurfaceFrames frames = geometry::revolved_synthetic_bell(stroke_specs(), kRingPoints, 2);
  PipelineSettings s = small_settings();
  std::string why;
  s.png_frames = offscreen_gl_available(&why);
  s.video = s.png_frames && !find_ffmpeg().empty();
  s.glb = s.obj = s.ply = s.viewer = s.pc2 = s.mdd = s.usda = true;
  s.geometry.tentacle_samples = 10;
  const std::filesystem::path dir = testing::scratch("surface_files");
  const AnimationOutputs out = write_surface_animation_outputs(frames, s, io::OutputDir(dir));
  EXPECT_EQ(out.frames, static_cast<std::size_t>(kFrames));
  // The wall (both surfaces) and two tubes of 10 rings of 6 sides.
  const std::size_t N = frames.surface.front().size(), rings = 10, tubes = 2 * 10 * 6;
  EXPECT_EQ(out.vertices, 2 * N + tubes);
  for (const char* f : {"jellyfish.glb", "blender_import.py", "viewer.html", "caches/jellyfish_1.obj",
                        "caches/jellyfish_1.pc2", "caches/jellyfish_1.mdd", "jellyfish.usda", "meshes/frame_0003.obj",
                        "meshes/frame_0003.ply"})
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / f)) << f;
  EXPECT_EQ(std::filesystem::is_regular_file(dir / "frames/frame_0003.png"), s.png_frames);
  EXPECT_EQ(std::filesystem::is_regular_file(dir / "jellyfish.mp4"), s.video);
  // The .glb read back: the frames, and the vertices with the u seam's duplicates (one per ring on
  // each surface, one per tube ring).
  const io::GlbContents glb = io::parse_glb(slurp(dir / "jellyfish.glb"));
  EXPECT_EQ(glb.json["asset"]["extras"]["frame_count"], kFrames);
  std::size_t glb_vertices = 0;
  for (const auto& primitive : glb.json["meshes"][0]["primitives"])
    glb_vertices += glb.json["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()]["count"].get<std::size_t>();
  EXPECT_EQ(glb_vertices, 2 * N + 2 * rings + tubes + 2 * 10);
  EXPECT_TRUE(glb.json["meshes"][0]["primitives"][0]["attributes"].contains("_VELOCITY"));
  // The point cache: every vertex, every frame.
  const std::string pc2 = slurp(dir / "caches/jellyfish_1.pc2");
  EXPECT_EQ(int_at(pc2, 16), static_cast<std::int32_t>(out.vertices));
  EXPECT_EQ(int_at(pc2, 28), kFrames);
  EXPECT_EQ(pc2.size(), 32 + 12 * out.vertices * kFrames);
  std::filesystem::remove_all(dir.parent_path());
}

TEST(SurfaceOutputs, TheRevolvedBellLooksLikeTheSlicePipelinesBell) {
  REQUIRE_OFFSCREEN_GL();
  const std::vector<geometry::SyntheticBell> specs = stroke_specs();
  PipelineSettings s = small_settings();
  s.png_frames = true;
  const std::filesystem::path surface_dir = testing::scratch("surface_look"), slice_dir = testing::scratch("slice_look");
  write_surface_animation_outputs(geometry::revolved_synthetic_bell(specs, kRingPoints, 2), s, io::OutputDir(surface_dir));
  std::vector<jellyfish::SliceFrame> slices;
  for (const geometry::SyntheticBell& spec : specs) slices.push_back(geometry::synthetic_bell(spec));
  write_animation_outputs(slices, s, io::OutputDir(slice_dir));
  // Measured: the bell covers 0.0368 (frame 0) and 0.0307 (frame 3, contracted) of the picture, 0.9972
  // and 0.9899 times the slice pipeline's bell, the frames 0.068 and 0.092 levels apart on average.
  const std::array<double, 2> expected_coverage{0.0368, 0.0307};
  for (int k : {0, kFrames - 1}) {
    const std::string name = "frames/frame_000" + std::to_string(k) + ".png";
    const RgbaImage surface = read_png_rgba(surface_dir / name), slice = read_png_rgba(slice_dir / name);
    const double coverage = static_cast<double>(covered(surface)) / (s.width_px * s.height_px);
    const double ratio = static_cast<double>(covered(surface)) / static_cast<double>(covered(slice));
    const double difference = mean_difference(surface, slice);
    std::printf("frame %d: the bell covers %.4f of the picture, %.4f times the slice pipeline's; mean |Δ| %.3f levels\n", k,
                coverage, ratio, difference);
    EXPECT_NEAR(coverage, expected_coverage[k == 0 ? 0 : 1], 0.002);
    EXPECT_NEAR(ratio, 1.0, 0.02);
    EXPECT_LT(difference, 0.3);
  }
  std::filesystem::remove_all(surface_dir.parent_path());
}

}  // namespace
}  // namespace jellysim::render
