// Mirror partners and the mirror-symmetric part of a spring body (elastic/mirror.hpp).
#include "jellysim/elastic/mirror.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace jellysim::elastic {
namespace {

// A "V" about x = 1: two arms of two points each and a vertex on the axis, with springs along the
// arms, a spring across and an angular spring at every joint.
Body v_shape() {
  Body b;
  b.add_point({0.0, 1.0}, 1.0);  // 0 left tip
  b.add_point({0.5, 0.5}, 1.0);  // 1 left middle
  b.add_point({1.0, 0.0}, 1.0);  // 2 vertex (on the axis)
  b.add_point({1.5, 0.5}, 1.0);  // 3 right middle
  b.add_point({2.0, 1.0}, 1.0);  // 4 right tip
  for (int k = 0; k < 4; ++k) b.add_linear_spring(k, k + 1, 10.0);
  b.add_linear_spring(4, 0, 5.0);  // across, stored the other way round
  b.add_angular_spring(0, 1, 2, 2.0, NAN);
  b.add_angular_spring(1, 2, 3, 3.0, NAN);
  b.add_angular_spring(2, 3, 4, 2.0, NAN);
  return b;
}

TEST(Mirror, FindsEveryPointsMirrorImage) {
  const Body b = v_shape();
  const std::vector<int> p = mirror_partners(b, 1.0, 1e-12);
  EXPECT_EQ(p, (std::vector<int>{4, 3, 2, 1, 0}));
  EXPECT_TRUE(springs_mirror_symmetric(b, p));
  EXPECT_TRUE(mirror_partners(b, 1.1, 1e-12).empty());  // the wrong axis
}

TEST(Mirror, RejectsBodiesThatAreNotMirrorImages) {
  Body moved = v_shape();
  moved.points.position[4].y += 1e-6;
  EXPECT_TRUE(mirror_partners(moved, 1.0, 1e-9).empty());
  EXPECT_FALSE(mirror_partners(moved, 1.0, 1e-5).empty());  // within a looser tolerance

  Body heavier = v_shape();
  heavier.points.mass[0] = 2.0;
  EXPECT_TRUE(mirror_partners(heavier, 1.0, 1e-12).empty());

  Body stiffer = v_shape();
  stiffer.linear.stiffness[0] = 11.0;
  EXPECT_FALSE(springs_mirror_symmetric(stiffer, mirror_partners(stiffer, 1.0, 1e-12)));

  Body bent = v_shape();
  bent.angular.rest_angle[2] += 0.1;  // one side bends more
  EXPECT_FALSE(springs_mirror_symmetric(bent, mirror_partners(bent, 1.0, 1e-12)));
}

TEST(Mirror, KeepsTheSymmetricPartOfPositionsAndVelocities) {
  Body b = v_shape();
  const std::vector<int> p = mirror_partners(b, 1.0, 1e-12);
  b.points.position[0] += Vec2{0.02, 0.04};
  b.points.position[2].x += 0.01;
  b.points.velocity[1] = {1.0, 2.0};
  b.points.velocity[3] = {1.0, 0.0};
  keep_mirror_symmetric_part(b, p, 1.0);
  EXPECT_NEAR(b.points.position[0].x, 0.01, 1e-15);
  EXPECT_NEAR(b.points.position[0].y, 1.02, 1e-15);
  EXPECT_NEAR(b.points.position[4].x, 1.99, 1e-15);
  EXPECT_NEAR(b.points.position[4].y, 1.02, 1e-15);
  EXPECT_DOUBLE_EQ(b.points.position[2].x, 1.0);  // back on the axis
  EXPECT_EQ(b.points.velocity[1], (Vec2{0.0, 1.0}));
  EXPECT_EQ(b.points.velocity[3], (Vec2{0.0, 1.0}));
  EXPECT_FALSE(mirror_partners(b, 1.0, 1e-12).empty());
}

TEST(Mirror, LeavesPinnedPointsAlone) {
  Body b;
  b.add_point({0.2, 0.0}, 0.0, PointKind::Pinned);
  b.add_point({1.8, 0.0}, 0.0, PointKind::Pinned);
  const std::vector<int> p = mirror_partners(b, 1.0, 1e-12);
  ASSERT_EQ(p, (std::vector<int>{1, 0}));
  b.points.position[0].x = 0.3;
  keep_mirror_symmetric_part(b, p, 1.0);
  EXPECT_EQ(b.points.position[0].x, 0.3);
}

}  // namespace
}  // namespace jellysim::elastic
