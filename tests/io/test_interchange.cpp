// What the .usda carries beside the meshes (issue 39): vertex velocities from the frame-to-frame
// positions, UsdPreviewSurface materials bound to the parts, face-varying UVs, and the film camera.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/interchange.hpp"
#include "jellysim/io/point_caches.hpp"

namespace jellysim::io {
namespace {

using geometry::Vec3;

/// v rotated by the unit quaternion q (x, y, z, w).
Vec3 rotate(const std::array<double, 4>& q, Vec3 v) {
  const Vec3 u{q[0], q[1], q[2]};
  const double w = q[3];
  return 2.0 * geometry::dot(u, v) * u + (w * w - geometry::dot(u, u)) * v + 2.0 * w * geometry::cross(u, v);
}

TEST(Interchange, ARigidlyTranslatingMeshHasItsTranslationVelocity) {
  const Vec3 velocity{0.03, -0.12, 0.005};  // m/s
  const std::vector<double> times{0.0, 0.04, 0.1, 0.13, 0.2};  // uneven steps
  std::vector<std::vector<Vec3>> frames;
  for (double t : times) frames.push_back({Vec3{0.01, 0.02, 0.0} + t * velocity, Vec3{-0.3, 0.5, 0.2} + t * velocity});
  const auto v = vertex_velocities(frames, times);
  ASSERT_EQ(v.size(), frames.size());
  for (const auto& frame : v)
    for (const Vec3& u : frame) EXPECT_LT(geometry::norm(u - velocity), 1e-12);
  // Central differences inside: x = t² gives 2t exactly on an even grid; one-sided at the ends.
  const std::vector<double> even{0.0, 0.1, 0.2, 0.3};
  std::vector<std::vector<Vec3>> falling;
  for (double t : even) falling.push_back({Vec3{0.0, t * t, 0.0}});
  const auto a = vertex_velocities(falling, even);
  EXPECT_NEAR(a[1][0].y, 0.2, 1e-12);
  EXPECT_NEAR(a[2][0].y, 0.4, 1e-12);
  EXPECT_NEAR(a[0][0].y, 0.1, 1e-12);  // (0.01 − 0) / 0.1
  EXPECT_NEAR(a[3][0].y, 0.5, 1e-12);  // (0.09 − 0.04) / 0.1
  EXPECT_EQ(vertex_velocities({{Vec3{1, 2, 3}}}, {0.0})[0][0], Vec3{});
  EXPECT_THROW(vertex_velocities(frames, {0.0, 0.1}), InputError);
}

TEST(Interchange, CameraRotationTurnsMinusZToTheViewAndYToThePicturesUp) {
  for (const CameraFrame& f : {CameraFrame{{0.1, 0.2, 0.3}, {0.0, 0.0, 0.0}, {0, 1, 0}},
                               CameraFrame{{0.0, 0.05, 0.0}, {0.001, -0.5, 0.002}, {0, 1, 0}},  // looking down
                               CameraFrame{{-0.2, 0.0, -0.1}, {0.3, 0.1, 0.4}, {0, 1, 0}},
                               CameraFrame{{0.0, 0.0, -1.0}, {0.0, 0.0, 0.0}, {0, 1, 0}}}) {  // looking along +z
    const std::array<double, 4> q = camera_rotation(f);
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
    const Vec3 forward = geometry::normalized(f.target - f.eye);
    EXPECT_LT(geometry::norm(rotate(q, {0, 0, -1}) - forward), 1e-12);
    const Vec3 up = rotate(q, {0, 1, 0});
    EXPECT_NEAR(geometry::dot(up, forward), 0.0, 1e-12);
    EXPECT_GT(up.y, 0.0);  // the picture's up leans toward +y
    EXPECT_NEAR(geometry::dot(geometry::cross(rotate(q, {1, 0, 0}), forward), up), 1.0, 1e-12);
  }
}

UsdBody moving_triangle() {
  UsdBody b;
  b.name = "jellyfish_1";
  b.topology.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  b.topology.indices = {0, 1, 2, 1, 3, 2};
  b.topology.parts = {{"umbrella", 0, 3}, {"tentacles", 3, 3}};
  for (int k = 0; k < 3; ++k) {
    b.root.push_back({0.0, 0.0, 0.0});
    const Vec3 shift{0.01 * k, 0.0, -0.002 * k};  // 0.3 m/s along x, −0.06 along z at 30 fps
    b.points.push_back({shift, Vec3{0.01, 0, 0} + shift, Vec3{0, 0.01, 0} + shift, Vec3{0.01, 0.01, 0} + shift});
  }
  b.uv = {{0.0f, 0.0f}, {0.75f, 0.0f}, {0.0f, 1.0f}, {0.5f, 1.0f}};
  return b;
}

/// The numbers of the text between `from` and the next `to`.
std::vector<double> numbers_between(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t a = text.find(from);
  if (a == std::string::npos) return {};
  std::string block = text.substr(a + from.size(), text.find(to, a + from.size()) - a - from.size());
  for (char& c : block)
    if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == 'e')) c = ' ';
  std::istringstream in(block);
  std::vector<double> out;
  for (double x; in >> x;) out.push_back(x);
  return out;
}

