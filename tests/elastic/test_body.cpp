// Body construction, energies and summed forces (thesis §2.1-2.3).
#include "jellysim/elastic/body.hpp"
#include "jellysim/elastic/forces.hpp"
#include "elastic_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace jellysim::elastic {
namespace {

using test::expect_vec_near;
using test::Random;

double potential_energy(const Body& body) {
  const Energy e = energy(body);
  return e.elastic + e.gravity;
}

TEST(Body, AddPointValidatesMass) {
  Body body;
  EXPECT_THROW(body.add_point({0, 0}, 0.0), std::invalid_argument);
  EXPECT_THROW(body.add_point({0, 0}, -1.0), std::invalid_argument);
  EXPECT_THROW(body.add_point({0, 0}, std::nan("")), std::invalid_argument);
  EXPECT_THROW(body.add_point({0, 0}, 1.0, PointKind::Prescribed), std::invalid_argument);
  EXPECT_EQ(body.add_point({0, 0}, 0.0, PointKind::Pinned), 0);  // a pinned point's mass is ignored
  EXPECT_EQ(body.add_point({1, 0}, 2.0, PointKind::Free, {3, 4}), 1);
  EXPECT_EQ(body.points.size(), 2u);
  EXPECT_EQ(body.points.velocity[1], (Vec2{3, 4}));
  EXPECT_EQ(body.points.motion[1], -1);
}

TEST(Body, AddSpringsValidateIndicesAndDefaultToRest) {
  Body body;
  body.add_point({0, 0}, 1.0);
  body.add_point({3, 4}, 1.0);
  body.add_point({3, 5}, 1.0);
  EXPECT_THROW(body.add_linear_spring(0, 3, 1.0), std::invalid_argument);
  EXPECT_THROW(body.add_linear_spring(-1, 1, 1.0), std::invalid_argument);
  EXPECT_THROW(body.add_linear_spring(1, 1, 1.0), std::invalid_argument);
  EXPECT_THROW(body.add_linear_spring(0, 1, -1.0), std::invalid_argument);
  EXPECT_THROW(body.add_angular_spring(0, 1, 1, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(body.add_angular_spring(0, 1, 7, 1.0, 0.0), std::invalid_argument);
  body.add_linear_spring(0, 1, 2.0);
  EXPECT_DOUBLE_EQ(body.linear.rest_length[0], 5.0);
  body.add_angular_spring(0, 1, 2, 1.0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_DOUBLE_EQ(body.angular.rest_angle[0], turning_angle({0, 0}, {3, 4}, {3, 5}));
  EXPECT_DOUBLE_EQ(energy(body).elastic, 0.0);
}

TEST(Body, PrescribedPointStartsOnItsMotion) {
  Body body;
  EXPECT_THROW(body.add_prescribed_point({}), std::invalid_argument);
  const int p = body.add_prescribed_point([](double t) {
    return PrescribedState{{std::cos(t), std::sin(t)}, {-std::sin(t), std::cos(t)}, {-std::cos(t), -std::sin(t)}};
  });
  EXPECT_EQ(body.points.kind[p], PointKind::Prescribed);
  EXPECT_EQ(body.points.motion[p], 0);
  EXPECT_EQ(body.points.position[p], (Vec2{1, 0}));
  EXPECT_EQ(body.points.velocity[p], (Vec2{0, 1}));
}

TEST(Body, EnergyComponents) {
  Body body;
  body.gravity = {0.0, -2.0};
  body.add_point({0, 1}, 3.0, PointKind::Free, {1, 1});
  body.add_point({2, 1}, 5.0, PointKind::Pinned);
  body.add_linear_spring(0, 1, 4.0, 1.5);
  const Energy e = energy(body);
  EXPECT_DOUBLE_EQ(e.kinetic, 0.5 * 3.0 * 2.0);
  EXPECT_DOUBLE_EQ(e.gravity, 3.0 * 2.0 * 1.0);  // -m g·x, free points only
  EXPECT_DOUBLE_EQ(e.elastic, 0.5 * 4.0 * 0.25);
  EXPECT_DOUBLE_EQ(e.total(), e.kinetic + e.gravity + e.elastic);
}

TEST(Body, ForcesAreMinusGradientOfPotentialEnergy) {
  Random rng(11);
  Body body = test::make_test_body(rng);
  std::vector<Vec2> force;
  accumulate_forces(body, body.points.position, std::vector<Vec2>(body.points.size()), 0.0, force);
  for (std::size_t p = 0; p < body.points.size(); ++p) {
    if (body.points.kind[p] != PointKind::Free) continue;
    const Vec2 x0 = body.points.position[p];
    const Vec2 grad = test::fd_gradient(
        [&](Vec2 x) {
          body.points.position[p] = x;
          return potential_energy(body);
        },
        x0);
    body.points.position[p] = x0;
    expect_vec_near(force[p], -grad, 1e-5 * (1.0 + norm(grad)));
  }
}

TEST(Body, SpringForcesConserveMomentumAndAngularMomentum) {
  Random rng(12);
  Body body = test::make_test_body(rng);
  body.gravity = {};
  std::vector<Vec2> force;
  accumulate_forces(body, body.points.position, body.points.velocity, 0.0, force);
  Vec2 total{};
  double torque = 0.0;
  for (std::size_t p = 0; p < body.points.size(); ++p) {
    total += force[p];
    torque += cross(body.points.position[p], force[p]);
  }
  expect_vec_near(total, {}, 1e-12);
  EXPECT_NEAR(torque, 0.0, 1e-12);
}

TEST(Body, DragUsesTheFluidVelocityHook) {
  Body body;
  body.drag_coefficient = 2.0;
  body.add_point({1, 2}, 1.0, PointKind::Free, {3, 0});
  std::vector<Vec2> force;
  accumulate_forces(body, body.points.position, body.points.velocity, 0.5, force);
  expect_vec_near(force[0], {-6, 0}, 0.0);  // still fluid
  body.fluid_velocity = [](Vec2 x, double t) { return Vec2{x.y * t, x.x}; };  // (1, 1) at x = (1, 2), t = ½
  accumulate_forces(body, body.points.position, body.points.velocity, 0.5, force);
  expect_vec_near(force[0], {-4, 2}, 0.0);
}

TEST(Body, GravityActsOnFreePointsOnly) {
  Body body;
  body.gravity = {0.0, -2.0};
  body.add_point({0, 0}, 3.0);
  body.add_point({1, 0}, 5.0, PointKind::Pinned);
  std::vector<Vec2> force;
  accumulate_forces(body, body.points.position, body.points.velocity, 0.0, force);
  EXPECT_EQ(force[0], (Vec2{0, -6}));
  EXPECT_EQ(force[1], Vec2{});
}

TEST(Body, AccumulateForcesRejectsMismatchedSizes) {
  Body body;
  body.add_point({0, 0}, 1.0);
  std::vector<Vec2> force;
  EXPECT_THROW(accumulate_forces(body, {}, body.points.velocity, 0.0, force), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::elastic
