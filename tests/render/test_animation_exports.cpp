// The film camera in the exported files (issue 39): write_animation_outputs with the follow camera
// writes the .glb and .usda with, at every frame, the camera the frame was rendered with (its eye,
// its view direction and up, its field of view and the picture's aspect).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "render_test_util.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/io/mesh_files.hpp"
#include "jellysim/render/animation_outputs.hpp"

namespace jellysim::render {
namespace {

using geometry::Vec3;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Float element `i` (of `width`) of a float accessor.
std::array<double, 4> element(const io::GlbContents& glb, int accessor, std::size_t i, std::size_t width) {
  const nlohmann::json& a = glb.json["accessors"][static_cast<std::size_t>(accessor)];
  const std::size_t at = glb.json["bufferViews"][a["bufferView"].get<std::size_t>()]["byteOffset"].get<std::size_t>();
  std::array<double, 4> out{};
  for (std::size_t c = 0; c < width; ++c) {
    float f;
    std::memcpy(&f, glb.bin.data() + at + 4 * (width * i + c), 4);
    out[c] = f;
  }
  return out;
}

Vec3 rotate(const std::array<double, 4>& q, Vec3 v) {
  const Vec3 u{q[0], q[1], q[2]};
  return 2.0 * geometry::dot(u, v) * u + (q[3] * q[3] - geometry::dot(u, u)) * v + 2.0 * q[3] * geometry::cross(u, v);
}

// The .glb/.usda materials are the renderer's look: colours, opacities and the tissue's
// transmission and attenuation distance (render.transmission, render.attenuation_distance).
TEST(AnimationExports, TheExportedMaterialsCarryTheRenderersLook) {
  RenderStyle style;
  style.umbrella = {0.2, 0.4, 0.6, 0.8};
  style.tentacles = {0.9, 0.1, 0.3, 0.5};
  style.transmission = 0.25;
  style.attenuation_distance_m = 0.004;
  const io::ExportLook look = export_look(style);
  EXPECT_EQ(look.bell_color[1], 0.4);
  EXPECT_EQ(look.umbrella_opacity, 0.8);
  EXPECT_EQ(look.tentacle_color[0], 0.9);
  EXPECT_EQ(look.tentacle_opacity, 0.5);
  EXPECT_EQ(look.transmission, 0.25);
  EXPECT_EQ(look.attenuation_distance_m, 0.004);
}

TEST(AnimationExports, TheExportedCameraIsTheRenderersAtEveryFrame) {
  PipelineSettings s;
  s.camera = "follow";
  s.width_px = 160;
  s.height_px = 90;
  s.geometry.latitude_samples = 21;
  s.geometry.disc_points = 16;
  s.png_frames = s.video = s.obj = s.ply = s.viewer = s.pc2 = false;
  s.usda = true;
  // Swimming up and sideways: the follow camera moves.
  const std::vector<jellyfish::SliceFrame> frames = testing::synthetic_stroke(5, 0.2, {0.003, 0.01});
  const std::filesystem::path dir = testing::scratch("exported_camera");
  const AnimationOutputs out = write_animation_outputs(frames, s, io::OutputDir(dir));
  ASSERT_EQ(out.cameras.size(), 5u);
  EXPECT_GT(geometry::norm(out.cameras[4].eye - out.cameras[0].eye), 0.005);  // it did move
  const io::GlbContents glb = io::parse_glb(slurp(dir / "jellyfish.glb"));
  const nlohmann::json& j = glb.json;
  EXPECT_NEAR(j["cameras"][0]["perspective"]["yfov"].get<double>(), s.fov_y_deg * std::acos(-1.0) / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(j["cameras"][0]["perspective"]["aspectRatio"], 160.0 / 90.0);
  const std::size_t node = j["nodes"].size() - 1;
  ASSERT_EQ(j["nodes"][node]["name"], "camera");
  int translation = -1, rotation = -1;
  for (const auto& ch : j["animations"][0]["channels"])
    if (ch["target"]["node"] == node)
      (ch["target"]["path"] == "translation" ? translation : rotation) =
          j["animations"][0]["samplers"][ch["sampler"].get<std::size_t>()]["output"];
  ASSERT_GE(translation, 0);
  ASSERT_GE(rotation, 0);
  for (std::size_t k = 0; k < 5; ++k) {
    const Camera& c = out.cameras[k];
    const auto e = element(glb, translation, k, 3);
    EXPECT_LT(geometry::norm(Vec3{e[0], e[1], e[2]} - c.eye), 1e-7) << k;  // float storage
    const auto q = element(glb, rotation, k, 4);
    const Vec3 forward = geometry::normalized(c.target - c.eye);
    EXPECT_LT(geometry::norm(rotate(q, {0, 0, -1}) - forward), 1e-6) << k;
    const Vec3 up = rotate(q, {0, 1, 0});  // the renderer's picture up: (f × up) × f
    EXPECT_LT(geometry::norm(up - geometry::cross(geometry::normalized(geometry::cross(forward, c.up)), forward)), 1e-6);
  }
  // The .usda's camera: frame 3's eye in its transform's last row.
  const std::string usda = slurp(dir / "jellyfish.usda");
  const std::size_t at = usda.find("matrix4d xformOp:transform.timeSamples");
  ASSERT_NE(at, std::string::npos);
  const std::size_t row = usda.find("3: ( ", at);
  ASSERT_NE(row, std::string::npos);
  std::string line = usda.substr(row + 3, usda.find('\n', row) - row - 3);
  for (char& ch : line)
    if (ch == '(' || ch == ')' || ch == ',') ch = ' ';
  std::istringstream in(line);
  std::vector<double> m;
  for (double x; in >> x;) m.push_back(x);
  ASSERT_EQ(m.size(), 16u);
  EXPECT_LT(geometry::norm(Vec3{m[12], m[13], m[14]} - out.cameras[3].eye), 1e-15);
  std::filesystem::remove_all(dir.parent_path());
}

// render.vertex_velocities: on (the default) the jellyfish's primitives carry _VELOCITY and the
// .usda its `velocities`; off, neither, and the .glb is smaller by the velocities' bytes.
TEST(AnimationExports, VertexVelocitiesAreWrittenOnlyWhenAskedFor) {
  const std::vector<jellyfish::SliceFrame> frames = testing::synthetic_stroke(4, 0.25);
  std::array<std::size_t, 2> glb_size{};
  for (const bool velocities : {true, false}) {
    PipelineSettings s;
    s.geometry.latitude_samples = 21;
    s.geometry.disc_points = 16;
    s.png_frames = s.video = s.obj = s.ply = s.viewer = s.pc2 = false;
    s.usda = true;
    s.vertex_velocities = velocities;
    const std::filesystem::path dir = testing::scratch(velocities ? "with_velocities" : "without_velocities");
    write_animation_outputs(frames, s, io::OutputDir(dir));
    const std::string bytes = slurp(dir / "jellyfish.glb");
    glb_size[velocities ? 0 : 1] = bytes.size();
    const io::GlbContents glb = io::parse_glb(bytes);
    const nlohmann::json& primitive = glb.json["meshes"][0]["primitives"][0];
    EXPECT_EQ(primitive["attributes"].contains("_VELOCITY"), velocities);
    EXPECT_EQ(primitive["targets"][1].contains("_VELOCITY"), velocities);
    EXPECT_EQ(slurp(dir / "jellyfish.usda").find("vector3f[] velocities") != std::string::npos, velocities);
    std::filesystem::remove_all(dir.parent_path());
  }
  EXPECT_LT(glb_size[1], glb_size[0]);
}

}  // namespace
}  // namespace jellysim::render
