// The swinging bar of thesis Figure 8.1.
#include "jellysim/elastic/bar.hpp"
#include "elastic_test_util.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <stdexcept>
#include <string>

namespace jellysim::elastic {
namespace {

std::string error_of(const BarSpec& spec) {
  try {
    make_bar(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Bar, DefaultsMatchFigure8_1) {
  const Body bar = make_bar({});
  EXPECT_EQ(bar.points.size(), 22u);
  EXPECT_EQ(bar.linear.size(), 11u + 4u * 10u);  // rungs + (2 rows + 2 diagonals) per cell
  EXPECT_EQ(bar.angular.size(), 0u);
  EXPECT_EQ(bar.gravity, (Vec2{0, -0.05}));
  EXPECT_EQ(bar.points.kind[0], PointKind::Pinned);
  EXPECT_EQ(bar.points.position[0], (Vec2{0, 0}));
  for (std::size_t p = 1; p < bar.points.size(); ++p) {
    EXPECT_EQ(bar.points.kind[p], PointKind::Free);
    EXPECT_EQ(bar.points.mass[p], 24.0);
  }
  test::expect_vec_near(bar.points.position[10], {0.45, 0}, 1e-15);   // top-right corner
  test::expect_vec_near(bar.points.position[11], {0, -0.045}, 1e-15);  // bottom-left corner
}

TEST(Bar, RotatedBarStartsAtRestWithAngularSprings) {
  BarSpec spec;
  spec.angle_rad = -std::numbers::pi / 3;
  spec.pivot = {0.2, 0.7};
  spec.angular_stiffness = 0.5;
  spec.segments = 7;
  const Body bar = make_bar(spec);
  EXPECT_EQ(bar.points.size(), 16u);
  EXPECT_EQ(bar.angular.size(), 12u);
  EXPECT_EQ(bar.points.position[0], spec.pivot);
  test::expect_vec_near(bar.points.position[7] - spec.pivot,
                        0.45 * Vec2{std::cos(spec.angle_rad), std::sin(spec.angle_rad)}, 1e-15);
  EXPECT_NEAR(energy(bar).elastic, 0.0, 1e-25);
  Body weightless = bar;
  weightless.gravity = {};
  std::vector<Vec2> force;
  accumulate_forces(weightless, bar.points.position, bar.points.velocity, 0.0, force);
  for (const Vec2& f : force) test::expect_vec_near(f, {}, 1e-12);
}

TEST(Bar, InvalidSpecNamesTheField) {
  BarSpec spec;
  spec.segments = 0;
  EXPECT_EQ(error_of(spec), "bar.segments = 0 is out of range [1, 10000]");
  spec = {};
  spec.length = -1;
  EXPECT_EQ(error_of(spec), "bar.length = -1 is out of range (0, inf)");
  spec = {};
  spec.width = 0;
  EXPECT_NE(error_of(spec).find("bar.width"), std::string::npos);
  spec = {};
  spec.point_mass = 0;
  EXPECT_NE(error_of(spec).find("bar.point_mass"), std::string::npos);
  spec = {};
  spec.angular_stiffness = -1;
  EXPECT_NE(error_of(spec).find("bar.angular_stiffness"), std::string::npos);
  spec = {};
  spec.segments = 10001;
  EXPECT_NE(error_of(spec).find("bar.segments"), std::string::npos);
}

}  // namespace
}  // namespace jellysim::elastic
