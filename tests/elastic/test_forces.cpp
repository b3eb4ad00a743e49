// Force laws of thesis §2.1-2.3: conservation, consistency with the energies, analytic Jacobians.
#include "jellysim/elastic/forces.hpp"
#include "elastic_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace jellysim::elastic {
namespace {

using test::expect_mat_near;
using test::expect_vec_near;
using test::Random;
constexpr double pi = std::numbers::pi;
constexpr int trials = 200;

struct Triple {
  Vec2 x[3];
};

/// Three points with both segments at least 0.2 long (so gradients stay O(1)).
Triple random_triple(Random& rng) {
  for (;;) {
    Triple t{{rng.point(), rng.point(), rng.point()}};
    if (norm(t.x[1] - t.x[0]) > 0.2 && norm(t.x[2] - t.x[1]) > 0.2) return t;
  }
}

// ---- Linear spring ----

TEST(LinearSpring, StretchedSpringPullsWithHookeMagnitude) {
  const Vec2 xi{1.0, 2.0}, xj{1.0 + 0.6, 2.0 + 0.8};  // length 1
  const Vec2 f = linear_spring_force(xi, xj, 3.0, 0.75);
  expect_vec_near(f, 3.0 * 0.25 * Vec2{0.6, 0.8}, 1e-14);  // k Δl, toward j
  const Vec2 compressed = linear_spring_force(xi, xj, 3.0, 1.5);
  expect_vec_near(compressed, -3.0 * 0.5 * Vec2{0.6, 0.8}, 1e-14);  // pushed away from j
}

TEST(LinearSpring, ZeroLengthGivesZeroForceAndFiniteJacobian) {
  const Vec2 x{0.3, -0.2};
  const LinearSpringForce f = linear_spring_force_and_jacobian(x, x, 5.0, 0.0);
  EXPECT_EQ(f.on_i, Vec2{});
  EXPECT_EQ(linear_spring_force(x, x, 5.0, 1.0), Vec2{});
  expect_mat_near(f.d_on_i_d_xi, -5.0 * Mat2::identity(), 0.0);
}

TEST(LinearSpring, ForcesBalanceAndExertNoTorque) {
  Random rng(1);
  for (int n = 0; n < trials; ++n) {
    const Vec2 xi = rng.point(), xj = rng.point();
    const Vec2 f = linear_spring_force(xi, xj, rng.uniform(0.1, 10), rng.uniform(0, 2));
    // F_j = -F_i by construction; the torque (x_i - x_j) × F_i vanishes because F ∥ x_ij.
    EXPECT_NEAR(cross(xi, f) + cross(xj, -f), 0.0, 1e-12);
  }
}

TEST(LinearSpring, ForceIsMinusEnergyGradient) {
  Random rng(2);
  for (int n = 0; n < trials; ++n) {
    const Vec2 xi = rng.point(), xj = rng.point();
    const double k = rng.uniform(0.1, 10), lr = rng.uniform(0, 2);
    const Vec2 grad = test::fd_gradient([&](Vec2 x) { return linear_spring_energy(x, xj, k, lr); }, xi);
    expect_vec_near(linear_spring_force(xi, xj, k, lr), -grad, 1e-6);
  }
}

TEST(LinearSpring, JacobianBlocksMatchFiniteDifferences) {
  Random rng(3);
  for (int n = 0; n < trials; ++n) {
    const Vec2 xi = rng.point(), xj = rng.point();
    if (norm(xj - xi) < 0.1) continue;
    const double k = rng.uniform(0.1, 10), lr = rng.uniform(0, 2);
    const LinearSpringForce f = linear_spring_force_and_jacobian(xi, xj, k, lr);
    expect_vec_near(f.on_i, linear_spring_force(xi, xj, k, lr), 1e-14);
    const Mat2 dii = test::fd_jacobian([&](Vec2 x) { return linear_spring_force(x, xj, k, lr); }, xi);
    const Mat2 dij = test::fd_jacobian([&](Vec2 x) { return linear_spring_force(xi, x, k, lr); }, xj);
    const Mat2 dji = test::fd_jacobian([&](Vec2 x) { return -linear_spring_force(x, xj, k, lr); }, xi);
    const Mat2 djj = test::fd_jacobian([&](Vec2 x) { return -linear_spring_force(xi, x, k, lr); }, xj);
    const double tol = 1e-5 * k;
    expect_mat_near(f.d_on_i_d_xi, dii, tol);
    expect_mat_near(-f.d_on_i_d_xi, dij, tol);
    expect_mat_near(-f.d_on_i_d_xi, dji, tol);
    expect_mat_near(f.d_on_i_d_xi, djj, tol);
  }
}

// ---- Angular spring ----

TEST(AngularSpring, TurningAngleOfRightAngles) {
  EXPECT_NEAR(turning_angle({0, 0}, {1, 0}, {1, 1}), pi / 2, 1e-15);    // left turn
  EXPECT_NEAR(turning_angle({0, 0}, {1, 0}, {1, -1}), -pi / 2, 1e-15);  // right turn
  EXPECT_NEAR(turning_angle({0, 0}, {1, 0}, {2, 0}), 0.0, 1e-15);       // straight on
}

TEST(AngularSpring, WrapAngleIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(pi), pi);
  EXPECT_DOUBLE_EQ(wrap_angle(-pi), pi);
  EXPECT_NEAR(wrap_angle(2 * pi - 0.02), -0.02, 1e-14);
  EXPECT_NEAR(wrap_angle(-3 * pi + 0.5), -pi + 0.5, 1e-14);
  EXPECT_NEAR(wrap_angle(0.3), 0.3, 0.0);
}

