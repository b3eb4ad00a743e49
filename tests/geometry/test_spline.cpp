// The C1 cubic of eq. 7.8 and Catmull–Rom; the 2D rendering model of §7.2.
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/geometry/rendering_model.hpp"
#include "jellysim/geometry/spline.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {
namespace {

const std::vector<Vec2> kPoints = {{0.0, 0.0}, {1.0, 0.5}, {1.5, 2.0}, {3.0, 2.2}, {3.5, 0.7}, {5.0, 1.0}};

TEST(Spline, ThesisCubicIsHermiteWithCentralDifferenceTangents) {
  const Vec2 a{0, 0}, b{1, 2}, c{3, 1}, d{4, 4};
  const CubicPiece q = cubic_piece(a, b, c, d, Interpolant::thesis_cubic);
  EXPECT_EQ(q.at(0.0), b);
  EXPECT_NEAR(q.at(1.0).x, c.x, 1e-15);
  EXPECT_NEAR(q.at(1.0).y, c.y, 1e-15);
  EXPECT_NEAR(q.derivative(0.0).x, (c - a).x, 1e-15);  // Q'(0) = x_{i+1} − x_{i−1}
  EXPECT_NEAR(q.derivative(1.0).y, (d - b).y, 1e-15);  // Q'(1) = x_{i+2} − x_i
  const CubicPiece cr = cubic_piece(a, b, c, d, Interpolant::catmull_rom);
  EXPECT_NEAR(cr.derivative(0.0).x, 0.5 * (c - a).x, 1e-15);
  EXPECT_NEAR(cr.derivative(1.0).y, 0.5 * (d - b).y, 1e-15);
}

class CurveTest : public ::testing::TestWithParam<Interpolant> {};

TEST_P(CurveTest, PassesThroughControlPoints) {
  for (std::size_t i = 0; i < kPoints.size(); ++i) {
    const Vec2 p = curve_point(kPoints, static_cast<double>(i), GetParam());
    EXPECT_NEAR(p.x, kPoints[i].x, 1e-14);
    EXPECT_NEAR(p.y, kPoints[i].y, 1e-14);
  }
}

TEST_P(CurveTest, IsC1AcrossPieces) {
  // One-sided difference quotients at each interior knot agree to O(h).
  const double h = 1e-6;
  for (std::size_t i = 1; i + 1 < kPoints.size(); ++i) {
    const double u = static_cast<double>(i);
    const Vec2 left = (curve_point(kPoints, u, GetParam()) - curve_point(kPoints, u - h, GetParam())) / h;
    const Vec2 right = (curve_point(kPoints, u + h, GetParam()) - curve_point(kPoints, u, GetParam())) / h;
    EXPECT_NEAR(left.x, right.x, 1e-4) << "knot " << i;
    EXPECT_NEAR(left.y, right.y, 1e-4) << "knot " << i;
  }
}

TEST_P(CurveTest, ResamplingKeepsEndsAndMirrorSymmetry) {
  std::vector<Vec2> mirrored(kPoints.rbegin(), kPoints.rend());
  const auto a = resample_open_curve(kPoints, 41, GetParam());
  const auto b = resample_open_curve(mirrored, 41, GetParam());
  ASSERT_EQ(a.size(), 41u);
  EXPECT_EQ(a.front(), kPoints.front());
  EXPECT_EQ(a.back(), kPoints.back());
  EXPECT_EQ(a[8], kPoints[1]);  // u = 5·8/40 = 1 exactly
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(a[k].x, b[a.size() - 1 - k].x, 1e-14);
    EXPECT_NEAR(a[k].y, b[a.size() - 1 - k].y, 1e-14);
  }
}

INSTANTIATE_TEST_SUITE_P(BothInterpolants, CurveTest,
                         ::testing::Values(Interpolant::thesis_cubic, Interpolant::catmull_rom));

TEST(RenderingModel, ExumbrellaPointsAwayFromTheCavityWhateverTheOrdering) {
  const jellyfish::SliceFrame bell = synthetic_bell(0.04, 0.028, 0.0, 21, 0);
  std::vector<Vec2> reversed(bell.umbrella.rbegin(), bell.umbrella.rend());
  const std::vector<Vec2>* orderings[] = {&bell.umbrella, &reversed};
  for (const std::vector<Vec2>* umbrella : orderings) {
    const auto ex = exumbrellar_points(*umbrella, bell.axis, bell.thickness_m);
    const std::size_t apex = umbrella->size() / 2;
    EXPECT_NEAR(ex[apex].y - (*umbrella)[apex].y, bell.thickness_m, 1e-12);  // apex: straight up
    for (std::size_t i = 0; i < ex.size(); ++i) {
      EXPECT_NEAR(norm(ex[i] - (*umbrella)[i]), bell.thickness_m, 1e-12);
      // The hemi-ellipse is convex: the exumbrella lies farther from the aperture centre.
      EXPECT_GT(norm(ex[i]), norm((*umbrella)[i]));
    }
  }
}

TEST(RenderingModel, HullAndResampledSurfaces) {
  const jellyfish::SliceFrame bell = synthetic_bell(0.04, 0.028, 0.5, 11, 6);
  const auto ex = exumbrellar_points(bell.umbrella, bell.axis, bell.thickness_m);
  const auto hull = closed_hull(bell.umbrella, ex);
  ASSERT_EQ(hull.size(), 22u);
  EXPECT_EQ(hull[10], bell.umbrella[10]);
  EXPECT_EQ(hull[11], ex[10]);
  EXPECT_EQ(hull[21], ex[0]);
  const RenderingSlice slice = make_rendering_slice(bell, 41, 9, Interpolant::catmull_rom);
  ASSERT_EQ(slice.subumbrella.size(), 41u);
  ASSERT_EQ(slice.exumbrella.size(), 41u);
  ASSERT_EQ(slice.tentacles.size(), 2u);
  EXPECT_EQ(slice.tentacles[0].size(), 9u);
  EXPECT_EQ(slice.subumbrella[20], bell.umbrella[5]);  // apex kept exactly
  for (std::size_t k = 0; k < 41; ++k) {  // symmetric slice: opposing samples mirror each other
    EXPECT_NEAR(slice.subumbrella[k].x, -slice.subumbrella[40 - k].x, 1e-15);
    EXPECT_NEAR(slice.subumbrella[k].y, slice.subumbrella[40 - k].y, 1e-15);
  }
}

TEST(RenderingModel, BadSlicesAreInputErrors) {
  jellyfish::SliceFrame bell = synthetic_bell(0.04, 0.028, 0.0, 11, 6);
  auto even = bell;
  even.umbrella.pop_back();
  EXPECT_THROW(validate_slice(even), InputError);
  auto thin = bell;
  thin.thickness_m = 0.0;
  EXPECT_THROW(validate_slice(thin), InputError);
  auto nan = bell;
  nan.umbrella[3].x = std::nan("");
  EXPECT_THROW(validate_slice(nan), InputError);
  auto muscle = bell;
  muscle.muscles[0].b = 99;
  EXPECT_THROW(validate_slice(muscle), InputError);
  EXPECT_THROW(make_rendering_slice(bell, 40, 9, Interpolant::catmull_rom), InputError);
  EXPECT_THROW(parse_interpolant("bezier", "render.interpolant"), InputError);
  EXPECT_THROW(synthetic_bell(0.04, 0.028, 1.5, 11, 6), InputError);
}

}  // namespace
}  // namespace jellysim::geometry
