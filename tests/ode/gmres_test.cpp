// Restarted GMRES (ode/gmres.hpp), used by the semi-implicit coupling and the Jacobian-free
// backward Euler.
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/ode/gmres.hpp"

namespace jellysim::ode {
namespace {

TEST(Gmres, SolvesASmallNonsymmetricSystem) {
  Eigen::MatrixXd a(3, 3);
  a << 4, 1, 0, 2, 5, 1, 0, 1, 3;
  const Eigen::VectorXd b = Eigen::Vector3d(1, 2, 3);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  const GmresReport r = gmres([&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = a * in; }, b, x, 1e-12, 50);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((a * x - b).norm(), 1e-11);
}

// GMRES from zero hands back the weights of its basis vectors: the solution is their combination
// (what the semi-implicit coupling uses to build the end-of-step force field from kept by-products),
// it solves the system, and it needs one operator application per iteration and no more.
TEST(Gmres, FromZeroReturnsTheSolutionAsACombinationOfTheVectorsItApplied) {
  const int n = 12;
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) += 0.3 * std::sin(1.0 + 3.0 * i + 7.0 * j) / n;  // I + rank 2: GMRES needs 3 steps
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.5 * i);
  std::vector<Eigen::VectorXd> applied;
  Eigen::VectorXd x, coefficients;
  const GmresReport r = gmres_from_zero(
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
        applied.push_back(in);
        out = a * in;
      },
      b, x, coefficients, 1e-12, 100);
  ASSERT_TRUE(r.converged);
  EXPECT_FALSE(r.restarted);
  ASSERT_TRUE(r.coefficients_valid);
  EXPECT_EQ(static_cast<int>(applied.size()), r.iterations);
  ASSERT_EQ(coefficients.size(), r.iterations);
  Eigen::VectorXd combined = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < coefficients.size(); ++k) combined += coefficients[k] * applied[static_cast<std::size_t>(k)];
  EXPECT_LT((combined - x).norm(), 1e-13 * x.norm());
  EXPECT_LT((a * x - b).norm(), 1e-11 * b.norm());
  EXPECT_LT(r.relative_residual, 1e-12);
  // Stopped before convergence, or restarted: no coefficients, but x is still GMRES's result.
  Eigen::VectorXd x2, c2;
  const GmresReport early = gmres_from_zero([&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = a * in; }, b,
                                            x2, c2, 1e-12, 2);
  EXPECT_FALSE(early.coefficients_valid);
  EXPECT_EQ(c2.size(), 0);
  EXPECT_LT((a * x2 - b).norm(), b.norm());
  Eigen::VectorXd x3, c3;
  const GmresReport restarted = gmres_from_zero([&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = a * in; },
                                                b, x3, c3, 1e-12, 100, 2);
  EXPECT_TRUE(restarted.converged);
  EXPECT_TRUE(restarted.restarted);
  EXPECT_FALSE(restarted.coefficients_valid);
  EXPECT_LT((a * x3 - b).norm(), 1e-11 * b.norm());
}

}  // namespace
}  // namespace jellysim::ode
