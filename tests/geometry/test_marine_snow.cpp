// Marine snow (geometry/marine_snow.hpp): tracers revolved about the bell's axis into specks.
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/geometry/marine_snow.hpp"

namespace jellysim::geometry {
namespace {

TEST(MarineSnow, KeepsEachTracersHeightAndDistanceFromTheAxis) {
  const std::vector<Vec2> tracers{{0.10, 0.05}, {0.13, 0.07}, {0.20, 0.02}, {0.50, 0.05}};
  const std::array<Vec3, 2> box{Vec3{0.0, 0.0, -0.2}, Vec3{0.3, 0.3, 0.2}};
  const MarineSnow snow(tracers, 0.12, box, 0.001);
  EXPECT_EQ(snow.count(), 3u);  // the one at x = 0.5 m (0.38 m from the axis) is outside the box
  Mesh mesh;
  snow.append(tracers, mesh);
  ASSERT_EQ(mesh.positions.size(), 3u * 4u);
  ASSERT_EQ(mesh.parts.size(), 1u);
  EXPECT_EQ(mesh.parts[0].name, "snow");
  EXPECT_EQ(mesh.parts[0].index_count, 3u * 4u * 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    Vec3 centre{};
    for (std::size_t c = 0; c < 4; ++c) centre = centre + 0.25 * mesh.positions[4 * k + c];
    EXPECT_NEAR(centre.y, tracers[k].y, 1e-15);
    EXPECT_NEAR(std::hypot(centre.x - 0.12, centre.z), std::abs(tracers[k].x - 0.12), 1e-15);
    for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(norm(mesh.positions[4 * k + c] - centre), 0.001, 1e-15);
  }
  // Particles 0 and 1 sit at different angles (golden-angle steps), not in one plane.
  EXPECT_GT(std::abs(mesh.positions[0].z - mesh.positions[4].z), 1e-3);
  // Every face is counter-clockwise seen from outside: its normal points away from the speck's centre.
  for (std::size_t t = 0; t < 4; ++t) {
    const Vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
               c = mesh.positions[mesh.indices[3 * t + 2]];
    Vec3 centre{};
    for (std::size_t v = 0; v < 4; ++v) centre = centre + 0.25 * mesh.positions[v];
    EXPECT_GT(dot(cross(b - a, c - a), (1.0 / 3.0) * (a + b + c) - centre), 0.0);
  }
  EXPECT_THROW(snow.append({{0.1, 0.1}}, mesh), std::invalid_argument);  // fewer tracers than the first frame
}

TEST(MarineSnow, DensityKeepsThatFractionOfTheTracersEvenlySpread) {
  std::vector<Vec2> tracers;
  for (int i = 0; i < 1000; ++i) tracers.push_back({0.1 + 1e-4 * i, 0.05});
  const std::array<Vec3, 2> box{Vec3{0.0, 0.0, -0.5}, Vec3{0.5, 0.5, 0.5}};
  EXPECT_EQ(MarineSnow(tracers, 0.1, box, 0.001).count(), 1000u);
  EXPECT_EQ(MarineSnow(tracers, 0.1, box, 0.001, 0.25).count(), 250u);
  EXPECT_EQ(MarineSnow(tracers, 0.1, box, 0.001, 0.0).count(), 0u);
  Mesh quarter;
  MarineSnow(tracers, 0.1, box, 0.001, 0.25).append(tracers, quarter);
  // Every fourth tracer: the first kept is tracer 3, the last tracer 999.
  EXPECT_NEAR(std::hypot(quarter.positions[0].x + quarter.positions[1].x + quarter.positions[2].x + quarter.positions[3].x - 0.4,
                         quarter.positions[0].z + quarter.positions[1].z + quarter.positions[2].z + quarter.positions[3].z),
              4 * 3e-4, 1e-12);
  EXPECT_THROW(MarineSnow(tracers, 0.1, box, 0.001, 1.5), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::geometry
