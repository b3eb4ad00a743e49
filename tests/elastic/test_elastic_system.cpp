// The spring-mass body as an ODE system (eq. 2.19): derivative, sparse Jacobian, state packing.
#include "jellysim/elastic/elastic_system.hpp"
#include "elastic_test_util.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace jellysim::elastic {
namespace {

using test::Random;

PrescribedState circle(double t) {
  return {{2.0 + std::cos(t), std::sin(t)}, {-std::sin(t), std::cos(t)}, {-std::cos(t), -std::sin(t)}};
}

/// The shared test body plus drag in a uniform current and a prescribed point tied in by springs.
Body make_system_body(Random& rng) {
  Body body = test::make_test_body(rng);
  body.drag_coefficient = 0.7;
  body.fluid_velocity = [](Vec2, double) { return Vec2{0.2, -0.1}; };
  const int driven = body.add_prescribed_point(circle);
  body.add_linear_spring(5, driven, 9.0, 0.4);
  body.add_angular_spring(4, 5, driven, 1.5, 0.2);
  return body;
}

ode::Vector derivative_at(const ElasticSystem& system, double t, const ode::Vector& y) {
  ode::Vector dydt;
  system.derivative(t, y, dydt);
  return dydt;
}

Eigen::MatrixXd fd_jacobian(const ElasticSystem& system, double t, const ode::Vector& y) {
  const double h = test::fd_step;
  Eigen::MatrixXd jac(y.size(), y.size());
  for (Eigen::Index c = 0; c < y.size(); ++c) {
    ode::Vector plus = y, minus = y;
    plus[c] += h;
    minus[c] -= h;
    jac.col(c) = (derivative_at(system, t, plus) - derivative_at(system, t, minus)) / (2.0 * h);
  }
  return jac;
}

Eigen::MatrixXd analytic_jacobian(const ElasticSystem& system, double t, const ode::Vector& y) {
  ode::SparseMatrix jac;
  system.jacobian(t, y, jac);
  return Eigen::MatrixXd(jac);
}

TEST(ElasticSystem, DimensionsAndPackUnpackRoundTrip) {
  Random rng(21);
  Body body = make_system_body(rng);
  ElasticSystem system(body);
  const auto n = static_cast<Eigen::Index>(body.points.size());
  EXPECT_EQ(system.dimension(), 4 * n);
  EXPECT_EQ(system.position_size(), 2 * n);
  ode::Vector y = system.pack_state();
  ASSERT_EQ(y.size(), 4 * n);
  EXPECT_EQ(y[2], body.points.position[1].x);
  EXPECT_EQ(y[2 * n + 3], body.points.velocity[1].y);
  y[0] += 0.25;
  ElasticSystem::unpack_state(y, 1.0, body);
  EXPECT_EQ(body.points.position[0].x, y[0]);
  const int driven = static_cast<int>(n) - 1;  // follows its motion at t, not the state
  EXPECT_EQ(body.points.position[driven], circle(1.0).position);
  EXPECT_EQ(body.points.velocity[driven], circle(1.0).velocity);
  EXPECT_THROW(ElasticSystem::unpack_state(ode::Vector(3), 0.0, body), std::invalid_argument);
}

TEST(ElasticSystem, DerivativeFollowsNewtonPinsAndPrescribedMotion) {
  Random rng(22);
  const Body body = make_system_body(rng);
  const ElasticSystem system(body);
  const double t = 0.3;
  const ode::Vector y = system.pack_state();
  const ode::Vector dydt = derivative_at(system, t, y);
  std::vector<Vec2> force;
  std::vector<Vec2> x = body.points.position, v = body.points.velocity;
  x.back() = circle(t).position;
  v.back() = circle(t).velocity;
  accumulate_forces(body, x, v, t, force);
  const auto n = static_cast<Eigen::Index>(body.points.size());
  for (Eigen::Index p = 0; p < n; ++p) {
    const Vec2 dx{dydt[2 * p], dydt[2 * p + 1]}, dv{dydt[2 * (n + p)], dydt[2 * (n + p) + 1]};
    switch (body.points.kind[p]) {
      case PointKind::Free:
        EXPECT_EQ(dx, v[p]);
        test::expect_vec_near(dv, force[p] / body.points.mass[p], 1e-12);
        break;
      case PointKind::Pinned:
        EXPECT_EQ(dx, Vec2{});
        EXPECT_EQ(dv, Vec2{});
        break;
      case PointKind::Prescribed:
        EXPECT_EQ(dx, circle(t).velocity);
        EXPECT_EQ(dv, circle(t).acceleration);
        break;
    }
  }
  EXPECT_EQ(system.evaluations(), 1);
}

TEST(ElasticSystem, SparseJacobianMatchesFiniteDifferences) {
  Random rng(23);
  const Body body = make_system_body(rng);
  const ElasticSystem system(body);
  const double t = 0.4;
  const ode::Vector y = system.pack_state();
  const Eigen::MatrixXd analytic = analytic_jacobian(system, t, y);
  const Eigen::MatrixXd numeric = fd_jacobian(system, t, y);
  const double scale = numeric.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 1.0);
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6 * scale);
  // ∂v'/∂v carries the drag: -κ_d/m on the diagonal of a free point.
  const auto n = system.position_size();
  EXPECT_NEAR(analytic(n, n), -body.drag_coefficient / body.points.mass[0], 1e-15);
  // Rows of the pinned (6) and prescribed (7) points are zero.
  for (Eigen::Index p : {6, 7}) {
    for (Eigen::Index r : {2 * p, 2 * p + 1, n + 2 * p, n + 2 * p + 1}) {
      EXPECT_EQ(analytic.row(r).cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

TEST(ElasticSystem, JacobianReusesItsPatternAndFollowsTopologyChanges) {
  Random rng(24);
  Body body = make_system_body(rng);
  const ElasticSystem system(body);
  ode::Vector y = system.pack_state();
  ode::SparseMatrix jac;
  system.jacobian(0.0, y, jac);
  y += 0.05 * ode::Vector::Ones(y.size());
  system.jacobian(0.1, y, jac);  // same pattern, new values
  const Eigen::MatrixXd fresh = analytic_jacobian(ElasticSystem(body), 0.1, y);
  EXPECT_LT((Eigen::MatrixXd(jac) - fresh).cwiseAbs().maxCoeff(), 1e-12);
  body.add_linear_spring(0, 4, 3.0, 1.0);  // new coupling: the pattern must grow
  system.jacobian(0.1, y, jac);
  EXPECT_LT((Eigen::MatrixXd(jac) - fd_jacobian(system, 0.1, y)).cwiseAbs().maxCoeff(), 1e-4);
  const auto n = system.position_size();
  EXPECT_NE(jac.coeff(n, 2 * 4), 0.0);  // v_0x' now depends on x_4x
}

TEST(ElasticSystem, TwoPointSpringOscillatesAtSqrtTwoKOverM) {
  const double k = 5.0, m = 2.0, rest = 1.0, stretch = 0.1;
  Body body;
  body.add_point({0, 0}, m);
  body.add_point({rest + stretch, 0}, m);
  body.add_linear_spring(0, 1, k, rest);
  const ElasticSystem system(body);
  const ode::Vector y = system.pack_state();
  const ode::Vector dydt = derivative_at(system, 0.0, y);
  // Relative coordinate r = x_1 - x_0 obeys r'' = -(2k/m)(r - l_r).
  const double omega2 = 2.0 * k / m;
  EXPECT_NEAR(dydt[6] - dydt[4], -omega2 * stretch, 1e-14);
  EXPECT_NEAR(dydt[7] - dydt[5], 0.0, 1e-15);
  // Linearised about rest the only oscillating mode has eigenvalues ±i sqrt(2k/m).
  ElasticSystem::unpack_state(ode::Vector::Zero(8), 0.0, body);
  body.points.position[1] = {rest, 0.0};
  const Eigen::MatrixXd jac = analytic_jacobian(system, 0.0, system.pack_state());
  const Eigen::VectorXcd eig = Eigen::EigenSolver<Eigen::MatrixXd>(jac).eigenvalues();
  EXPECT_NEAR(eig.imag().cwiseAbs().maxCoeff(), std::sqrt(omega2), 1e-12);
  EXPECT_NEAR(eig.real().cwiseAbs().maxCoeff(), 0.0, 1e-6);  // zero modes are defective: O(√ε)
}

}  // namespace
}  // namespace jellysim::elastic
