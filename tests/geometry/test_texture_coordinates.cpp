// Texture coordinates of the jellyfish mesh (issue 39): one per vertex, in [0, 1], u around the axis
// and the tubes, v monotone along the bell's profile (apex → margin on both surfaces) and along the
// tentacles; the u seam split so that no triangle's coordinates wrap.
#include <gtest/gtest.h>

#include <algorithm>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/geometry/texture_coordinates.hpp"

namespace jellysim::geometry {
namespace {

FrameGeometry small_bell() {
  GeometrySettings s;
  s.latitude_samples = 21;
  s.disc_points = 16;
  s.tentacle_count = 4;
  s.tentacle_samples = 6;
  s.tube_sides = 5;
  const jellyfish::SliceFrame slice = synthetic_bell(0.04, 0.028, 0.4, 21, 8);
  return GeometryBuilder(s, 0.028).build(slice);
}

TEST(TextureCoordinates, OnePerVertexInTheUnitSquareAroundTheAxisAndAlongTheProfile) {
  const FrameGeometry g = small_bell();
  const std::vector<TexCoord> uv = texture_coordinates(g);
  ASSERT_EQ(uv.size(), g.mesh.vertex_count());
  for (const TexCoord& t : uv) {
    EXPECT_GE(t[0], 0.0f);
    EXPECT_LT(t[0], 1.0f);
    EXPECT_GE(t[1], 0.0f);
    EXPECT_LE(t[1], 1.0f);
  }
  const UmbrellaLayout& L = g.umbrella;
  const int E = L.exumbrella_rings, J = L.disc_points;
  EXPECT_EQ(uv[L.vertex(0, 0)][1], 0.0f);          // exumbrellar apex
  EXPECT_EQ(uv[L.vertex(E, 3)][1], 1.0f);          // exumbrellar margin
  EXPECT_EQ(uv[L.vertex(E + 1, 3)][1], 1.0f);      // subumbrellar margin
  EXPECT_EQ(uv[L.vertex(L.rows - 1, 0)][1], 0.0f); // subumbrellar apex
  for (int j = 0; j < J; ++j) {
    for (int r = 1; r <= E; ++r) EXPECT_GT(uv[L.vertex(r, j)][1], uv[L.vertex(r - 1, r == 1 ? 0 : j)][1]);  // apex → margin
    for (int r = E + 2; r < L.rows; ++r)  // subumbrella, rim → apex: v falls
      EXPECT_LT(uv[L.vertex(r, r == L.rows - 1 ? 0 : j)][1], uv[L.vertex(r - 1, j)][1]);
    for (int r = 1; r + 1 < L.rows; ++r) EXPECT_FLOAT_EQ(uv[L.vertex(r, j)][0], static_cast<float>(j) / J);
  }
  // Tubes: ring m of tentacle t, side s at u = s / sides, v = m / (samples − 1).
  const std::size_t sides = 5, samples = g.tentacle_lines.front().size();
  std::size_t at = L.vertex_count();
  for (std::size_t t = 0; t < g.tentacle_lines.size(); ++t)
    for (std::size_t m = 0; m < samples; ++m)
      for (std::size_t s = 0; s < sides; ++s, ++at) {
        EXPECT_FLOAT_EQ(uv[at][0], static_cast<float>(s) / 5.0f);
        EXPECT_FLOAT_EQ(uv[at][1], static_cast<float>(m) / static_cast<float>(samples - 1));
      }
  EXPECT_EQ(at, uv.size());
}

TEST(TextureCoordinates, TheSeamIsSplitSoNoTriangleWraps) {
  const FrameGeometry g = small_bell();
  const std::vector<TexCoord> uv = texture_coordinates(g);
  const Mesh& m = g.mesh;
  const SeamSplit split = split_u_seam(uv, m.indices, 0, static_cast<std::uint32_t>(m.indices.size()));
  ASSERT_EQ(split.corners.size(), m.indices.size());
  // One duplicate per umbrella ring (its j = 0 vertex) and per tube ring (its side 0).
  const std::size_t rings = static_cast<std::size_t>(g.umbrella.rows - 2);
  const std::size_t tube_rings = g.tentacle_lines.size() * g.tentacle_lines.front().size();
  EXPECT_EQ(split.duplicated.size(), rings + tube_rings);
  ASSERT_EQ(split.uv.size(), uv.size() + split.duplicated.size());
  for (std::size_t d = 0; d < split.duplicated.size(); ++d) {
    EXPECT_EQ(uv[split.duplicated[d]][0], 0.0f);
    EXPECT_EQ(split.uv[uv.size() + d][0], 1.0f);
    EXPECT_EQ(split.uv[uv.size() + d][1], uv[split.duplicated[d]][1]);
  }
  float widest = 0.0f;
  for (std::size_t k = 0; k < m.indices.size(); k += 3) {
    const float a = split.uv[split.corners[k]][0], b = split.uv[split.corners[k + 1]][0], c = split.uv[split.corners[k + 2]][0];
    widest = std::max(widest, std::max({a, b, c}) - std::min({a, b, c}));
    for (int e = 0; e < 3; ++e) {  // a corner uses its own vertex or a duplicate of it
      const std::uint32_t entry = split.corners[k + static_cast<std::size_t>(e)];
      const std::uint32_t vertex = entry < uv.size() ? entry : split.duplicated[entry - uv.size()];
      EXPECT_EQ(vertex, m.indices[k + static_cast<std::size_t>(e)]);
    }
  }
  EXPECT_LE(widest, 0.5f);  // at the poles ½ (the pole sits at u = ½), elsewhere one column, 1/16 or 1/5
}

}  // namespace
}  // namespace jellysim::geometry
