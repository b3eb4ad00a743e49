// The one-pass Runge–Kutta stage sums (ode/stage_sum.hpp) against the term-by-term vector sums they
// replace: bit for bit, for every number of terms (zero weights skipped, more terms than one pass
// takes), on whole vectors, on segments and without the base vector.
#include "jellysim/ode/stage_sum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace jellysim::ode {
namespace {

/// The reference: out = y, then out += (h w_j) k_j for each non-zero weight, one vector at a time.
Vector term_by_term(const Vector& y, double h, const std::vector<double>& w, const std::vector<Vector>& k) {
  Vector out = y;
  for (std::size_t j = 0; j < w.size(); ++j) {
    if (w[j] != 0.0) out += (h * w[j]) * k[j];
  }
  return out;
}

TEST(StageSum, OnePassRoundsExactlyLikeTheTermByTermSums) {
  std::mt19937 engine(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Index n = 37;  // odd: the vectorised loops end with a scalar tail
  const auto random_vector = [&] {
    Vector v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = u(engine) * std::pow(10.0, 3.0 * u(engine));
    return v;
  };
  const Vector y = random_vector();
  for (std::size_t terms = 0; terms <= 19; ++terms) {
    std::vector<double> w;
    std::vector<Vector> k;
    for (std::size_t j = 0; j < terms; ++j) {
      w.push_back(j % 3 == 1 ? 0.0 : u(engine));  // some zero weights, as in Butcher tableaus
      k.push_back(random_vector());
    }
    const double h = 0.0137;
    const Vector expected = term_by_term(y, h, w, k);
    Vector whole;
    form_stage_state(y, h, w, k, whole);
    ASSERT_EQ(whole.size(), n);
    for (Eigen::Index i = 0; i < n; ++i) ASSERT_EQ(whole[i], expected[i]) << terms << " terms, entry " << i;
    Vector parts = Vector::Constant(n, -7.0);
    form_stage_segment(y, h, w, k, parts, 0, 10);
    form_stage_segment(y, h, w, k, parts, 10, 16);
    form_stage_segment(y, h, w, k, parts, 26, n - 26);
    for (Eigen::Index i = 0; i < n; ++i) ASSERT_EQ(parts[i], expected[i]) << terms << " terms, entry " << i;
    if (terms == 0) continue;
    const Vector expected_sum = term_by_term(Vector::Zero(n), h, w, k);  // the error estimate's form
    Vector sum;
    form_weighted_sum(h, w, k, sum);
    for (Eigen::Index i = 0; i < n; ++i) ASSERT_EQ(sum[i], expected_sum[i]) << terms << " terms, entry " << i;
  }
}

TEST(StageSum, LeavesEntriesOutsideTheSegmentAlone) {
  const Vector y = Vector::LinSpaced(8, 1.0, 8.0);
  const std::vector<Vector> k{Vector::Ones(8)};
  const std::vector<double> w{0.5};
  Vector out = Vector::Zero(8);
  form_stage_segment(y, 2.0, w, k, out, 3, 2);
  const Vector expected = (Vector(8) << 0, 0, 0, 5, 6, 0, 0, 0).finished();
  EXPECT_EQ(out, expected);
}

}  // namespace
}  // namespace jellysim::ode
