// Obstacles in 3D: polygon triangulation (ear clipping) and the extruded prisms of the animation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "jellysim/geometry/obstacle_mesh.hpp"

namespace jellysim::geometry {
namespace {

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += 0.5 * cross(p[i], p[(i + 1) % p.size()]);
  return a;
}

double triangle_area(Vec2 a, Vec2 b, Vec2 c) { return 0.5 * cross(b - a, c - a); }

bool inside(Vec2 q, const std::vector<Vec2>& p) {  // even–odd rule
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < p[j].x + (q.y - p[j].y) * (p[i].x - p[j].x) / (p[i].y - p[j].y))
      in = !in;
  return in;
}

// A triangulation covers the polygon exactly when its counter-clockwise triangles lie inside it
// and their areas add up to the polygon's.
void expect_triangulates(const std::vector<Vec2>& p, const std::vector<std::uint32_t>& t) {
  ASSERT_EQ(t.size() % 3, 0u);
  double sum = 0.0;
  for (std::size_t k = 0; k < t.size(); k += 3) {
    const Vec2 a = p[t[k]], b = p[t[k + 1]], c = p[t[k + 2]];
    const double area = triangle_area(a, b, c);
    EXPECT_GT(area, 0.0) << "triangle " << k / 3;
    EXPECT_TRUE(inside((a + b + c) / 3.0, p)) << "triangle " << k / 3;
    sum += area;
  }
  EXPECT_NEAR(sum, polygon_area(p), 1e-12 * std::abs(polygon_area(p)) + 1e-15);
}

TEST(Triangulation, ConcaveLShapeGivesNMinusTwoTriangles) {
  const std::vector<Vec2> l{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto t = triangulate_polygon(l);
  EXPECT_EQ(t.size(), 3u * 4u);
  expect_triangulates(l, t);
}

TEST(Triangulation, StarWithManyReflexVerticesIsCoveredExactly) {
  std::vector<Vec2> star;
  for (int k = 0; k < 40; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 40, r = k % 2 == 0 ? 1.0 : 0.35 + 0.1 * std::sin(3.0 * k);
    star.push_back({r * std::cos(a), r * std::sin(a)});
  }
  const auto t = triangulate_polygon(star);
  EXPECT_EQ(t.size(), 3u * 38u);
  expect_triangulates(star, t);
}

// A box resampled into markers has runs of collinear points: they get no zero-area triangles.
TEST(Triangulation, CollinearMarkersOnStraightEdgesAddNoSlivers) {
  std::vector<Vec2> box;
  const Vec2 corners[4] = {{0, 0}, {0.08, 0}, {0.08, 0.03}, {0, 0.03}};
  for (int c = 0; c < 4; ++c)
    for (int s = 0; s < 5; ++s) box.push_back(corners[c] + (s / 5.0) * (corners[(c + 1) % 4] - corners[c]));
  const auto t = triangulate_polygon(box);
  expect_triangulates(box, t);
}

TEST(Triangulation, RejectsClockwiseDegenerateAndCrossingPolygons) {
  EXPECT_THROW(triangulate_polygon({{0, 0}, {1, 0}}), std::invalid_argument);
  EXPECT_THROW(triangulate_polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}}), std::invalid_argument);  // clockwise
  EXPECT_THROW(triangulate_polygon({{0, 0}, {1, 0}, {2, 0}}), std::invalid_argument);          // no area
  // Counter-clockwise on balance (area 1.5), but edges 0 and 2 cross: ear clipping alone would
  // return one triangle of it.
  EXPECT_THROW(triangulate_polygon({{0, 2}, {3, 0}, {3, 3}, {0, 0}}), std::invalid_argument);
  // A vertex touching a non-adjacent edge.
  EXPECT_THROW(triangulate_polygon({{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}), std::invalid_argument);
}

// Volume of a closed mesh by the divergence theorem: positive when every face points outward.
double enclosed_volume(const Mesh& m) {
  double v = 0.0;
  for (std::size_t k = 0; k < m.indices.size(); k += 3)
    v += dot(m.positions[m.indices[k]], cross(m.positions[m.indices[k + 1]], m.positions[m.indices[k + 2]])) / 6.0;
  return v;
}

