// The sort-and-sweep crossing test (jellyfish/segment_sweep.hpp) gives the exact pairwise answer:
// against the quadratic loop it replaced, on random polygons and polylines (crossing or not), and
// in the three checks built on it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/jellyfish/obstacle.hpp"
#include "jellysim/jellyfish/segment_sweep.hpp"

namespace jellysim::jellyfish {
namespace {

bool proper_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

/// Random closed polygons: a star (radius jittered around a circle, never crossing) or points
/// thrown anywhere (mostly crossing), some vertices snapped to a coarse lattice so that collinear
/// and touching edges occur.
std::vector<Vec2> random_polygon(std::mt19937& rng, int n, bool star) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) {
    Vec2 v = star ? Vec2{0.5, 0.5} + (0.2 + 0.25 * u(rng)) * Vec2{std::cos(2 * std::numbers::pi * k / n),
                                                                    std::sin(2 * std::numbers::pi * k / n)}
                  : Vec2{u(rng), u(rng)};
    if (!star && u(rng) < 0.3) v = {std::round(v.x * 4) / 4, std::round(v.y * 4) / 4};
    p.push_back(v);
  }
  return p;
}

bool brute_polygon_self_intersects(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j)
      if (!(i == 0 && j + 1 == n) && proper_cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return true;
  return false;
}

bool brute_polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (proper_cross(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
  return point_in_polygon(a.front(), b) || point_in_polygon(b.front(), a);
}

bool brute_polyline_self_intersects(const std::vector<Vec2>& p) {
  for (std::size_t i = 0; i + 1 < p.size(); ++i)
    for (std::size_t j = i + 2; j + 1 < p.size(); ++j) {
      const Vec2 a = p[i], b = p[i + 1], c = p[j], d = p[j + 1];
      const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
      const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0) return true;
    }
  return false;
}

bool polygon_rejected(const std::vector<Vec2>& p) {
  ObstacleSpec s;
  s.name = "test";
  s.shape = ObstacleShape::polygon;
  s.vertices_m = p;
  try {
    validate(s);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what()).find("self-intersecting") != std::string::npos;
  }
  return false;
}

TEST(SegmentSweep, AgreesWithThePairwiseLoopOnRandomShapes) {
  std::mt19937 rng(7);
  int crossing = 0, cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 3 + trial % 40;
    const bool star = trial % 3 == 0;
    const std::vector<Vec2> p = random_polygon(rng, n, star), q = random_polygon(rng, 3 + trial % 7, trial % 2 == 0);
    const bool self = brute_polygon_self_intersects(p);
    crossing += self;
    ++cases;
    ASSERT_EQ(polygon_rejected(p), self) << "trial " << trial;
    ASSERT_EQ(polygons_overlap(p, q), brute_polygons_overlap(p, q)) << "trial " << trial;
    ASSERT_EQ(polyline_self_intersects(p), brute_polyline_self_intersects(p)) << "trial " << trial;
  }
  // Both answers occur often enough for the comparison to mean something.
  EXPECT_GT(crossing, cases / 5);
  EXPECT_LT(crossing, cases - cases / 5);
}

// A 50,000-vertex outline (the case that took 14 s): the answer is right both ways.
TEST(SegmentSweep, LargeOutlines) {
  std::vector<Vec2> p;
  const int n = 50000;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n, r = 0.1 + 0.01 * std::sin(37 * a);
    p.push_back({0.5 + r * std::cos(a), 0.5 + r * std::sin(a)});
  }
  EXPECT_FALSE(polygon_rejected(p));
  std::swap(p[100], p[30000]);  // two long edges across the outline
  EXPECT_TRUE(polygon_rejected(p));
}

}  // namespace
}  // namespace jellysim::jellyfish
