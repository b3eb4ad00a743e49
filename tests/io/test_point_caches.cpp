// Point caches and the USD stage (io/point_caches.hpp): the bytes each format's readers expect.
// (That Blender's Mesh Cache modifier plays a PC2 file exactly is checked by
// scripts/check-point-cache-in-blender.py; docs/rendering.md records the run.)
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <regex>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/point_caches.hpp"

namespace jellysim::io {
namespace {

using geometry::Vec3;

PointFrames two_frames() { return {{{1, 2, 3}, {4, 5, 6}}, {{1.5, 2, 3}, {4, 5.5, 6.25}}}; }

template <class T>
T read_le(const std::string& bytes, std::size_t at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

float read_be_float(const std::string& bytes, std::size_t at) {
  std::uint32_t bits = 0;
  for (int b = 0; b < 4; ++b) bits = (bits << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(b)]);
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

TEST(PointCaches, Pc2HasItsHeaderAndOneSamplePerFrame) {
  const std::string b = pc2_bytes(two_frames(), 0.0);
  ASSERT_EQ(b.size(), 32u + 2u * 2u * 12u);
  EXPECT_EQ(b.substr(0, 12), std::string("POINTCACHE2\0", 12));
  EXPECT_EQ(read_le<std::int32_t>(b, 12), 1);  // version
  EXPECT_EQ(read_le<std::int32_t>(b, 16), 2);  // points
  EXPECT_EQ(read_le<float>(b, 20), 0.0f);      // start frame
  EXPECT_EQ(read_le<float>(b, 24), 1.0f);      // sample rate
  EXPECT_EQ(read_le<std::int32_t>(b, 28), 2);  // samples
  EXPECT_EQ(read_le<float>(b, 32 + 24), 1.5f);          // frame 1, point 0, x
  EXPECT_EQ(read_le<float>(b, 32 + 24 + 12 + 8), 6.25f);  // frame 1, point 1, z
}

TEST(PointCaches, MddIsBigEndianWithFrameTimes) {
  const std::string b = mdd_bytes(two_frames(), {0.0, 1.0 / 30.0});
  ASSERT_EQ(b.size(), 8u + 2u * 4u + 2u * 2u * 12u);
  EXPECT_EQ(static_cast<unsigned char>(b[3]), 2u);  // frames, big-endian
  EXPECT_EQ(static_cast<unsigned char>(b[7]), 2u);  // points
  EXPECT_EQ(read_be_float(b, 12), 1.0f / 30.0f);
  EXPECT_EQ(read_be_float(b, 16 + 24 + 16), 5.5f);  // frame 1, point 1, y
  EXPECT_THROW(mdd_bytes(two_frames(), {0.0}), InputError);
}

TEST(PointCaches, FramesMustKeepTheirPointCount) {
  PointFrames f = two_frames();
  f[1].pop_back();
  EXPECT_THROW(pc2_bytes(f, 0.0), InputError);
  EXPECT_THROW(pc2_bytes({}, 0.0), InputError);
}

UsdBody triangle_body(const std::string& name) {
  UsdBody b;
  b.name = name;
  b.topology.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  b.topology.indices = {0, 1, 2};
  b.topology.parts = {{"umbrella", 0, 3}};
  b.root = {{0.1, 0.2, 0.0}, {0.1, 0.25, 0.0}};
  b.points = {{{-0.01, 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}}, {{-0.01, 0, 0}, {0.01, 0, 0}, {0, 0.02, 0}}};
  return b;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PointCaches, UsdStageHasAPrimPerBodyWithRootMotionAndTimeSampledPoints) {
  const std::string usda = usda_text({triangle_body("jellyfish_1"), triangle_body("jellyfish_2")}, 30.0, "test");
  EXPECT_TRUE(usda.starts_with("#usda 1.0\n"));
  for (const char* line : {"upAxis = \"Y\"", "metersPerUnit = 1", "timeCodesPerSecond = 30", "framesPerSecond = 30",
                           "startTimeCode = 0", "endTimeCode = 1", "defaultPrim = \"jellysim\""})
    EXPECT_NE(usda.find(line), std::string::npos) << line;
  EXPECT_EQ(count(usda, "def Xform \"jellyfish_"), 2u);
  EXPECT_EQ(count(usda, "def Mesh \"mesh\""), 2u);
  EXPECT_EQ(count(usda, "double3 xformOp:translate.timeSamples"), 2u);
  EXPECT_NE(usda.find("1: (0.1, 0.25, 0),"), std::string::npos);  // root motion, frame 1
  EXPECT_NE(usda.find("1: [(-0.01, 0, 0), (0.01, 0, 0), (0, 0.02, 0)],"), std::string::npos);
  EXPECT_NE(usda.find("int[] faceVertexIndices = [0, 1, 2]"), std::string::npos);
  EXPECT_NE(usda.find("def GeomSubset \"umbrella\""), std::string::npos);
  // Braces and brackets balance (a reader would choke otherwise).
  EXPECT_EQ(count(usda, "{"), count(usda, "}"));
  EXPECT_EQ(count(usda, "["), count(usda, "]"));
  EXPECT_EQ(count(usda, "("), count(usda, ")"));
  EXPECT_THROW(usda_text({triangle_body("2nd")}, 30.0, "test"), InputError);  // not a prim name
  UsdBody short_body = triangle_body("b");
  short_body.root.pop_back();
  EXPECT_THROW(usda_text({short_body}, 30.0, "test"), InputError);
}

}  // namespace
}  // namespace jellysim::io
