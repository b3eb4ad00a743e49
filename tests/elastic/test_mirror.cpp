// Mirror partners and the mirror-symmetric part of a spring body (elastic/body_mirror.hpp).
#include "jellysim/elastic/body_mirror.hpp"

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

// The "V" with IB2d's laws in mirror-image pairs: torsional beams stored in the same order on both
// sides (image curvature −C) and in reversed order (image C), non-invariant beams with curvature
// (−C_x, C_y), power springs and dashpots.
Body v_shape_with_ib2d_laws() {
  Body b = v_shape();
  b.add_torsional_beam(0, 1, 2, 2.0, 0.2);
  b.add_torsional_beam(4, 3, 2, 2.0, -0.2);     // the same order on the right: −C
  b.add_torsional_beam(0, 1, 3, 1.0, 0.3);
  b.add_torsional_beam(1, 3, 4, 1.0, 0.3);      // the image (4, 3, 1; −0.3) walked from the other end
  b.add_torsional_beam(1, 2, 3, 4.0, NAN);      // its own image
  b.add_non_invariant_beam(0, 1, 2, 3.0, {0.1, 0.2});
  b.add_non_invariant_beam(2, 3, 4, 3.0, {-0.1, 0.2});  // the image with the ends swapped
  b.add_non_invariant_beam(1, 2, 3, 1.0, {NAN, NAN});   // C = (0, 1): its own image
  b.add_power_spring(0, 1, 5.0, 0.6, 2.5);
  b.add_power_spring(3, 4, 5.0, 0.6, 2.5);
  b.add_dashpot(1, 2, 0.5);
  b.add_dashpot(3, 2, 0.5);
  b.add_dashpot(4, 0, 0.2);
  return b;
}

TEST(Mirror, ChecksIb2dLawsForMirrorImages) {
  const Body b = v_shape_with_ib2d_laws();
  const std::vector<int> p = mirror_partners(b, 1.0, 1e-12);
  ASSERT_EQ(p, (std::vector<int>{4, 3, 2, 1, 0}));
  EXPECT_TRUE(springs_mirror_symmetric(b, p));

  Body torsion = v_shape_with_ib2d_laws();
  torsion.torsional.curvature[1] *= -1.0;  // the same C on both sides, same order: not an image
  EXPECT_FALSE(springs_mirror_symmetric(torsion, p));
  // A beam centred on the axis is its own image walked the other way round, whatever its C.
  Body middle = v_shape_with_ib2d_laws();
  middle.torsional.curvature[4] += 0.1;
  EXPECT_TRUE(springs_mirror_symmetric(middle, p));
  Body unpaired = v_shape_with_ib2d_laws();
  unpaired.torsional.curvature[3] += 0.1;  // (1, 3, 4) no longer the image of (0, 1, 3)
  EXPECT_FALSE(springs_mirror_symmetric(unpaired, p));

  Body lopsided = v_shape_with_ib2d_laws();
  lopsided.non_invariant.curvature[1].x *= -1.0;  // C_x not negated
  EXPECT_FALSE(springs_mirror_symmetric(lopsided, p));
  Body tilted = v_shape_with_ib2d_laws();
  tilted.non_invariant.curvature[2].x = 0.05;  // a centred beam needs C_x = 0
  EXPECT_FALSE(springs_mirror_symmetric(tilted, p));

  Body degree = v_shape_with_ib2d_laws();
  degree.power.degree[0] = 3.0;
  EXPECT_FALSE(springs_mirror_symmetric(degree, p));

  Body damped = v_shape_with_ib2d_laws();
  damped.dashpots.coefficient[1] = 0.6;
  EXPECT_FALSE(springs_mirror_symmetric(damped, p));
  Body extra = v_shape_with_ib2d_laws();
  extra.add_dashpot(0, 1, 0.1);  // no image on 4-3
  EXPECT_FALSE(springs_mirror_symmetric(extra, p));
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
