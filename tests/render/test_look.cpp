// Look development (issue 39), the renderer's part: an opaque bell drawn front-most, transparent
// backgrounds as RGBA with alpha 0, OpenEXR frames read back with OpenEXR's own reader, the camera
// framed in metres.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/render/exr_frames.hpp"
#include "render_test_util.hpp"

namespace jellysim::render {
namespace {

namespace fs = std::filesystem;
using geometry::Vec3;
using testing::scratch;

geometry::FrameGeometry plain_bell(double scale = 1.0) {
  geometry::GeometrySettings s;
  s.noise.structural_weight = s.noise.compression_weight = s.noise.unstructured_weight = 0.0;
  const auto slice = geometry::synthetic_bell(0.04 * scale, 0.028 * scale, 0.0, 21, 8);
  return geometry::GeometryBuilder(s, 0.028 * scale).build(slice);
}

/// Looking into the bell's cavity from below and to the side, where the cavity's far inner wall lies
/// behind the near outer wall.
Camera view_from_below() { return camera_looking_at({0.0, 0.008, 0.0}, {0.3, -0.35, 1.0}, 0.11, 40.0); }

TEST(Look, AnOpaqueBellIsDrawnFrontMost) {
  REQUIRE_OFFSCREEN_GL();
  const geometry::FrameGeometry g = plain_bell();
  RenderStyle opaque;
  opaque.umbrella[3] = 1.0;
  opaque.rim = 0.0;
  opaque.obstacles = opaque.umbrella;
  // The ground truth: the same surface as an opaque part drawn with plain depth testing.
  geometry::Mesh reference = g.mesh;
  for (geometry::MeshPart& part : reference.parts)
    if (part.name == "umbrella") part.name = "obstacles";
  OffscreenRenderer renderer(160, 120);
  const RgbImage bell = renderer.render(g.mesh, view_from_below(), opaque);
  const RgbImage truth = renderer.render(reference, view_from_below(), opaque);
  const ImageDifference d = compare_images(bell, truth);
  // Measured: mean 0.018, a few edge pixels up to 10 levels (multisampled silhouettes drawn in
  // another order). In mesh order without depth writes (how the back-then-front passes drew the
  // front faces) the cavity's far wall covers the near one: mean 5.4, max 117.
  EXPECT_LT(d.mean_abs, 0.05);
  EXPECT_LE(d.max_abs, 16);
}

TEST(Look, TransparentBackgroundHasAlphaZeroAndTheBellCovers) {
  REQUIRE_OFFSCREEN_GL();
  const geometry::FrameGeometry g = plain_bell();
  RenderStyle style;
  style.background = Background::transparent;
  OffscreenRenderer renderer(160, 120);
  renderer.draw(g.mesh, view_from_below(), style);
  RgbaImage image;
  renderer.read_back(image);
  EXPECT_EQ(image.at(2, 2)[3], 0);
  EXPECT_EQ(image.at(157, 117)[3], 0);
  // The bell's middle: at least its base opacity 0.35 (two walls of it: more).
  EXPECT_GE(image.at(80, 60)[3], 89);
  // Through a PNG: alpha kept, straight colour.
  const fs::path file = scratch("rgba") / "frame.png";
  io::write_file(file, png_bytes(image));
  const RgbaImage back = read_png_rgba(file);
  EXPECT_EQ(back.pixels, image.pixels);
  // The water and a solid colour stay opaque.
  style.background = Background::solid;
  renderer.draw(g.mesh, view_from_below(), style);
  renderer.read_back(image);
  EXPECT_EQ(image.at(2, 2)[3], 255);
  EXPECT_EQ(image.at(80, 60)[3], 255);
}

/// A square of side `side_m` facing the camera at `distance_m`, as an opaque part.
geometry::Mesh square_facing(const Camera& c, double distance_m, double side_m, Vec3 shift) {
  const Vec3 f = geometry::normalized(c.target - c.eye);
  const Vec3 r = geometry::normalized(geometry::cross(f, c.up)), u = geometry::cross(r, f);
  const Vec3 centre = c.eye + distance_m * f + shift;
  geometry::Mesh m;
  for (double a : {-0.5, 0.5})
    for (double b : {-0.5, 0.5}) {
      m.positions.push_back(centre + (a * side_m) * r + (b * side_m) * u);
      m.normals.push_back(-1.0 * f);
    }
  m.indices = {0, 2, 3, 0, 3, 1};
  m.parts.push_back({"obstacles", 0, 6});
  return m;
}

/// Reads one float channel of an EXR file with OpenEXR's reader.
std::vector<float> read_channel(const fs::path& file, const char* name, Imf::PixelType type = Imf::FLOAT) {
  Imf::InputFile in(file.c_str());
  const Imath::Box2i w = in.header().dataWindow();
  const int width = w.max.x - w.min.x + 1, height = w.max.y - w.min.y + 1;
  std::vector<float> values(static_cast<std::size_t>(width * height));
  Imf::FrameBuffer frame;
  frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float),
                                sizeof(float) * static_cast<std::size_t>(width)));
  in.setFrameBuffer(frame);
  in.readPixels(w.min.y, w.max.y);
  EXPECT_EQ(in.header().channels().findChannel(name)->type, type) << name;
  return values;
}

