// MAC grid geometry, staggering, world↔grid conversion and bilinear sampling.
#include <gtest/gtest.h>

#include <limits>

#include <cmath>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {
namespace {

TEST(MacGrid, WorldAndGridCoordinatesAreInverse) {
  const MacGrid g(8, 4, 2.0, 0.5, {-1.0, 3.0});
  EXPECT_DOUBLE_EQ(g.dx(), 0.25);
  EXPECT_DOUBLE_EQ(g.dy(), 0.125);
  const Vec2 w = g.world_from_grid(2.5, 1.0);
  EXPECT_DOUBLE_EQ(w.x, -1.0 + 2.5 * 0.25);
  EXPECT_DOUBLE_EQ(w.y, 3.0 + 0.125);
  const Vec2 back = g.grid_from_world(w);
  EXPECT_DOUBLE_EQ(back.x, 2.5);
  EXPECT_DOUBLE_EQ(back.y, 1.0);
}

TEST(Field, KnowsItsStaggering) {
  const MacGrid g(4, 3, 4.0, 3.0);
  const Field p(g, kCellCentres), u(g, kXFaces), v(g, kYFaces), w(g, kNodes);
  EXPECT_EQ(p.count_x(), 4);
  EXPECT_EQ(u.count_x(), 5);
  EXPECT_EQ(u.count_y(), 3);
  EXPECT_EQ(v.count_y(), 4);
  EXPECT_EQ(w.count_x(), 5);
  EXPECT_DOUBLE_EQ(p.position(0, 0).x, 0.5);
  EXPECT_DOUBLE_EQ(u.position(0, 0).x, 0.0);
  EXPECT_DOUBLE_EQ(u.position(0, 0).y, 0.5);
  EXPECT_DOUBLE_EQ(v.position(2, 3).x, 2.5);
  EXPECT_DOUBLE_EQ(v.position(2, 3).y, 3.0);
  EXPECT_DOUBLE_EQ(u.position(-1, -1).x, -1.0);  // ghosts lie outside the domain
}

TEST(Field, BilinearSamplingIsExactForLinearFunctions) {
  const MacGrid g(5, 7, 1.0, 2.0, {0.3, -0.2});
  for (Staggering s : {kCellCentres, kXFaces, kYFaces, kNodes}) {
    Field f(g, s);
    auto linear = [](Vec2 p) { return 2.0 + 3.0 * p.x - 1.5 * p.y; };
    for (int j = -1; j <= f.count_y(); ++j)
      for (int i = -1; i <= f.count_x(); ++i) f(i, j) = linear(f.position(i, j));
    for (Vec2 p : {Vec2{0.31, -0.19}, Vec2{0.77, 1.1}, Vec2{1.3, 1.8}, Vec2{0.5, 0.5}})
      EXPECT_NEAR(f.sample(p), linear(p), 1e-12);
  }
}

// The largest |value| over the interior: ghosts ignored, every position in a row counts (rows of
// 7 and 8 u-faces test the unrolled part and the remainder), and NaN anywhere is reported.
TEST(Field, SamplingAtANaNPositionStaysInsideTheField) {
  // A diverged run once sampled at NaN: the index became INT_MIN and the read left the field.
  const MacGrid g(6, 4, 1.2, 0.8);
  Field f(g, kXFaces, 3.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(f.sample({nan, 0.3}), 3.0);
  EXPECT_DOUBLE_EQ(f.sample({0.3, nan}), 3.0);
  EXPECT_DOUBLE_EQ(f.sample({std::numeric_limits<double>::infinity(), -1e300}), 3.0);
}

TEST(Field, MaxAbsInteriorSeesEverySampleAndNaN) {
  for (int nx : {6, 7}) {
    Field u(MacGrid(nx, 3, 1.0, 1.0), kXFaces);
    EXPECT_EQ(u.max_abs_interior(), 0.0);
    u(-1, 1) = 100.0;  // a ghost
    EXPECT_EQ(u.max_abs_interior(), 0.0);
    for (int j = 0; j < u.count_y(); ++j)
      for (int i = 0; i < u.count_x(); ++i) {
        Field f = u;
        f(i, j) = -2.5;
        ASSERT_EQ(f.max_abs_interior(), 2.5) << i << ", " << j;
        f(i, j) = std::nan("");
        ASSERT_TRUE(std::isnan(f.max_abs_interior())) << i << ", " << j;
      }
  }
}

TEST(Boundaries, NoSlipGhostsPutTheWallVelocityOnTheWall) {
  const MacGrid g(4, 4, 1.0, 1.0);
  Velocity vel(g);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i <= 4; ++i) vel.u(i, j) = 0.3 + 0.1 * i - 0.05 * j;
  const Boundaries b = Boundaries::lid_driven_cavity(1.0);
  apply_velocity_boundaries(vel, b);
  for (int i = 1; i < 4; ++i) {
    EXPECT_NEAR(0.5 * (vel.u(i, 3) + vel.u(i, 4)), 1.0, 1e-15);   // lid
    EXPECT_NEAR(0.5 * (vel.u(i, -1) + vel.u(i, 0)), 0.0, 1e-15);  // bottom wall
    EXPECT_NEAR(vel.u.sample({vel.u.position(i, 0).x, 1.0}), 1.0, 1e-12);
  }
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(vel.u(0, j), 0.0);
    EXPECT_EQ(vel.u(4, j), 0.0);
  }
}

TEST(Boundaries, ParseAndPrintRoundTrip) {
  for (BoundaryType t : {BoundaryType::no_slip, BoundaryType::free_slip, BoundaryType::outflow,
                         BoundaryType::inflow, BoundaryType::periodic})
    EXPECT_EQ(boundary_type_from_string(to_string(t)), t);
  EXPECT_FALSE(boundary_type_from_string("sticky").has_value());
  Boundaries b = Boundaries::all(BoundaryType::no_slip);
  b.west.type = BoundaryType::periodic;
  EXPECT_THROW(b.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::fluid