TEST(ObstaclePrisms, PrismEnclosesOutlineAreaTimesDepthInEitherOrientation) {
  const std::vector<Vec2> l{{0.1, 0.1}, {0.3, 0.1}, {0.3, 0.2}, {0.2, 0.2}, {0.2, 0.3}, {0.1, 0.3}};
  std::vector<Vec2> reversed = l;
  std::reverse(reversed.begin(), reversed.end());
  for (const auto& outline : {l, reversed}) {
    const ObstaclePrisms prisms({outline}, 0.05);
    Mesh mesh;
    prisms.append({outline}, mesh);
    ASSERT_NE(mesh.part("obstacles"), nullptr);
    EXPECT_EQ(mesh.vertex_count(), 6u * l.size());
    EXPECT_EQ(mesh.triangle_count(), 2u * l.size() + 2u * (l.size() - 2));
    EXPECT_NEAR(enclosed_volume(mesh), polygon_area(l) * 0.05, 1e-12);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      EXPECT_NEAR(norm(mesh.normals[v]), 1.0, 1e-12);
      EXPECT_NEAR(std::abs(mesh.positions[v].z), 0.025, 1e-15);
    }
  }
}

// Every face's normal points away from the solid: each triangle's vertex normals agree with its
// winding (counter-clockwise seen from outside).
TEST(ObstaclePrisms, VertexNormalsAgreeWithTheOutwardWinding) {
  std::vector<Vec2> circle;
  for (int k = 0; k < 28; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 28;
    circle.push_back({0.4 + 0.03 * std::cos(a), 0.5 + 0.03 * std::sin(a)});
  }
  const std::vector<Vec2> box{{0.55, 0.43}, {0.63, 0.43}, {0.63, 0.46}, {0.55, 0.46}};
  const ObstaclePrisms prisms({circle, box}, 0.1);
  Mesh mesh;
  prisms.append({circle, box}, mesh);
  for (std::size_t k = 0; k < mesh.indices.size(); k += 3) {
    const Vec3 a = mesh.positions[mesh.indices[k]], b = mesh.positions[mesh.indices[k + 1]],
               c = mesh.positions[mesh.indices[k + 2]];
    const Vec3 face = normalized(cross(b - a, c - a));
    for (int corner = 0; corner < 3; ++corner) EXPECT_GT(dot(face, mesh.normals[mesh.indices[k + corner]]), 0.7);
  }
  // The circle's walls are smooth: the two quads meeting at a marker share its normal. The box's
  // walls meet at a sharp edge: their normals there are perpendicular.
  EXPECT_NEAR(norm(mesh.normals[1] - mesh.normals[4]), 0.0, 1e-12);  // marker 1 from walls 0 and 1
  const std::size_t box_base = 6 * circle.size();
  EXPECT_NEAR(dot(mesh.normals[box_base + 1], mesh.normals[box_base + 4]), 0.0, 1e-12);
}

TEST(ObstaclePrisms, MovedOutlinesKeepTheTopologyAndCountsAreChecked) {
  const std::vector<Vec2> box{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const ObstaclePrisms prisms({box}, 1.0);
  Mesh first, moved;
  prisms.append({box}, first);
  std::vector<Vec2> shifted = box;
  for (Vec2& p : shifted) p += Vec2{0.2, -0.1};
  prisms.append({shifted}, moved);
  EXPECT_TRUE(same_topology(first, moved));
  EXPECT_NEAR(moved.positions[0].x - first.positions[0].x, 0.2, 1e-15);
  EXPECT_THROW(prisms.append({}, moved), std::invalid_argument);
  EXPECT_THROW(prisms.append({{{0, 0}, {1, 0}, {1, 1}}}, moved), std::invalid_argument);
  EXPECT_THROW(ObstaclePrisms({box}, 0.0), std::invalid_argument);
  EXPECT_THROW(ObstaclePrisms({{{0, 0}, {1, 0}}}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::geometry
