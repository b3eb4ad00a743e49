// Offscreen rendering (EGL surfaceless, Mesa llvmpipe), PNG round trip, the stored reference image
// (the whole animation-output pipeline: tests/experiments/test_render_pipeline.cpp). Skipped (with the reason) where no EGL device exists.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/obstacle_mesh.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/render/gl_renderer.hpp"
#include "jellysim/render/video.hpp"
#include "render_test_util.hpp"

namespace jellysim::render {
namespace {

namespace fs = std::filesystem;
using testing::scratch;

/// The known scene of the reference image: the expanded synthetic bell without noise.
RgbImage render_known_mesh() {
  geometry::GeometrySettings s;
  s.noise.structural_weight = s.noise.compression_weight = s.noise.unstructured_weight = 0.0;
  const auto slice = geometry::synthetic_bell(0.04, 0.028, 0.0, 21, 8);
  const geometry::FrameGeometry g = geometry::GeometryBuilder(s, 0.028).build(slice);
  const Camera camera = camera_looking_at({0.0, 0.008, 0.0}, {0.4, 0.25, 1.0}, 0.11, 40.0);
  OffscreenRenderer renderer(160, 120);
  return renderer.render(g.mesh, camera, RenderStyle{});
}

double brightness(Rgb c) { return (c[0] + c[1] + c[2]) / 3.0; }

TEST(Renderer, JellyfishStandsOutFromTheWater) {
  REQUIRE_OFFSCREEN_GL();
  const RgbImage image = render_known_mesh();
  ASSERT_EQ(image.width, 160);
  // The bell (image centre) is brighter than the water beside it at the same height.
  EXPECT_GT(brightness(image.at(80, 50)), brightness(image.at(5, 50)) + 40.0);
  // Background: lighter near the surface than in the depth.
  EXPECT_GT(brightness(image.at(5, 2)), brightness(image.at(5, 117)));
}

TEST(Renderer, MatchesTheStoredReferenceImage) {
  REQUIRE_OFFSCREEN_GL();
  const RgbImage image = render_known_mesh();
  const fs::path reference = fs::path(JELLYSIM_SOURCE_DIR) / "tests/render/data/reference_bell.png";
  if (std::getenv("JELLYSIM_UPDATE_REFERENCE")) write_png(image, reference);
  const RgbImage expected = read_png(reference);
  const ImageDifference d = compare_images(image, expected);
  // Tolerance: mean |Δ| ≤ 1 level per channel (0–255), no pixel off by more than 48 levels —
  // room for another Mesa/llvmpipe version's rounding and multisample patterns, none for a
  // missing mesh, wrong camera or wrong lighting (each moves the mean by ≥ 5 levels).
  EXPECT_LE(d.mean_abs, 1.0);
  EXPECT_LE(d.max_abs, 48);
}

/// The noisy expanded bell of the reference scene.
geometry::FrameGeometry noisy_bell() {
  return geometry::GeometryBuilder(geometry::GeometrySettings{}, 0.028).build(geometry::synthetic_bell(0.04, 0.028, 0.6, 21, 8));
}
Camera reference_camera() { return camera_looking_at({0.0, 0.008, 0.0}, {0.4, 0.25, 1.0}, 0.11, 40.0); }

// Obstacles are opaque and drawn before the translucent umbrella, writing depth: a prism in front of
// the bell hides it completely, so the picture there is the prism's alone.
TEST(Renderer, ObstaclePrismInFrontHidesTheBell) {
  REQUIRE_OFFSCREEN_GL();
  const geometry::FrameGeometry bell = noisy_bell();
  const std::vector<Vec2> box{{-0.01, -0.002}, {0.01, -0.002}, {0.01, 0.018}, {-0.01, 0.018}};
  const geometry::ObstaclePrisms prisms({box}, 0.06);  // its near cap at z = 3 cm, the bell's rim at 2 cm
  geometry::Mesh with_bell = bell.mesh, alone;
  prisms.append({box}, with_bell);
  prisms.append({box}, alone);
  OffscreenRenderer renderer(160, 120);
  const RgbImage a = renderer.render(with_bell, reference_camera(), RenderStyle{});
  const RgbImage b = renderer.render(alone, reference_camera(), RenderStyle{});
  const RgbImage c = renderer.render(bell.mesh, reference_camera(), RenderStyle{});
  EXPECT_EQ(a.at(80, 60), b.at(80, 60));
  EXPECT_GT(std::abs(brightness(a.at(80, 60)) - brightness(c.at(80, 60))), 10.0);
}

TEST(Renderer, FramesRepeatWithReusedImagesAndTheCachedBackground) {
  REQUIRE_OFFSCREEN_GL();
  const geometry::FrameGeometry g = noisy_bell();
  OffscreenRenderer renderer(160, 120);
  const RgbImage first = renderer.render(g.mesh, reference_camera(), RenderStyle{});
  RgbImage reused;
  renderer.render(g.mesh, reference_camera(), RenderStyle{}, reused);
  EXPECT_EQ(reused.pixels, first.pixels);
  renderer.draw(g.mesh, reference_camera(), RenderStyle{});
  renderer.read_back(reused);
  EXPECT_EQ(reused.pixels, first.pixels);
  // Another water colour redraws the cached background; going back restores the first frame.
  RenderStyle green;
  green.water_top = {0.1, 0.6, 0.2};
  const RgbImage other = renderer.render(g.mesh, reference_camera(), green);
  EXPECT_GT(compare_images(other, first).mean_abs, 5.0);
  renderer.render(g.mesh, reference_camera(), RenderStyle{}, reused);
  EXPECT_EQ(reused.pixels, first.pixels);
  // The background alone (no parts drawn) is the water, as before the mesh.
  geometry::Mesh nothing = g.mesh;
  nothing.parts.clear();
  const RgbImage water = renderer.render(nothing, reference_camera(), RenderStyle{});
  EXPECT_EQ(water.at(5, 60), first.at(5, 60));
  EXPECT_GT(compare_images(water, first).mean_abs, 5.0);
}

TEST(Renderer, InteractiveSettingsStayCloseToTheDefaultLook) {
  REQUIRE_OFFSCREEN_GL();
  const geometry::FrameGeometry g = noisy_bell();
  OffscreenRenderer multisampled(160, 120), single(160, 120, 1);
  EXPECT_EQ(single.samples(), 1);
  EXPECT_GT(multisampled.samples(), 1);
  RenderStyle gouraud;
  gouraud.per_vertex_lighting = true;
  const RgbImage reference = multisampled.render(g.mesh, reference_camera(), RenderStyle{});
  // Measured with llvmpipe (Mesa 22.3): per-vertex lighting 0.41 levels mean, no multisampling
  // 1.0 (aliased edges differ by up to ~220 levels, so no bound on the largest difference).
  EXPECT_LE(compare_images(multisampled.render(g.mesh, reference_camera(), gouraud), reference).mean_abs, 1.0);
  EXPECT_LE(compare_images(single.render(g.mesh, reference_camera(), RenderStyle{}), reference).mean_abs, 2.5);
  EXPECT_LE(compare_images(single.render(g.mesh, reference_camera(), gouraud), reference).mean_abs, 2.5);
  EXPECT_GT(compare_images(single.render(g.mesh, reference_camera(), gouraud), reference).mean_abs, 0.0);
}

TEST(Renderer, PngRoundTripIsExact) {
  RgbImage image(7, 5, {10, 20, 30});
  image.set(3, 2, {255, 0, 128});
  draw_text(image, 0, 0, "A", 1, {1, 2, 3});
  const fs::path file = scratch("png") / "a.png";
  write_png(image, file);
  const RgbImage back = read_png(file);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_THROW(read_png(file.parent_path() / "missing.png"), InputError);
  fs::remove_all(file.parent_path().parent_path());
}

TEST(Renderer, BadSizeIsAnInputError) {
  EXPECT_THROW(OffscreenRenderer(4, 4), InputError);
}

}  // namespace
}  // namespace jellysim::render
