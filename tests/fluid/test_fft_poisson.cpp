// The transform (FFT) pressure solver against the direct one (sparse Cholesky) on every per-axis
// side combination, odd, even, non-square and tiny grids, with each of its methods; and
// bit-identical results between solves.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "jellysim/fluid/direct_poisson.hpp"
#include "jellysim/fluid/fft_poisson.hpp"

namespace jellysim::fluid {
namespace {

using PB = PressureBoundary;

struct AxisSides {
  PB low, high;
  const char* name;
};

// Every combination one axis can have (periodic sides come in pairs).
constexpr std::array<AxisSides, 5> kAxisSides = {{
    {PB::periodic, PB::periodic, "P"},
    {PB::neumann, PB::neumann, "NN"},
    {PB::neumann, PB::dirichlet, "ND"},
    {PB::dirichlet, PB::neumann, "DN"},
    {PB::dirichlet, PB::dirichlet, "DD"},
}};

constexpr std::array<FftPoissonMethod, 3> kMethods = {
    FftPoissonMethod::rows_then_tridiagonal, FftPoissonMethod::r2r_rows_then_tridiagonal, FftPoissonMethod::r2r_2d};

const char* method_name(FftPoissonMethod m) {
  switch (m) {
    case FftPoissonMethod::rows_then_tridiagonal: return "rows_then_tridiagonal";
    case FftPoissonMethod::r2r_rows_then_tridiagonal: return "r2r_rows_then_tridiagonal";
    case FftPoissonMethod::r2r_2d: return "r2r_2d";
  }
  return "?";
}

std::vector<double> random_rhs(int n, unsigned seed) {
  std::vector<double> b(static_cast<std::size_t>(n));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (double& x : b) x = d(rng);
  return b;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

struct GridSize {
  int nx, ny;
};

// Odd and even, non-square, the main scene's 60², and the smallest sizes (1 and 2 cells).
const std::vector<GridSize> kSizes = {{37, 50}, {50, 37}, {60, 60}, {16, 9}, {1, 6}, {6, 1}, {2, 5}, {5, 2}, {2, 2}, {3, 1}};

TEST(FftPoisson, AgreesWithTheDirectSolverOnEverySideCombinationAndGrid) {
  for (const GridSize& size : kSizes)
    for (const AxisSides& x : kAxisSides)
      for (const AxisSides& y : kAxisSides) {
        // Anisotropic cells (Δx ≠ Δy) so that the two axes cannot be confused.
        const PoissonOperator op(size.nx, size.ny, 2.0 / size.nx, 1.5 / size.ny, {x.low, x.high, y.low, y.high});
        const std::string label = std::to_string(size.nx) + "x" + std::to_string(size.ny) + " x:" + x.name + " y:" + y.name;
        if (op.size() == 1 && op.singular()) continue;  // 1 cell, no Dirichlet side: ∇² = 0, nothing to solve
        const std::vector<double> b = random_rhs(op.size(), 17);
        std::vector<double> p_direct(b.size(), 0.0);
        DirectPoissonSolver direct;
        direct.solve(op, b, p_direct);
        std::vector<double> compatible = b;
        if (op.singular()) remove_mean(compatible);
        const double scale = std::max(max_abs(p_direct), 1e-300);
        for (FftPoissonMethod method : kMethods) {
          FftPoissonSolver fft(method);
          std::vector<double> p(b.size(), 0.0);
          const PressureSolveReport r = fft.solve(op, b, p);
          EXPECT_TRUE(r.converged);
          EXPECT_LE(max_difference(p, p_direct), 1e-10 * scale) << label << " " << method_name(method);
          EXPECT_LE(op.residual_max(p, compatible), 1e-10 * max_abs(compatible)) << label << " " << method_name(method);
        }
      }
}

TEST(FftPoisson, SingularProblemsGetTheMeanFreeSolution) {
  for (const GridSize& size : {GridSize{37, 50}, GridSize{60, 60}, GridSize{1, 6}})
    for (int x = 0; x < 2; ++x)
      for (int y = 0; y < 2; ++y) {  // periodic or Neumann–Neumann on each axis
        const PoissonOperator op(size.nx, size.ny, 1.0 / size.nx, 1.0 / size.ny,
                                 {kAxisSides[x].low, kAxisSides[x].high, kAxisSides[y].low, kAxisSides[y].high});
        ASSERT_TRUE(op.singular());
        const std::vector<double> b = random_rhs(op.size(), 23);  // not compatible: the mean is removed
        std::vector<double> p(b.size(), 0.0);
        FftPoissonSolver fft;
        fft.solve(op, b, p);
        double sum = 0.0;
        for (double v : p) sum += v;
        EXPECT_LE(std::abs(sum) / static_cast<double>(p.size()), 1e-13 * max_abs(p));
      }
}

TEST(FftPoisson, RepeatedSolvesAreBitIdentical) {
  for (const AxisSides& x : kAxisSides)
    for (const AxisSides& y : kAxisSides) {
      const PoissonOperator op(37, 50, 0.02, 0.03, {x.low, x.high, y.low, y.high});
      const std::vector<double> b = random_rhs(op.size(), 29);
      FftPoissonSolver first, second;
      std::vector<double> p1(b.size(), 0.0), p2(b.size(), 1.0), p3(b.size(), -1.0);
      first.solve(op, b, p1);
      first.solve(op, b, p2);   // the same plan again
      second.solve(op, b, p3);  // a fresh plan
      EXPECT_EQ(p1, p2) << x.name << " " << y.name;
      EXPECT_EQ(p1, p3) << x.name << " " << y.name;
    }
}

TEST(FftPoisson, ReplansWhenTheProblemChanges) {
  FftPoissonSolver fft;
  DirectPoissonSolver direct;
  for (const GridSize& size : {GridSize{60, 60}, GridSize{37, 50}, GridSize{60, 60}}) {
    const PoissonOperator op(size.nx, size.ny, 0.01, 0.01, {PB::neumann, PB::neumann, PB::neumann, PB::dirichlet});
    const std::vector<double> b = random_rhs(op.size(), 31);
    std::vector<double> p(b.size(), 0.0), p_direct(b.size(), 0.0);
    fft.solve(op, b, p);
    direct.solve(op, b, p_direct);
    EXPECT_LE(max_difference(p, p_direct), 1e-10 * max_abs(p_direct));
  }
}

}  // namespace
}  // namespace jellysim::fluid
