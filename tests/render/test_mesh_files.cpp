// OBJ, PLY and animated glTF binary writers: structure read back and checked.
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/io/mesh_files.hpp"

namespace jellysim::io {
namespace {

geometry::Animation small_animation(int frames) {
  std::vector<jellyfish::SliceFrame> slices;
  for (int k = 0; k < frames; ++k) {
    geometry::SyntheticBell spec;
    spec.contraction = 0.3 * k;
    spec.time_s = 0.05 * k;
    spec.aperture_centre_m = {0.0, 0.002 * k};
    slices.push_back(geometry::synthetic_bell(spec));
  }
  geometry::GeometrySettings s;
  s.latitude_samples = 21;
  s.disc_points = 16;
  s.tentacle_count = 4;
  s.tentacle_samples = 6;
  return geometry::build_animation(slices, s);
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
  GlbBody body{"jellyfish_1", anim.frames[0], {}, {}};
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

TEST(MeshFiles, MalformedInputsAreInputErrors) {
  EXPECT_THROW(parse_glb("glTF"), InputError);
  geometry::Animation anim = small_animation(2);
  anim.times_s[1] = anim.times_s[0];
  EXPECT_THROW(glb_bytes(anim, {}), InputError);
}

}  // namespace
}  // namespace jellysim::io