TEST(Interchange, UsdHasVelocitiesMaterialsFaceVaryingUvsAndTheCamera) {
  ExportLook look;
  look.bell_color = {0.2, 0.4, 0.9};
  look.umbrella_opacity = 0.3;
  ExportCamera camera;
  camera.fov_y_deg = 35.0;
  camera.aspect = 1.5;
  for (int k = 0; k < 3; ++k) camera.frames.push_back({{0.1 * k, 0.05, 0.3}, {0.1 * k, 0.0, 0.0}, {0, 1, 0}});
  const std::string usda = usda_text({moving_triangle()}, 30.0, "test", look, camera);
  // Velocities: every point of every frame moves at (0.3, 0, −0.06) m/s (float text).
  const std::vector<double> v = numbers_between(usda, "vector3f[] velocities.timeSamples = {", "}");
  ASSERT_EQ(v.size(), 3u * (1 + 4 * 3));  // per frame: its time code, 4 points × 3
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t p = 0; p < 4; ++p) {
      EXPECT_NEAR(v[13 * k + 1 + 3 * p], 0.3, 1e-6);
      EXPECT_NEAR(v[13 * k + 2 + 3 * p], 0.0, 1e-6);
      EXPECT_NEAR(v[13 * k + 3 + 3 * p], -0.06, 1e-6);
    }
  // The material: UsdPreviewSurface with the look's colour, opacity and ior, bound to the subset.
  EXPECT_NE(usda.find("def Material \"umbrella\""), std::string::npos);
  EXPECT_NE(usda.find("uniform token info:id = \"UsdPreviewSurface\""), std::string::npos);
  EXPECT_NE(usda.find("color3f inputs:diffuseColor = (0.2, 0.4, 0.9)"), std::string::npos);
  EXPECT_NE(usda.find("float inputs:opacity = 0.3"), std::string::npos);
  EXPECT_NE(usda.find("float inputs:ior = 1.34"), std::string::npos);
  EXPECT_NE(usda.find("rel material:binding = </jellysim/Looks/umbrella>"), std::string::npos);
  EXPECT_NE(usda.find("rel material:binding = </jellysim/Looks/tentacles>"), std::string::npos);
  // UVs: face-varying, an index per face corner. Both triangles wrap (u spans more than ½): their
  // u = 0 corners use duplicates at u = 1, made per part (the second triangle is another part).
  EXPECT_NE(usda.find("interpolation = \"faceVarying\""), std::string::npos);
  const std::vector<double> st = numbers_between(usda, "texCoord2f[] primvars:st = [", "]");
  EXPECT_EQ(st, (std::vector<double>{0, 0, 0.75, 0, 0, 1, 0.5, 1, 1, 0, 1, 1, 1, 1}));
  EXPECT_EQ(numbers_between(usda, "int[] primvars:st:indices = [", "]"), (std::vector<double>{4, 1, 5, 1, 3, 6}));
  // The camera: its view angle, and frame 2's eye in the transform's last row.
  const std::vector<double> focal = numbers_between(usda, "float focalLength = ", "\n");
  const std::vector<double> aperture = numbers_between(usda, "float verticalAperture = ", "\n");
  ASSERT_EQ(focal.size(), 1u);
  ASSERT_EQ(aperture.size(), 1u);
  EXPECT_NEAR(2.0 * std::atan(0.5 * aperture[0] / focal[0]) * 180.0 / std::numbers::pi, 35.0, 1e-4);
  EXPECT_NEAR(numbers_between(usda, "float horizontalAperture = ", "\n")[0], 1.5 * aperture[0], 1e-4);
  const std::vector<double> m = numbers_between(usda, "matrix4d xformOp:transform.timeSamples = {", "}");
  ASSERT_EQ(m.size(), 3u * 17u);
  EXPECT_NEAR(m[34 + 13], 0.2, 1e-12);  // frame 2: time code, then 16 entries; eye x
  EXPECT_NEAR(m[34 + 14], 0.05, 1e-12);
  EXPECT_NEAR(m[34 + 15], 0.3, 1e-12);
  // Row 3 is "back" (the view direction reversed): (0, 0.05, 0.3) normalised.
  EXPECT_NEAR(m[34 + 10], 0.05 / std::hypot(0.05, 0.3), 1e-12);
  EXPECT_NEAR(m[34 + 11], 0.3 / std::hypot(0.05, 0.3), 1e-12);
  camera.frames.pop_back();
  EXPECT_THROW(usda_text({moving_triangle()}, 30.0, "test", look, camera), InputError);
}

}  // namespace
}  // namespace jellysim::io
