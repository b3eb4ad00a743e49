// Richardson extrapolation and Roache's GCI (studies/grid_convergence.hpp) on sequences whose
// answer is known: f(h) = f₀ + C h^p exactly recovers p and f₀, for equal and unequal refinement
// ratios; Celik et al.'s procedure on oscillatory and degenerate sequences.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "jellysim/studies/grid_convergence.hpp"

namespace jellysim::studies {
namespace {

std::vector<double> power_law(const std::vector<double>& h, double f0, double c, double p) {
  std::vector<double> f;
  for (double x : h) f.push_back(f0 + c * std::pow(x, p));
  return f;
}

TEST(GridConvergence, RecoversOrderAndLimitOfAPowerLaw) {
  const std::vector<double> h{0.04, 0.02, 0.01};
  for (double p : {1.0, 1.6, 2.0}) {
    const GridConvergence g = grid_convergence(h, power_law(h, 3.0, 5.0, p));
    ASSERT_TRUE(g.observed_order && g.extrapolated && g.gci_fine);
    EXPECT_NEAR(*g.observed_order, p, 1e-9);
    EXPECT_NEAR(*g.extrapolated, 3.0, 1e-9);
    EXPECT_FALSE(g.oscillatory);
    // GCI = 1.25 |e21| / (r^p − 1), the finest grid's relative error times 1.25 when p is exact.
    const double finest = 3.0 + 5.0 * std::pow(0.01, p);
    EXPECT_NEAR(*g.gci_fine, 1.25 * (finest - 3.0) / finest, 1e-9);
    EXPECT_NEAR(*g.relative_change_finest, 5.0 * (std::pow(0.02, p) - std::pow(0.01, p)) / finest, 1e-12);
  }
}

TEST(GridConvergence, HandlesUnequalRefinementRatios) {
  // Celik et al.'s fixed-point iteration for p when r21 ≠ r32.
  const std::vector<double> h{0.05, 0.03, 0.01};
  const GridConvergence g = grid_convergence(h, power_law(h, -1.0, 2.0, 1.3));
  ASSERT_TRUE(g.observed_order && g.extrapolated);
  EXPECT_NEAR(*g.observed_order, 1.3, 1e-8);
  EXPECT_NEAR(*g.extrapolated, -1.0, 1e-8);
}

TEST(GridConvergence, UsesTheThreeFinestGridsAndFlagsOscillation) {
  // A coarse outlier does not matter; alternating differences are flagged.
  const std::vector<double> h{0.08, 0.04, 0.02, 0.01};
  std::vector<double> f = power_law(h, 1.0, 1.0, 2.0);
  f[0] = 100.0;
  EXPECT_NEAR(*grid_convergence(h, f).observed_order, 2.0, 1e-9);
  const GridConvergence o = grid_convergence(std::vector<double>{0.04, 0.02, 0.01}, std::vector<double>{1.0, 1.2, 1.1});
  EXPECT_TRUE(o.oscillatory);
  ASSERT_TRUE(o.observed_order);
  EXPECT_NEAR(*o.observed_order, 1.0, 1e-9);  // |0.2 / 0.1| = 2¹
}

TEST(GridConvergence, TwoGridsGiveOnlyTheChange) {
  const GridConvergence g = grid_convergence(std::vector<double>{0.02, 0.01}, std::vector<double>{0.9, 1.0});
  EXPECT_FALSE(g.observed_order || g.extrapolated || g.gci_fine);
  EXPECT_NEAR(*g.relative_change_finest, 0.1, 1e-12);
  const GridConvergence same = grid_convergence(std::vector<double>{0.04, 0.02, 0.01}, std::vector<double>{1.0, 2.0, 2.0});
  EXPECT_FALSE(same.observed_order);  // the two finest agree exactly: nothing to extrapolate
  EXPECT_EQ(*same.relative_change_finest, 0.0);
}

TEST(GridConvergence, RefusesSpacingsThatDoNotDecrease) {
  EXPECT_THROW(grid_convergence(std::vector<double>{0.01, 0.02}, std::vector<double>{1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(grid_convergence(std::vector<double>{0.02, 0.01}, std::vector<double>{1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::studies
