// Pressure solvers and projection: divergence-free results for every boundary mix, SOR and
// multigrid agree, multigrid cost per digit does not grow with the grid.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "jellysim/fluid/direct_poisson.hpp"
#include "jellysim/fluid/fft_poisson.hpp"
#include "jellysim/fluid/multigrid.hpp"
#include "jellysim/fluid/projection.hpp"
#include "jellysim/fluid/sor.hpp"
#include "fluid_test_util.hpp"

namespace jellysim::fluid {
namespace {

using testing::boundary_mixes;
using testing::Mix;
using testing::randomise;

class ProjectionMixes : public ::testing::TestWithParam<std::string> {};

TEST_P(ProjectionMixes, DivergenceVanishesForEveryBoundaryMix) {
  const MacGrid g(24, 16, 1.5, 1.0, {0.2, -0.1});
  PressureSolverSettings ps;
  ps.relative_tolerance = 1e-13;
  ps.max_iterations = 20000;
  for (const Mix& mix : boundary_mixes()) {
    FlowState s(g);
    randomise(s.velocity, 7);
    apply_velocity_boundaries(s.velocity, mix.b);
    const double before = max_divergence(s.velocity);
    Projector projector(make_pressure_solver(GetParam(), ps));
    const PressureSolveReport r = projector.project(s, mix.b, 0.01, 1000.0);
    EXPECT_TRUE(r.converged) << mix.name;
    EXPECT_LT(max_divergence(s.velocity) / before, 1e-10) << mix.name << " with " << GetParam();
  }
}

INSTANTIATE_TEST_SUITE_P(PressureSolvers, ProjectionMixes, ::testing::Values("sor", "multigrid", "direct", "fft"));

// The direct (sparse Cholesky) and transform (FFT) solvers give the multigrid solution to
// round-off on every boundary mix; re-solving on the same operator reuses the factor.
TEST(PressureSolvers, DirectFftAndMultigridAgreeOnEveryBoundaryMix) {
  const MacGrid g(30, 22, 2.0, 1.5);
  PressureSolverSettings ps;
  ps.relative_tolerance = 1e-13;
  ps.max_iterations = 1000;
  for (const Mix& mix : boundary_mixes()) {
    const PoissonOperator op(g, mix.b);
    std::vector<double> b(static_cast<std::size_t>(op.size()));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    for (double& x : b) x = d(rng);
    std::vector<double> p_direct(b.size(), 0.0), p_mg(b.size(), 0.0);
    DirectPoissonSolver direct;
    MultigridSolver mg(ps);
    const PressureSolveReport r = direct.solve(op, b, p_direct);
    EXPECT_TRUE(mg.solve(op, b, p_mg).converged) << mix.name;
    EXPECT_LT(r.residual_max, 1e-10 * r.rhs_max) << mix.name;
    double diff = 0.0;
    for (std::size_t k = 0; k < b.size(); ++k) diff = std::max(diff, std::abs(p_direct[k] - p_mg[k]));
    EXPECT_LT(diff / max_abs(p_mg), 1e-10) << mix.name;
    std::vector<double> again(b.size(), 0.0);
    direct.solve(op, b, again);
    EXPECT_EQ(again, p_direct) << mix.name;
    // The transform solver gives the same solution (every mix here has uniform cells).
    std::vector<double> p_fft(b.size(), 0.0);
    FftPoissonSolver fft;
    fft.solve(op, b, p_fft);
    std::vector<double> compatible = b;
    if (op.singular()) remove_mean(compatible);
    EXPECT_LT(op.residual_max(p_fft, compatible), 1e-10 * max_abs(compatible)) << mix.name;
    double fft_diff = 0.0;
    for (std::size_t k = 0; k < b.size(); ++k) fft_diff = std::max(fft_diff, std::abs(p_fft[k] - p_mg[k]));
    EXPECT_LT(fft_diff / max_abs(p_mg), 1e-10) << mix.name << " (fft)";
  }
}

TEST(PressureSolvers, SorAndMultigridAgreeOnEveryBoundaryMix) {
  const MacGrid g(32, 24, 2.0, 1.5);
  PressureSolverSettings ps;
  ps.relative_tolerance = 1e-12;
  ps.max_iterations = 50000;
  for (const Mix& mix : boundary_mixes()) {
    const PoissonOperator op(g, mix.b);
    std::vector<double> b(static_cast<std::size_t>(op.size()));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    for (double& x : b) x = d(rng);
    std::vector<double> p_sor(b.size(), 0.0), p_mg(b.size(), 0.0);
    SorSolver sor(ps);
    MultigridSolver mg(ps);
    EXPECT_TRUE(sor.solve(op, b, p_sor).converged) << mix.name;
    EXPECT_TRUE(mg.solve(op, b, p_mg).converged) << mix.name;
    double diff = 0.0;
    for (std::size_t k = 0; k < b.size(); ++k) diff = std::max(diff, std::abs(p_sor[k] - p_mg[k]));
    EXPECT_LT(diff / max_abs(p_mg), 1e-9) << mix.name;
  }
}

TEST(PressureSolvers, MultigridCyclesDoNotGrowWithTheGrid) {
  PressureSolverSettings ps;
  ps.relative_tolerance = 1e-8;
  std::vector<int> cycles;
  for (int n : {32, 64, 128, 256}) {
    const MacGrid g(n, n, 1.0, 1.0);
    const PoissonOperator op(g, Boundaries::all(BoundaryType::no_slip));
    std::vector<double> b(static_cast<std::size_t>(op.size()));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        b[static_cast<std::size_t>(j) * n + i] = std::cos(3.0 * (i + 0.5) / n) * std::sin(7.0 * (j + 0.5) / n) + ((i * 7 + j * 3) % 5 - 2);
    std::vector<double> p(b.size(), 0.0);
    MultigridSolver mg(ps);
    const PressureSolveReport r = mg.solve(op, b, p);
    EXPECT_TRUE(r.converged);
    cycles.push_back(r.iterations);
  }
  EXPECT_LE(cycles.back(), cycles.front() + 3);
  EXPECT_LE(cycles.back(), 15);
}

TEST(PressureSolvers, UnknownNameIsRejected) {
  EXPECT_THROW(make_pressure_solver("jacobi"), std::invalid_argument);
}

TEST(Projection, PressureHasZeroMeanWhenOnlyDefinedUpToAConstant) {
  const MacGrid g(16, 16, 1.0, 1.0);
  FlowState s(g);
  randomise(s.velocity, 11);
  const Boundaries b = Boundaries::all(BoundaryType::no_slip);
  apply_velocity_boundaries(s.velocity, b);
  Projector projector(make_pressure_solver("multigrid"));
  projector.project(s, b, 0.1, 1.0);
  double sum = 0.0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) sum += s.pressure(i, j);
  EXPECT_NEAR(sum / 256.0, 0.0, 1e-10);
}

}  // namespace
}  // namespace jellysim::fluid
