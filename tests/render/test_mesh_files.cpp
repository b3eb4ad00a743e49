// OBJ, PLY and animated glTF binary writers: structure read back and checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/geometry/texture_coordinates.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/io/mesh_files.hpp"

namespace jellysim::io {
namespace {

geometry::GeometrySettings small_settings() {
  geometry::GeometrySettings s;
  s.latitude_samples = 21;
  s.disc_points = 16;
  s.tentacle_count = 4;
  s.tentacle_samples = 6;
  return s;
}

geometry::Animation small_animation(int frames) {
  std::vector<jellyfish::SliceFrame> slices;
  for (int k = 0; k < frames; ++k) {
    geometry::SyntheticBell spec;
    spec.contraction = 0.3 * k;
    spec.time_s = 0.05 * k;
    spec.aperture_centre_m = {0.0, 0.002 * k};
    slices.push_back(geometry::synthetic_bell(spec));
  }
  return geometry::build_animation(slices, small_settings());
}

TEST(MeshFiles, ObjHasEveryVertexNormalAndFace) {
  const geometry::Mesh mesh = small_animation(1).frames[0];
  const std::string text = obj_text(mesh, "test");
  std::istringstream in(text);
  std::string line;
  std::size_t v = 0, vn = 0, f = 0, groups = 0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    if (line.rfind("vn ", 0) == 0) ++vn;
    if (line.rfind("f ", 0) == 0) ++f;
    if (line.rfind("g ", 0) == 0) ++groups;
  }
  EXPECT_EQ(v, mesh.vertex_count());
  EXPECT_EQ(vn, mesh.vertex_count());
  EXPECT_EQ(f, mesh.triangle_count());
  EXPECT_EQ(groups, 2u);
  EXPECT_NE(text.find("f 1//1 "), std::string::npos);
}

TEST(MeshFiles, PlyHeaderAndBinaryBodyAgree) {
  const geometry::Mesh mesh = small_animation(1).frames[0];
  const std::string bytes = ply_bytes(mesh, "test");
  const std::size_t end = bytes.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = bytes.substr(0, end);
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(header.find("element vertex " + std::to_string(mesh.vertex_count()) + "\n"), std::string::npos);
  EXPECT_NE(header.find("element face " + std::to_string(mesh.triangle_count()) + "\n"), std::string::npos);
  const std::size_t body = bytes.size() - end - std::strlen("end_header\n");
  EXPECT_EQ(body, mesh.vertex_count() * 24 + mesh.triangle_count() * 13);
  float x0 = 0.0f;
  std::memcpy(&x0, bytes.data() + end + 11, 4);
  EXPECT_EQ(x0, static_cast<float>(mesh.positions[0].x));
}

TEST(MeshFiles, GlbRoundTripsWithItsVerticesFramesAndBounds) {
  const int frames = 4;
  const geometry::Animation anim = small_animation(frames);
  const std::string bytes = glb_bytes(anim, {{"umbrella", {0.8, 0.9, 1.0, 0.4}, 0.3}});
  ASSERT_EQ(bytes.size() % 4, 0u);
  const GlbContents glb = parse_glb(bytes);
  const nlohmann::json& j = glb.json;
  EXPECT_EQ(j["asset"]["version"], "2.0");
  EXPECT_EQ(j["buffers"][0]["byteLength"].get<std::size_t>(), glb.bin.size());
  const auto& primitives = j["meshes"][0]["primitives"];
  ASSERT_EQ(primitives.size(), 2u);  // umbrella, tentacles
  std::size_t vertices = 0, triangles = 0;
  for (const auto& p : primitives) {
    const auto& position = j["accessors"][p["attributes"]["POSITION"].get<int>()];
    vertices += position["count"].get<std::size_t>();
    triangles += j["accessors"][p["indices"].get<int>()]["count"].get<std::size_t>() / 3;
    EXPECT_EQ(p["targets"].size(), static_cast<std::size_t>(frames - 1));
    // Min/max of the stored floats match the data in the BIN chunk.
    const auto& view = j["bufferViews"][position["bufferView"].get<int>()];
    const std::size_t offset = view["byteOffset"], count = position["count"];
    float lo = 1e30f, hi = -1e30f;
    for (std::size_t v = 0; v < count; ++v) {
      float y;
      std::memcpy(&y, glb.bin.data() + offset + v * 12 + 4, 4);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    EXPECT_EQ(position["min"][1].get<float>(), lo);
    EXPECT_EQ(position["max"][1].get<float>(), hi);
  }
  EXPECT_EQ(vertices, anim.frames[0].vertex_count());
  EXPECT_EQ(triangles, anim.frames[0].triangle_count());
  const auto& sampler = j["animations"][0]["samplers"][0];
  EXPECT_EQ(j["accessors"][sampler["input"].get<int>()]["count"].get<int>(), frames);
  EXPECT_EQ(j["accessors"][sampler["output"].get<int>()]["count"].get<int>(), frames * (frames - 1));
  EXPECT_EQ(j["meshes"][0]["weights"].size(), static_cast<std::size_t>(frames - 1));
  EXPECT_EQ(j["materials"][0]["alphaMode"], "BLEND");
}

// A body with root motion, every second frame (and the last) a target: two nodes (the moving pivot, the scaled
// mesh), quantized position differences that decode to the frames' positions within half a
// quantization step, and the pivot's path as a translation channel.
TEST(MeshFiles, GlbBodiesCarryRootMotionAndQuantizedMorphTargets) {
  using geometry::Vec3;
  const int frames = 4;
  const geometry::Animation anim = small_animation(frames);
  GlbBody body{"jellyfish_1", anim.frames[0], {}, {}, {}, true};
  for (int k = 0; k < frames; ++k) {
    const Vec3 root{0.0, 0.002 * k, 0.0};
    body.root.push_back(root);
    std::vector<Vec3> local = anim.frames[static_cast<std::size_t>(k)].positions;
    for (Vec3& p : local) p = p - root;
    body.positions.push_back(local);
  }
  for (Vec3& p : body.first.positions) p = p - body.root[0];
  const GlbContents glb = parse_glb(glb_bytes({body}, anim.times_s, {}, 2));
  const nlohmann::json& j = glb.json;
  EXPECT_EQ(j["extensionsRequired"][0], "KHR_mesh_quantization");
  ASSERT_EQ(j["nodes"].size(), 2u);
  EXPECT_EQ(j["nodes"][0]["name"], "jellyfish_1");
  EXPECT_EQ(j["nodes"][0]["children"][0], 1);
  const double scale = j["nodes"][1]["scale"][0].get<double>();
  const auto& primitive = j["meshes"][0]["primitives"][0];
  ASSERT_EQ(primitive["targets"].size(), 2u);  // frame 2 and the last, 3
  const auto& base = j["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  const auto& target = j["accessors"][primitive["targets"][1]["POSITION"].get<int>()];
  EXPECT_EQ(target["componentType"], 5122);
  EXPECT_TRUE(target["normalized"].get<bool>());
  const auto& view = j["bufferViews"][target["bufferView"].get<int>()];
  EXPECT_EQ(view["byteStride"], 8);
  const std::size_t base_at = j["bufferViews"][base["bufferView"].get<int>()]["byteOffset"];
  const std::size_t target_at = view["byteOffset"];
  double worst = 0.0;
  for (std::size_t v = 0; v < target["count"].get<std::size_t>(); ++v)
    for (std::size_t c = 0; c < 3; ++c) {
      float b;
      std::int16_t q;
      std::memcpy(&b, glb.bin.data() + base_at + 12 * v + 4 * c, 4);
      std::memcpy(&q, glb.bin.data() + target_at + 8 * v + 2 * c, 2);
      const double decoded = scale * (static_cast<double>(b) + q / 32767.0);
      const Vec3 p = body.positions[3][v];
      worst = std::max(worst, std::abs(decoded - (c == 0 ? p.x : c == 1 ? p.y : p.z)));
    }
  EXPECT_LT(worst, 0.5 * scale / 32767.0 + 1e-7);  // half a step, plus the base's float rounding
  const auto& channels = j["animations"][0]["channels"];
  ASSERT_EQ(channels.size(), 2u);
  EXPECT_EQ(channels[0]["target"]["path"], "weights");
  EXPECT_EQ(channels[1]["target"]["path"], "translation");
  EXPECT_EQ(channels[1]["target"]["node"], 0);
  const auto& weights = j["accessors"][j["animations"][0]["samplers"][0]["output"].get<int>()];
  EXPECT_EQ(weights["componentType"], 5121);
  EXPECT_EQ(weights["count"], 3 * 2);  // keyframes 0, 2, 3 × two targets
}

/// Reads accessor `a`'s element `i`, component `c` as stored (float, or normalized integer).
double accessor_value(const GlbContents& glb, int a, std::size_t i, std::size_t c) {
  const nlohmann::json& accessor = glb.json["accessors"][static_cast<std::size_t>(a)];
  const nlohmann::json& view = glb.json["bufferViews"][accessor["bufferView"].get<std::size_t>()];
  const int type = accessor["componentType"];
  const std::size_t size = type == 5126 ? 4 : type == 5122 ? 2 : 1;
  const std::size_t width = accessor["type"] == "SCALAR" ? 1 : accessor["type"] == "VEC2" ? 2 : accessor["type"] == "VEC3" ? 3 : 4;
  const std::size_t stride = view.contains("byteStride") ? view["byteStride"].get<std::size_t>() : size * width;
  const char* at = glb.bin.data() + view["byteOffset"].get<std::size_t>() + stride * i + size * c;
  if (type == 5126) {
    float f;
    std::memcpy(&f, at, 4);
    return f;
  }
  if (type == 5122) {
    std::int16_t q;
    std::memcpy(&q, at, 2);
    return q / 32767.0;
  }
  return static_cast<std::int8_t>(*at) / 127.0;
}

/// A small bell (its UVs: geometry::texture_coordinates) translating rigidly at `velocity` (m/s)
/// relative to a pivot at the origin, at `anim`'s times.
GlbBody translating_body(const geometry::Animation& anim, geometry::Vec3 velocity) {
  const geometry::FrameGeometry g = geometry::GeometryBuilder(small_settings(), 0.028).build(geometry::synthetic_bell({}));
  GlbBody body{"jellyfish_1", g.mesh, {}, {}, geometry::texture_coordinates(g), true};
  for (double t : anim.times_s) {
    std::vector<geometry::Vec3> p = g.mesh.positions;
    for (geometry::Vec3& x : p) x = x + t * velocity;
    body.positions.push_back(p);
  }
  return body;
}

// Materials (issue 39): the look's colours and opacity; the bell alpha-blended as our renderer draws
// it (no KHR_materials_transmission, which made it glass in Blender and three.js), its tissue's
// transmission, attenuation distance and thickness in the material's extras, KHR_materials_ior.
TEST(MeshFiles, GlbMaterialsCarryTheLookAsAlphaBlendingWithTheTissueInExtras) {
  const geometry::Animation anim = small_animation(3);
  ExportLook look;
  look.bell_color = {0.1, 0.5, 0.7};
  look.umbrella_opacity = 0.25;
  look.transmission = 0.8;
  look.attenuation_distance_m = 0.02;
  look.tissue_thickness_m = 0.0015;
  look.tentacle_color = {0.9, 0.3, 0.2};
  const GlbContents glb = parse_glb(glb_bytes({translating_body(anim, {0.01, 0, 0})}, anim.times_s, glb_materials(look), 1));
  const nlohmann::json& j = glb.json;
  EXPECT_EQ(j["extensionsUsed"], nlohmann::json({"KHR_mesh_quantization", "KHR_materials_ior"}));
  const nlohmann::json& bell = j["materials"][0];
  EXPECT_EQ(bell["name"], "umbrella");
  EXPECT_EQ(bell["pbrMetallicRoughness"]["baseColorFactor"], nlohmann::json({0.1, 0.5, 0.7, 0.25}));
  EXPECT_EQ(bell["alphaMode"], "BLEND");
  EXPECT_TRUE(bell["doubleSided"].get<bool>());  // both walls of the shell drawn, as we draw them
  EXPECT_FALSE(bell["extensions"].contains("KHR_materials_transmission"));
  EXPECT_DOUBLE_EQ(bell["extras"]["jellysim_transmission"], 0.8);
  EXPECT_DOUBLE_EQ(bell["extras"]["jellysim_attenuation_distance_m"], 0.02);
  EXPECT_DOUBLE_EQ(bell["extras"]["jellysim_tissue_thickness_m"], 0.0015);
  EXPECT_DOUBLE_EQ(bell["extensions"]["KHR_materials_ior"]["ior"], 1.34);
  const nlohmann::json& tentacles = j["materials"][1];
  EXPECT_EQ(tentacles["pbrMetallicRoughness"]["baseColorFactor"], nlohmann::json({0.9, 0.3, 0.2, 0.75}));
  EXPECT_FALSE(tentacles.contains("extensions"));
}

// UVs and velocities (issue 39): TEXCOORD_0 one per primitive vertex in [0, 1] with the seam's
// vertices duplicated; _VELOCITY in the base and the morph targets decodes, at every kept frame, to
// the rigid translation's velocity.
TEST(MeshFiles, GlbHasTexCoordsAndVelocitiesOfATranslatingMesh) {
  const geometry::Animation anim = small_animation(4);  // frames 0.05 s apart
  const geometry::Vec3 velocity{0.04, -0.1, 0.02};
  const GlbBody body = translating_body(anim, velocity);
  const GlbContents glb = parse_glb(glb_bytes({body}, anim.times_s, {}, 2));
  const nlohmann::json& mesh = glb.json["meshes"][0];
  const double vscale = mesh["extras"]["velocity_scale_m_per_s"];
  EXPECT_NEAR(vscale, 0.1, 1e-9);  // the largest component, frame 0's (the others' differences are ~0)
  std::size_t vertices = 0;
  for (const auto& p : mesh["primitives"]) {
    const int uv = p["attributes"]["TEXCOORD_0"], velocity_attribute = p["attributes"]["_VELOCITY"];
    const std::size_t count = glb.json["accessors"][static_cast<std::size_t>(uv)]["count"];
    EXPECT_EQ(count, glb.json["accessors"][p["attributes"]["POSITION"].get<std::size_t>()]["count"].get<std::size_t>());
    vertices += count;
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t c = 0; c < 2; ++c) {
        EXPECT_GE(accessor_value(glb, uv, i, c), 0.0);
        EXPECT_LE(accessor_value(glb, uv, i, c), 1.0);
      }
    ASSERT_EQ(p["targets"].size(), 2u);  // frames 2 and 3 (the last)
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const double want = c == 0 ? velocity.x : c == 1 ? velocity.y : velocity.z;
        const double base = vscale * accessor_value(glb, velocity_attribute, i, c);
        EXPECT_NEAR(base, want, 0.5 * vscale / 127.0 + 1e-9);
        for (const auto& t : p["targets"])
          EXPECT_NEAR(base + vscale * accessor_value(glb, t["_VELOCITY"].get<int>(), i, c), want, vscale / 127.0 + 1e-9);
      }
  }
  // The seams were split: a duplicate per umbrella ring (20) and per tube ring (4 tubes × 6 rings).
  EXPECT_EQ(vertices - body.first.vertex_count(), 20u + 4u * 6u);
}

// The film camera (issue 39): a perspective camera node whose animated translation and rotation
// put it at each frame's eye looking at its target.
TEST(MeshFiles, GlbCameraFollowsTheRenderersCamera) {
  using geometry::Vec3;
  const geometry::Animation anim = small_animation(3);
  ExportCamera camera;
  camera.fov_y_deg = 30.0;
  camera.aspect = 2.0;
  for (int k = 0; k < 3; ++k) camera.frames.push_back({{0.02 * k, 0.05, 0.2}, {0.02 * k, -0.01 * k, 0.0}, {0, 1, 0}});
  const GlbContents glb = parse_glb(glb_bytes({translating_body(anim, {})}, anim.times_s, {}, 1, 30.0, camera));
  const nlohmann::json& j = glb.json;
  const nlohmann::json& perspective = j["cameras"][0]["perspective"];
  EXPECT_NEAR(perspective["yfov"].get<double>(), 30.0 * std::acos(-1.0) / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(perspective["aspectRatio"], 2.0);
  EXPECT_NEAR(perspective["znear"].get<double>(), 0.02 * std::hypot(0.05, 0.2), 1e-15);
  const std::size_t node = j["nodes"].size() - 1;
  EXPECT_EQ(j["nodes"][node]["camera"], 0);
  EXPECT_NE(std::find(j["scenes"][0]["nodes"].begin(), j["scenes"][0]["nodes"].end(), node), j["scenes"][0]["nodes"].end());
  int translation = -1, rotation = -1;
  for (const auto& ch : j["animations"][0]["channels"])
    if (ch["target"]["node"] == node) {
      const int output = j["animations"][0]["samplers"][ch["sampler"].get<std::size_t>()]["output"];
      (ch["target"]["path"] == "translation" ? translation : rotation) = output;
    }
  ASSERT_GE(translation, 0);
  ASSERT_GE(rotation, 0);
  for (std::size_t k = 0; k < 3; ++k) {
    const CameraFrame& f = camera.frames[k];
    EXPECT_NEAR(accessor_value(glb, translation, k, 0), f.eye.x, 1e-7);
    EXPECT_NEAR(accessor_value(glb, translation, k, 2), f.eye.z, 1e-7);
    const std::array<double, 4> q{accessor_value(glb, rotation, k, 0), accessor_value(glb, rotation, k, 1),
                                  accessor_value(glb, rotation, k, 2), accessor_value(glb, rotation, k, 3)};
    // −z rotated by q: 2 (u·v) u + (w² − u·u) v + 2 w (u × v) with v = (0, 0, −1).
    const Vec3 u{q[0], q[1], q[2]};
    const Vec3 view = -2.0 * u.z * u + (q[3] * q[3] - geometry::dot(u, u)) * Vec3{0, 0, -1} +
                      2.0 * q[3] * geometry::cross(u, Vec3{0, 0, -1});
    EXPECT_LT(geometry::norm(view - geometry::normalized(f.target - f.eye)), 1e-6);
  }
}

TEST(MeshFiles, ObjHasTexCoordsWithTheSeamSplitPerCorner) {
  const geometry::Mesh mesh = small_animation(1).frames[0];
  std::vector<geometry::TexCoord> uv(mesh.vertex_count());
  for (std::size_t v = 0; v < uv.size(); ++v) uv[v] = {static_cast<float>(v % 4) / 4.0f, 0.5f};
  const std::string text = obj_text(mesh, "test", "", uv);
  std::istringstream in(text);
  std::string line;
  std::size_t vt = 0, with_texture = 0, faces = 0;
  while (std::getline(in, line)) {
    vt += line.rfind("vt ", 0) == 0;
    if (line.rfind("f ", 0) == 0) {
      ++faces;
      with_texture += line.find("//") == std::string::npos;
    }
  }
  EXPECT_GT(vt, mesh.vertex_count());  // the per-vertex entries and the seam's duplicates
  EXPECT_EQ(with_texture, faces);
  EXPECT_NE(text.find("f 1/"), std::string::npos);
  EXPECT_EQ(text.find("vt 1.1"), std::string::npos);
}

TEST(MeshFiles, MalformedInputsAreInputErrors) {
  EXPECT_THROW(parse_glb("glTF"), InputError);
  geometry::Animation anim = small_animation(2);
  anim.times_s[1] = anim.times_s[0];
  EXPECT_THROW(glb_bytes(anim, {}), InputError);
}

}  // namespace
}  // namespace jellysim::io