TEST(Look, ExrFrameHoldsBeautyDepthAndVelocityReadBackByOpenExr) {
  REQUIRE_OFFSCREEN_GL();
  const Camera camera = camera_looking_at({0.0, 0.0, 0.0}, {0.3, 0.2, 1.0}, 0.1, 40.0);
  const double distance = 0.08, dx = 0.002;  // the square moved dx to the right since the last frame
  const Vec3 right = geometry::normalized(geometry::cross(camera.target - camera.eye, camera.up));
  const geometry::Mesh now = square_facing(camera, distance, 0.02, Vec3{});
  const geometry::Mesh before = square_facing(camera, distance, 0.02, -dx * right);
  RenderStyle style;
  style.background = Background::transparent;
  const int W = 160, H = 120;
  OffscreenRenderer renderer(W, H);
  renderer.draw(now, camera, style);
  RgbaImage beauty;
  renderer.read_back(beauty);
  FramePasses passes;
  renderer.draw_passes(now, before.positions, camera, camera, passes);
  const fs::path file = scratch("exr") / "frame_0000.exr";
  io::write_file(file, exr_bytes(beauty, passes));

  Imf::InputFile in(file.c_str());
  std::vector<std::string> names;
  for (auto c = in.header().channels().begin(); c != in.header().channels().end(); ++c) names.push_back(c.name());
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "G", "R", "Z", "velocity.X", "velocity.Y"}));
  const auto z = read_channel(file, "Z"), vx = read_channel(file, "velocity.X"), vy = read_channel(file, "velocity.Y");
  const auto alpha = read_channel(file, "A", Imf::HALF), red = read_channel(file, "R", Imf::HALF);
  const std::size_t centre = static_cast<std::size_t>(H / 2 * W + W / 2), corner = 0;
  // Depth: the square's distance along the view axis; the background far away.
  EXPECT_NEAR(z[centre], distance, 1e-6);
  EXPECT_EQ(z[corner], kBackgroundDepth);
  // Velocity: dx at that distance in pixels, (H/2) / (d tan(fov/2)) per metre, to the right.
  const double expected = dx * (H / 2.0) / (distance * std::tan(20.0 * std::numbers::pi / 180.0));
  EXPECT_NEAR(vx[centre], expected, 1e-3 * expected);
  EXPECT_NEAR(vy[centre], 0.0, 1e-3);
  EXPECT_EQ(vx[corner], 0.0f);
  // Beauty: opaque square, transparent background; linear premultiplied colour.
  EXPECT_EQ(alpha[centre], 1.0f);
  EXPECT_EQ(alpha[corner], 0.0f);
  const auto px = beauty.at(W / 2, H / 2);
  EXPECT_NEAR(red[centre], linear_premultiplied(px[0], px[3]), 1e-3);
  EXPECT_NEAR(linear_premultiplied(128, 255), 0.2195, 1e-4);  // (128/255)^2.2
}

/// The bell's width on screen (picture heights) under the fixed camera.
double screen_width(double scale, const PipelineSettings& s) {
  const geometry::FrameGeometry g = plain_bell(scale);
  const auto slice = geometry::synthetic_bell(0.04 * scale, 0.028 * scale, 0.0, 21, 8);
  const Camera c = fixed_camera({{slice}}, s, g.mesh);
  const auto a = screen_position(c, {slice.umbrella.front().x, slice.umbrella.front().y, 0.0});
  const auto b = screen_position(c, {slice.umbrella.back().x, slice.umbrella.back().y, 0.0});
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

TEST(Look, CameraFramedInMetresShowsABiggerBellBigger) {
  PipelineSettings metres;  // camera_distance_m = 0.22
  const double ratio = screen_width(2.0, metres) / screen_width(1.0, metres);
  EXPECT_NEAR(ratio, 2.0, 0.1);
  PipelineSettings extents;
  extents.camera_distance = 2.6;  // the former framing: in first-frame mesh extents
  EXPECT_NEAR(screen_width(2.0, extents) / screen_width(1.0, extents), 1.0, 0.005);  // 1.0016: the tubes keep their radius
}

}  // namespace
}  // namespace jellysim::render