TEST(AngularSpring, ForcesBalanceAndExertNoTorque) {
  Random rng(4);
  for (int n = 0; n < trials; ++n) {
    const Triple t = random_triple(rng);
    const AngularSpringForce f =
        angular_spring_force(t.x[0], t.x[1], t.x[2], rng.uniform(0.1, 10), rng.uniform(-pi, pi));
    expect_vec_near(f.on_i + f.on_j + f.on_k, {}, 1e-12);
    EXPECT_NEAR(cross(t.x[0], f.on_i) + cross(t.x[1], f.on_j) + cross(t.x[2], f.on_k), 0.0, 1e-12);
  }
}

TEST(AngularSpring, ForceIsMinusEnergyGradient) {
  Random rng(5);
  for (int n = 0; n < trials; ++n) {
    Triple t = random_triple(rng);
    const double k = rng.uniform(0.1, 10), rest = rng.uniform(-pi, pi);
    const AngularSpringForce f = angular_spring_force(t.x[0], t.x[1], t.x[2], k, rest);
    const Vec2 on[3] = {f.on_i, f.on_j, f.on_k};
    // Skip configurations within a few FD steps of the energy's kink at θ - θ_r = ±π.
    if (std::abs(wrap_angle(turning_angle(t.x[0], t.x[1], t.x[2]) - rest)) > pi - 1e-3) continue;
    for (int p = 0; p < 3; ++p) {
      const Vec2 grad = test::fd_gradient(
          [&](Vec2 x) {
            Triple moved = t;
            moved.x[p] = x;
            return angular_spring_energy(moved.x[0], moved.x[1], moved.x[2], k, rest);
          },
          t.x[p]);
      expect_vec_near(on[p], -grad, 1e-5 * k);
    }
  }
}

TEST(AngularSpring, JacobianMatchesFiniteDifferences) {
  Random rng(6);
  for (int n = 0; n < trials; ++n) {
    const Triple t = random_triple(rng);
    const double k = rng.uniform(0.1, 10), rest = rng.uniform(-pi, pi);
    if (std::abs(wrap_angle(turning_angle(t.x[0], t.x[1], t.x[2]) - rest)) > pi - 1e-3) continue;
    const AngularSpringForce f = angular_spring_force_and_jacobian(t.x[0], t.x[1], t.x[2], k, rest);
    for (int q = 0; q < 3; ++q) {
      const auto force_of = [&](Vec2 x, int p) {
        Triple moved = t;
        moved.x[q] = x;
        const AngularSpringForce g = angular_spring_force(moved.x[0], moved.x[1], moved.x[2], k, rest);
        const Vec2 on[3] = {g.on_i, g.on_j, g.on_k};
        return on[p];
      };
      for (int p = 0; p < 3; ++p) {
        const Mat2 fd = test::fd_jacobian([&](Vec2 x) { return force_of(x, p); }, t.x[q]);
        expect_mat_near(f.jacobian[p][q], fd, 1e-4 * k);
      }
    }
  }
}

