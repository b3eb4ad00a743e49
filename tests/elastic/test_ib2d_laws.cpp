// IB2d's structural laws (forces.hpp): torsional and non-invariant beams, power-law springs and
// dashpots; their hand values, balance, energies and Jacobians, and their use by Body and
// ElasticSystem.
#include "jellysim/elastic/elastic_system.hpp"
#include "jellysim/elastic/forces.hpp"
#include "jellysim/elastic/spring_assembly.hpp"
#include "elastic_test_util.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace jellysim::elastic {
namespace {

using test::expect_mat_near;
using test::expect_vec_near;
using test::Random;
constexpr int trials = 200;

// The 5-point structure of the hand-value tests: a bump 0-1-2 of height h = 0.25 over a base of
// 2, point 3 at unit distance from 2 along (0.6, 0.8), and point 4 below.
constexpr double h = 0.25;
const Vec2 X[5] = {{-1.0, 0.0}, {0.0, h}, {1.0, 0.0}, {1.6, 0.8}, {0.3, -0.9}};

/// Largest absolute entry of a block, at least 1: the scale of a relative tolerance.
double scale_of(const Mat2& m) {
  return std::max({1.0, std::abs(m.xx), std::abs(m.xy), std::abs(m.yx), std::abs(m.yy)});
}

struct Triple {
  Vec2 x[3];
};

Triple random_triple(Random& rng) { return {{rng.point(), rng.point(), rng.point()}}; }

/// Checks a three-point law: forces sum to zero, F = −∇E, Jacobian = central differences.
template <typename Law, typename Energy>
void check_three_point_law(const Triple& t, Law&& law, Energy&& energy) {
  const ThreePointForce f = law(t.x[0], t.x[1], t.x[2]);
  const Vec2 sum = f.on[0] + f.on[1] + f.on[2];
  const double force_scale = 1.0 + norm(f.on[0]) + norm(f.on[1]) + norm(f.on[2]);
  expect_vec_near(sum, {}, 1e-13 * force_scale);
  for (int q = 0; q < 3; ++q) {
    const auto moved = [&](Vec2 x) {
      Triple m = t;
      m.x[q] = x;
      return m;
    };
    const Vec2 grad = test::fd_gradient(
        [&](Vec2 x) {
          const Triple m = moved(x);
          return energy(m.x[0], m.x[1], m.x[2]);
        },
        t.x[q]);
    expect_vec_near(f.on[q], -grad, 1e-6 * force_scale);
    for (int p = 0; p < 3; ++p) {
      const Mat2 fd = test::fd_jacobian(
          [&](Vec2 x) {
            const Triple m = moved(x);
            return law(m.x[0], m.x[1], m.x[2]).on[p];
          },
          t.x[q]);
      expect_mat_near(f.jacobian[p][q], fd, 1e-6 * scale_of(fd));
    }
  }
}

// ---- Torsional beam ----

TEST(TorsionalBeam, HandValuesOnABump) {
  // c = (X_r − X_m)(Y_m − Y_l) − (Y_r − Y_m)(X_m − X_l) = (1)(h) − (−h)(1) = 2h.
  EXPECT_DOUBLE_EQ(beam_cross_product(X[0], X[1], X[2]), 2.0 * h);
  const double k = 3.0;
  // C = 0: e = k (c − C) = 2kh = 1.5. F_l = e perp(x_r − x_m) = e (h, 1): the left end is pulled up
  // and toward the middle; F_r = e perp(x_m − x_l) = e (−h, 1); F_m = −e perp(x_r − x_l) = (0, −2e):
  // the middle is pushed down, flattening the bump.
  const ThreePointForce flat = torsional_beam_force_and_jacobian(X[0], X[1], X[2], k, 0.0);
  expect_vec_near(flat.on[0], {0.375, 1.5}, 1e-15);
  expect_vec_near(flat.on[1], {0.0, -3.0}, 1e-15);
  expect_vec_near(flat.on[2], {-0.375, 1.5}, 1e-15);
  EXPECT_DOUBLE_EQ(torsional_beam_energy(X[0], X[1], X[2], k, 0.0), 0.5 * k * 0.25);  // ½ k (2h)²
  // C = 0.2 (a preferred bump lower than the present one): e = 3 (0.5 − 0.2) = 0.9.
  const ThreePointForce bent = torsional_beam_force_and_jacobian(X[0], X[1], X[2], k, 0.2);
  expect_vec_near(bent.on[0], {0.225, 0.9}, 1e-15);
  expect_vec_near(bent.on[1], {0.0, -1.8}, 1e-15);
  expect_vec_near(bent.on[2], {-0.225, 0.9}, 1e-15);
  // C = 1 (a higher bump preferred): e = −1.5, the middle is pulled up.
  EXPECT_GT(torsional_beam_force_and_jacobian(X[0], X[1], X[2], k, 1.0).on[1].y, 0.0);
  // At the preferred value there is no force.
  const ThreePointForce rest = torsional_beam_force_and_jacobian(X[0], X[1], X[2], k, 2.0 * h);
  for (const Vec2 f : rest.on) EXPECT_EQ(f, Vec2{});
}

TEST(TorsionalBeam, BalancedEnergyGradientAndJacobian) {
  Random rng(31);
  for (int n = 0; n < trials; ++n) {
    const Triple t = random_triple(rng);
    const double k = rng.uniform(0.1, 10), c = rng.uniform(-1, 1);
    check_three_point_law(
        t, [&](Vec2 l, Vec2 m, Vec2 r) { return torsional_beam_force_and_jacobian(l, m, r, k, c); },
        [&](Vec2 l, Vec2 m, Vec2 r) { return torsional_beam_energy(l, m, r, k, c); });
  }
}

TEST(TorsionalBeam, ExertsNoNetTorqueAndReversingNegatesTheCrossProduct) {
  Random rng(32);
  for (int n = 0; n < trials; ++n) {
    const Triple t = random_triple(rng);
    const ThreePointForce f = torsional_beam_force_and_jacobian(t.x[0], t.x[1], t.x[2], 2.0, 0.3);
    EXPECT_NEAR(cross(t.x[0], f.on[0]) + cross(t.x[1], f.on[1]) + cross(t.x[2], f.on[2]), 0.0, 1e-12);
    EXPECT_NEAR(beam_cross_product(t.x[2], t.x[1], t.x[0]), -beam_cross_product(t.x[0], t.x[1], t.x[2]), 1e-15);
  }
}

// ---- Non-invariant beam ----

TEST(NonInvariantBeam, HandValuesOnABump) {
  // D = x_l − 2 x_m + x_r − C = (0, −2h) − (0.1, −0.2) = (−0.1, −0.3).
  const double k = 2.0;
  const Vec2 c{0.1, -0.2};
  const ThreePointForce f = non_invariant_beam_force_and_jacobian(X[0], X[1], X[2], k, c);
  expect_vec_near(f.on[0], {0.2, 0.6}, 1e-15);    // −k D
  expect_vec_near(f.on[1], {-0.4, -1.2}, 1e-15);  // +2k D
  expect_vec_near(f.on[2], {0.2, 0.6}, 1e-15);    // −k D
  EXPECT_NEAR(non_invariant_beam_energy(X[0], X[1], X[2], k, c), 0.5 * k * (0.01 + 0.09), 1e-15);
  // The Jacobian is constant: −k w_a w_b I with w = (1, −2, 1).
  expect_mat_near(f.jacobian[0][0], -k * Mat2::identity(), 0.0);
  expect_mat_near(f.jacobian[0][1], 2.0 * k * Mat2::identity(), 0.0);
  expect_mat_near(f.jacobian[0][2], -k * Mat2::identity(), 0.0);
  expect_mat_near(f.jacobian[1][1], -4.0 * k * Mat2::identity(), 0.0);
  expect_mat_near(f.jacobian[2][1], 2.0 * k * Mat2::identity(), 0.0);
}

TEST(NonInvariantBeam, BalancedEnergyGradientAndJacobian) {
  Random rng(33);
  for (int n = 0; n < trials; ++n) {
    const Triple t = random_triple(rng);
    const double k = rng.uniform(0.1, 10);
    const Vec2 c = rng.point();
    check_three_point_law(
        t, [&](Vec2 l, Vec2 m, Vec2 r) { return non_invariant_beam_force_and_jacobian(l, m, r, k, c); },
        [&](Vec2 l, Vec2 m, Vec2 r) { return non_invariant_beam_energy(l, m, r, k, c); });
  }
}

// ---- Power-law spring ----

TEST(PowerSpring, HandValuesStretchedAndCompressed) {
  // x_i = X[2], x_j = X[3]: length 1 along d̂ = (0.6, 0.8). α = 2, k = 3.
  const double k = 3.0, alpha = 2.0;
  // Stretched by e = 0.25: T = ½ (α+1) k e² = 4.5 · 0.0625 = 0.28125 > 0, F_i toward j.
  expect_vec_near(power_spring_force(X[2], X[3], k, 0.75, alpha), 0.28125 * Vec2{0.6, 0.8}, 1e-15);
  EXPECT_NEAR(power_spring_energy(X[2], X[3], k, 0.75, alpha), 0.5 * k * 0.015625, 1e-15);  // ½ k e³
  // Compressed by 0.5: T = −4.5 · 0.25 = −1.125, F_i pushed away from j.
  expect_vec_near(power_spring_force(X[2], X[3], k, 1.5, alpha), -1.125 * Vec2{0.6, 0.8}, 1e-15);
  EXPECT_NEAR(power_spring_energy(X[2], X[3], k, 1.5, alpha), 0.5 * k * 0.125, 1e-15);
  // α = 1 is Hooke's law, the linear spring.
  for (double rest : {0.0, 0.75, 1.5}) {
    expect_vec_near(power_spring_force(X[2], X[3], k, rest, 1.0), linear_spring_force(X[2], X[3], k, rest), 1e-15);
    expect_mat_near(power_spring_force_and_jacobian(X[2], X[3], k, rest, 1.0).d_on_i_d_xi,
                    linear_spring_force_and_jacobian(X[2], X[3], k, rest).d_on_i_d_xi, 1e-15);
  }
}

TEST(PowerSpring, ZeroLengthGivesNoForce) {
  const LinearSpringForce f = power_spring_force_and_jacobian(X[1], X[1], 2.0, 0.0, 3.0);
  EXPECT_EQ(f.on_i, Vec2{});
  EXPECT_EQ(power_spring_force(X[1], X[1], 2.0, 0.5, 3.0), Vec2{});
  expect_mat_near(f.d_on_i_d_xi, Mat2{}, 0.0);  // T'(e = 0) = 0 for α > 1
}

TEST(PowerSpring, EnergyGradientAndJacobian) {
  Random rng(34);
  for (int n = 0; n < trials; ++n) {
    const Vec2 xi = rng.point(), xj = rng.point();
    const double k = rng.uniform(0.1, 10), rest = rng.uniform(0, 2), alpha = rng.uniform(1, 4);
    const double stretch = norm(xj - xi) - rest;
    // |e|^(α−1) is not smooth at e = 0 for α < 2: stay a few steps away from it.
    if (norm(xj - xi) < 0.1 || std::abs(stretch) < 1e-2) continue;
    const LinearSpringForce f = power_spring_force_and_jacobian(xi, xj, k, rest, alpha);
    expect_vec_near(f.on_i, power_spring_force(xi, xj, k, rest, alpha), 1e-14 * (1.0 + norm(f.on_i)));
    const Vec2 grad = test::fd_gradient([&](Vec2 x) { return power_spring_energy(x, xj, k, rest, alpha); }, xi);
    expect_vec_near(f.on_i, -grad, 1e-6 * (1.0 + norm(grad)));
    const Mat2 dii = test::fd_jacobian([&](Vec2 x) { return power_spring_force(x, xj, k, rest, alpha); }, xi);
    const Mat2 dij = test::fd_jacobian([&](Vec2 x) { return power_spring_force(xi, x, k, rest, alpha); }, xj);
    expect_mat_near(f.d_on_i_d_xi, dii, 1e-6 * scale_of(dii));
    expect_mat_near(-f.d_on_i_d_xi, dij, 1e-6 * scale_of(dij));
  }
}

// ---- Dashpot ----

TEST(Dashpot, HandValuesDampTheClosingSpeed) {
  // x_i = X[0], x_j = X[2]: d̂ = (1, 0). v_j − v_i = (−1, 2): closing at 1 m/s along the line.
  // F_i = b ((v_j − v_i)·d̂) d̂ = 4 · (−1) · (1, 0): i is pushed away from the approaching j.
  const Vec2 vi{0.5, 1.0}, vj{-0.5, 3.0};
  expect_vec_near(dashpot_force(X[0], X[2], vi, vj, 4.0), {-4.0, 0.0}, 0.0);
  // Sliding across the line (relative velocity ⟂ d̂) is not damped; a common velocity is not either.
  expect_vec_near(dashpot_force(X[0], X[2], {0, 1}, {0, -1}, 4.0), {}, 0.0);
  expect_vec_near(dashpot_force(X[0], X[2], {3, 1}, {3, 1}, 4.0), {}, 0.0);
  EXPECT_EQ(dashpot_force(X[1], X[1], vi, vj, 4.0), Vec2{});
}

TEST(Dashpot, JacobiansMatchFiniteDifferences) {
  Random rng(35);
  for (int n = 0; n < trials; ++n) {
    const Vec2 xi = rng.point(), xj = rng.point(), vi = rng.point(), vj = rng.point();
    if (norm(xj - xi) < 0.1) continue;
    const double b = rng.uniform(0.1, 10);
    const DashpotForce f = dashpot_force_and_jacobian(xi, xj, vi, vj, b);
    expect_vec_near(f.on_i, dashpot_force(xi, xj, vi, vj, b), 1e-14 * (1.0 + norm(f.on_i)));
    const Vec2 dir = (xj - xi) / norm(xj - xi);
    expect_mat_near(f.d_on_i_d_vi, -b * Mat2::outer(dir, dir), 1e-14);
    const Mat2 dvi = test::fd_jacobian([&](Vec2 v) { return dashpot_force(xi, xj, v, vj, b); }, vi);
    const Mat2 dvj = test::fd_jacobian([&](Vec2 v) { return dashpot_force(xi, xj, vi, v, b); }, vj);
    const Mat2 dxi = test::fd_jacobian([&](Vec2 x) { return dashpot_force(x, xj, vi, vj, b); }, xi);
    const Mat2 dxj = test::fd_jacobian([&](Vec2 x) { return dashpot_force(xi, x, vi, vj, b); }, xj);
    expect_mat_near(f.d_on_i_d_vi, dvi, 1e-6 * scale_of(dvi));
    expect_mat_near(-f.d_on_i_d_vi, dvj, 1e-6 * scale_of(dvj));
    expect_mat_near(f.d_on_i_d_xi, dxi, 1e-6 * scale_of(dxi));
    expect_mat_near(-f.d_on_i_d_xi, dxj, 1e-6 * scale_of(dxj));
  }
}

// ---- Body ----

/// The 5-point structure as a body: all four IB2d laws, away from rest, with point 4 pinned.
Body make_ib2d_body() {
  Body body;
  for (int p = 0; p < 4; ++p) body.add_point(X[p], 0.5 + 0.25 * p, PointKind::Free, {0.1 * p, -0.2 * p});
  body.add_point(X[4], 1.0, PointKind::Pinned);
  body.add_torsional_beam(0, 1, 2, 3.0, 0.2);
  body.add_torsional_beam(1, 2, 3, 1.5, -0.1);
  body.add_non_invariant_beam(0, 1, 2, 2.0, {0.1, -0.2});
  body.add_non_invariant_beam(2, 3, 4, 0.7, {-0.3, 0.4});
  body.add_power_spring(2, 3, 3.0, 0.75, 2.0);
  body.add_power_spring(4, 1, 1.2, 0.8, 3.5);
  body.add_dashpot(0, 2, 4.0);
  body.add_dashpot(3, 4, 0.6);
  return body;
}

TEST(Ib2dBody, AddValidatesItsArguments) {
  Body body = make_ib2d_body();
  const double nan = std::nan("");
  EXPECT_THROW(body.add_torsional_beam(0, 1, 5, 1.0, 0.0), std::invalid_argument);   // out of range
  EXPECT_THROW(body.add_torsional_beam(0, 1, 0, 1.0, 0.0), std::invalid_argument);   // repeated point
  EXPECT_THROW(body.add_torsional_beam(0, 1, 2, -1.0, 0.0), std::invalid_argument);  // negative stiffness
  EXPECT_THROW(body.add_torsional_beam(0, 1, 2, 1.0, INFINITY), std::invalid_argument);
  EXPECT_THROW(body.add_non_invariant_beam(-1, 1, 2, 1.0, {}), std::invalid_argument);
  EXPECT_THROW(body.add_non_invariant_beam(0, 2, 2, 1.0, {}), std::invalid_argument);
  EXPECT_THROW(body.add_non_invariant_beam(0, 1, 2, nan, {}), std::invalid_argument);
  EXPECT_THROW(body.add_non_invariant_beam(0, 1, 2, 1.0, {nan, 0.0}), std::invalid_argument);  // half-NaN
  EXPECT_THROW(body.add_power_spring(1, 1, 1.0, 0.5, 2.0), std::invalid_argument);
  EXPECT_THROW(body.add_power_spring(1, 7, 1.0, 0.5, 2.0), std::invalid_argument);
  EXPECT_THROW(body.add_power_spring(1, 2, INFINITY, 0.5, 2.0), std::invalid_argument);
  EXPECT_THROW(body.add_power_spring(1, 2, 1.0, 0.5, 0.5), std::invalid_argument);   // α < 1
  EXPECT_THROW(body.add_power_spring(1, 2, 1.0, 0.5, 10.5), std::invalid_argument);  // α > 10
  EXPECT_THROW(body.add_power_spring(1, 2, 1.0, 0.5, nan), std::invalid_argument);
  EXPECT_THROW(body.add_power_spring(1, 2, 1.0, INFINITY, 2.0), std::invalid_argument);
  EXPECT_THROW(body.add_dashpot(3, 3, 1.0), std::invalid_argument);
  EXPECT_THROW(body.add_dashpot(3, 9, 1.0), std::invalid_argument);
  EXPECT_THROW(body.add_dashpot(3, 2, -0.1), std::invalid_argument);
  // Nothing was added by the failed calls.
  EXPECT_EQ(body.torsional.size(), 2u);
  EXPECT_EQ(body.non_invariant.size(), 2u);
  EXPECT_EQ(body.power.size(), 2u);
  EXPECT_EQ(body.dashpots.size(), 2u);
}

TEST(Ib2dBody, AddDefaultsToTheCurrentShape) {
  Body body = make_ib2d_body();
  const double nan = std::nan("");
  body.add_torsional_beam(0, 1, 2, 1.0, nan);
  EXPECT_DOUBLE_EQ(body.torsional.curvature.back(), 2.0 * h);
  body.add_non_invariant_beam(0, 1, 2, 1.0, {nan, nan});
  EXPECT_EQ(body.non_invariant.curvature.back(), (Vec2{0.0, -2.0 * h}));
  body.add_power_spring(2, 3, 1.0, -1.0, 1.5);
  EXPECT_DOUBLE_EQ(body.power.rest_length.back(), 1.0);
  body.add_power_spring(2, 3, 1.0, 0.5, 10.0);  // the ends of the range are allowed
  body.add_power_spring(2, 3, 1.0, 0.5, 1.0);
  EXPECT_EQ(body.power.size(), 5u);
}

TEST(Ib2dBody, SpringForcesSumTheLawsAndBalance) {
  const Body body = make_ib2d_body();
  std::vector<Vec2> force(body.points.size());
  add_spring_forces(body, body.points.position, force);
  std::vector<Vec2> expected(body.points.size());
  const ThreePointForce t0 = torsional_beam_force_and_jacobian(X[0], X[1], X[2], 3.0, 0.2);
  const ThreePointForce t1 = torsional_beam_force_and_jacobian(X[1], X[2], X[3], 1.5, -0.1);
  const ThreePointForce n0 = non_invariant_beam_force_and_jacobian(X[0], X[1], X[2], 2.0, {0.1, -0.2});
  const ThreePointForce n1 = non_invariant_beam_force_and_jacobian(X[2], X[3], X[4], 0.7, {-0.3, 0.4});
  const Vec2 p0 = power_spring_force(X[2], X[3], 3.0, 0.75, 2.0);
  const Vec2 p1 = power_spring_force(X[4], X[1], 1.2, 0.8, 3.5);
  for (int a = 0; a < 3; ++a) {
    expected[a] += t0.on[a] + n0.on[a];
    expected[1 + a] += t1.on[a];
    expected[2 + a] += n1.on[a];
  }
  expected[2] += p0;
  expected[3] -= p0;
  expected[4] += p1;
  expected[1] -= p1;
  Vec2 total{};
  for (std::size_t p = 0; p < force.size(); ++p) {
    expect_vec_near(force[p], expected[p], 1e-14);
    total += force[p];
  }
  expect_vec_near(total, {}, 1e-13);
}

TEST(Ib2dBody, AccumulateForcesIncludesTheDashpots) {
  const Body body = make_ib2d_body();
  std::vector<Vec2> with_dashpots, springs_only(body.points.size());
  accumulate_forces(body, body.points.position, body.points.velocity, 0.0, with_dashpots);
  add_spring_forces(body, body.points.position, springs_only);
  const auto& v = body.points.velocity;
  const Vec2 d0 = dashpot_force(X[0], X[2], v[0], v[2], 4.0);
  const Vec2 d1 = dashpot_force(X[3], X[4], v[3], v[4], 0.6);
  EXPECT_GT(norm(d0), 0.1);  // v_2 − v_0 = (0.2, −0.4) has a component along the line
  const Vec2 dashpot[5] = {d0, {}, -d0, d1, -d1};
  for (std::size_t p = 0; p < 5; ++p) expect_vec_near(with_dashpots[p], springs_only[p] + dashpot[p], 1e-14);
}

TEST(Ib2dBody, ForcesAreMinusGradientOfElasticEnergy) {
  Body body = make_ib2d_body();
  std::vector<Vec2> force(body.points.size());
  add_spring_forces(body, body.points.position, force);
  for (std::size_t p = 0; p < body.points.size(); ++p) {
    const Vec2 x0 = body.points.position[p];
    const Vec2 grad = test::fd_gradient(
        [&](Vec2 x) {
          body.points.position[p] = x;
          return energy(body).elastic;
        },
        x0);
    body.points.position[p] = x0;
    expect_vec_near(force[p], -grad, 1e-6 * (1.0 + norm(grad)));
  }
}

TEST(Ib2dBody, SpringJacobianBlocksMatchFiniteDifferences) {
  Body body = make_ib2d_body();
  const std::size_t n = body.points.size();
  std::vector<Mat2> analytic(n * n);
  for_each_spring_jacobian_block(body, body.points.position, [&](int a, int b, const Mat2& d) {
    analytic[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] =
        analytic[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] + d;
  });
  for (std::size_t b = 0; b < n; ++b) {
    const Vec2 x0 = body.points.position[b];
    for (std::size_t a = 0; a < n; ++a) {
      const Mat2 fd = test::fd_jacobian(
          [&](Vec2 x) {
            std::vector<Vec2> moved = body.points.position, force(n);
            moved[b] = x;
            add_spring_forces(body, moved, force);
            return force[a];
          },
          x0);
      expect_mat_near(analytic[a * n + b], fd, 1e-6 * scale_of(fd));
    }
  }
}

TEST(Ib2dBody, ElasticSystemJacobianIncludesTheDashpots) {
  const Body body = make_ib2d_body();
  const ElasticSystem system(body);
  const double t = 0.2;
  const ode::Vector y = system.pack_state();
  ode::SparseMatrix sparse;
  system.jacobian(t, y, sparse);
  const Eigen::MatrixXd analytic(sparse);
  Eigen::MatrixXd numeric(y.size(), y.size());
  for (Eigen::Index c = 0; c < y.size(); ++c) {
    ode::Vector plus = y, minus = y, dplus, dminus;
    plus[c] += test::fd_step;
    minus[c] -= test::fd_step;
    system.derivative(t, plus, dplus);
    system.derivative(t, minus, dminus);
    numeric.col(c) = (dplus - dminus) / (2.0 * test::fd_step);
  }
  const double scale = numeric.cwiseAbs().maxCoeff();
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6 * scale);
  // ∂v_0'/∂v_2 = +b d̂d̂ᵀ / m_0 with d̂ = (1, 0) for the dashpot 0-2.
  const auto np = system.position_size();
  EXPECT_NEAR(analytic(np, np + 4), 4.0 / body.points.mass[0], 1e-14);
}

}  // namespace
}  // namespace jellysim::elastic
