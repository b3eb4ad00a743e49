#pragma once
// Shared helpers for the elastic tests: seeded random configurations and finite differences.
#include "jellysim/elastic/body.hpp"
#include "jellysim/math/vec2.hpp"

#include <gtest/gtest.h>

#include <random>

namespace jellysim::elastic::test {

class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }
  Vec2 point(double half_width = 1.0) { return {uniform(-half_width, half_width), uniform(-half_width, half_width)}; }

 private:
  std::mt19937 engine_;
};

/// Step for central differences: error O(h²) from truncation plus O(ε/h) from rounding.
inline constexpr double fd_step = 1e-6;

inline void expect_vec_near(Vec2 actual, Vec2 expected, double tol) {
  EXPECT_NEAR(actual.x, expected.x, tol);
  EXPECT_NEAR(actual.y, expected.y, tol);
}

inline void expect_mat_near(const Mat2& actual, const Mat2& expected, double tol) {
  EXPECT_NEAR(actual.xx, expected.xx, tol);
  EXPECT_NEAR(actual.xy, expected.xy, tol);
  EXPECT_NEAR(actual.yx, expected.yx, tol);
  EXPECT_NEAR(actual.yy, expected.yy, tol);
}

/// Central-difference Jacobian of a Vec2-valued function of one point: column c = ∂f/∂x_c.
template <typename F>
Mat2 fd_jacobian(F&& f, Vec2 x) {
  const Vec2 dx{fd_step, 0.0}, dy{0.0, fd_step};
  const Vec2 cx = (f(x + dx) - f(x - dx)) / (2.0 * fd_step);
  const Vec2 cy = (f(x + dy) - f(x - dy)) / (2.0 * fd_step);
  return {cx.x, cy.x, cx.y, cy.y};
}

/// Central-difference gradient of a scalar function of one point.
template <typename F>
Vec2 fd_gradient(F&& f, Vec2 x) {
  const Vec2 dx{fd_step, 0.0}, dy{0.0, fd_step};
  return {(f(x + dx) - f(x - dx)) / (2.0 * fd_step), (f(x + dy) - f(x - dy)) / (2.0 * fd_step)};
}

/// A small body with springs away from rest: points 0..5 free, 6 pinned, a chain of linear
/// springs with cross braces, angular springs along the chain, gravity, no drag.
inline Body make_test_body(Random& rng) {
  Body body;
  body.gravity = {0.3, -9.8};
  for (int p = 0; p < 6; ++p) {
    body.add_point({0.5 * p + rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)}, rng.uniform(0.5, 2.0),
                   PointKind::Free, rng.point());
  }
  const int pinned = body.add_point({1.0, 0.8}, 1.0, PointKind::Pinned);
  for (int p = 0; p + 1 < 6; ++p) body.add_linear_spring(p, p + 1, rng.uniform(1, 20), rng.uniform(0.3, 0.7));
  for (int p = 0; p + 2 < 6; ++p) body.add_linear_spring(p, p + 2, rng.uniform(1, 20), rng.uniform(0.8, 1.2));
  body.add_linear_spring(2, pinned, 7.0, 0.5);
  for (int p = 0; p + 2 < 6; ++p) {
    body.add_angular_spring(p, p + 1, p + 2, rng.uniform(0.5, 3), rng.uniform(-0.5, 0.5));
  }
  return body;
}

}  // namespace jellysim::elastic::test