/// Points i = (-1, 0), j = (0, 0) and k at unit distance in direction θ from j: turning angle θ.
Triple with_turning_angle(double theta) { return {{{-1.0, 0.0}, {0.0, 0.0}, {std::cos(theta), std::sin(theta)}}}; }

TEST(AngularSpring, NearPiRestoresAcrossTheShortWay) {
  const double k = 2.0;
  const Triple t = with_turning_angle(pi - 0.01);
  EXPECT_NEAR(turning_angle(t.x[0], t.x[1], t.x[2]), pi - 0.01, 1e-14);
  const AngularSpringForce f = angular_spring_force(t.x[0], t.x[1], t.x[2], k, -pi + 0.01);
  // θ - θ_r wraps to -0.02: |F_k| = κ |wrap| |∇_k θ| = κ 0.02 / |b| with |b| = 1.
  EXPECT_NEAR(norm(f.on_k), k * 0.02, 1e-12);
  EXPECT_NEAR(norm(f.on_i), k * 0.02, 1e-12);
  // The restoring force increases θ through π toward θ_r = -π + 0.01: F_k ∥ +∇_k θ = perp(b).
  EXPECT_GT(dot(f.on_k, perp(t.x[2] - t.x[1])), 0.0);
  EXPECT_NEAR(angular_spring_energy(t.x[0], t.x[1], t.x[2], k, -pi + 0.01), 0.5 * k * 0.02 * 0.02, 1e-14);
}

TEST(AngularSpring, ForceIsContinuousWhenTheAngleCrossesPi) {
  const double k = 2.0, rest = 3.0, eps = 1e-7;
  const Triple below = with_turning_angle(pi - eps);
  const Triple above = with_turning_angle(pi + eps);  // turning_angle reports -π + ε
  EXPECT_LT(turning_angle(above.x[0], above.x[1], above.x[2]), 0.0);
  const AngularSpringForce fb = angular_spring_force(below.x[0], below.x[1], below.x[2], k, rest);
  const AngularSpringForce fa = angular_spring_force(above.x[0], above.x[1], above.x[2], k, rest);
  EXPECT_GT(norm(fb.on_k), 0.2);  // κ (π - 3) ≈ 0.28: a real force, not a vanishing one
  expect_vec_near(fa.on_k, fb.on_k, 1e-5);
  expect_vec_near(fa.on_i, fb.on_i, 1e-5);
  expect_vec_near(fa.on_j, fb.on_j, 1e-5);
}

TEST(AngularSpring, DegenerateSegmentGivesNoForce) {
  const AngularSpringForce f = angular_spring_force_and_jacobian({0, 0}, {0, 0}, {1, 0}, 1.0, 0.5);
  EXPECT_EQ(f.on_i, Vec2{});
  EXPECT_EQ(f.on_j, Vec2{});
  EXPECT_EQ(f.on_k, Vec2{});
}

// ---- Drag, gravity, material ----

TEST(OtherForces, DragOpposesRelativeVelocityAndGravityScalesWithMass) {
  expect_vec_near(drag_force({1.0, 2.0}, {0.5, -1.0}, 4.0), {-2.0, -12.0}, 0.0);
  expect_vec_near(gravity_force(24.0, {0.0, -0.05}), {0.0, -1.2}, 1e-15);
}

TEST(Material, StiffnessFromModulusIsModulusTimesAreaOverLength) {
  // Bell mesoglea (Megill): λ = 1186 Pa, A = (1 mm)², l_r = 2 cm → κ_l = 1186·1e-6/0.02.
  EXPECT_NEAR(linear_stiffness_from_modulus(1186.0, 1e-6, 0.02), 0.0593, 1e-15);
  EXPECT_THROW(linear_stiffness_from_modulus(0.0, 1e-6, 0.02), std::invalid_argument);
  EXPECT_THROW(linear_stiffness_from_modulus(1186.0, -1e-6, 0.02), std::invalid_argument);
  EXPECT_THROW(linear_stiffness_from_modulus(1186.0, 1e-6, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::elastic
