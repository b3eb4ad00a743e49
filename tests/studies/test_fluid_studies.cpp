// The fluid validation studies of §8.1.3 (studies/): Taylor-Green convergence orders and the
// driven cavity against Ghia, Ghia & Shin (1982).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/studies/driven_cavity.hpp"
#include "jellysim/studies/taylor_green.hpp"

namespace jellysim::studies {
namespace {

TEST(TaylorGreen, EulerianConvergesAtSecondOrderInSpace) {
  TaylorGreenSettings s;
  s.solvers = {"eulerian"};
  s.grids = {16, 32, 64};
  const TaylorGreenResult r = run_taylor_green(s);
  for (const TaylorGreenRun& run : r.runs)
    std::printf("  eulerian %3d²: dt %.4g, %d steps, L2 error %.3e, max error %.3e\n", run.cells, run.dt_s,
                run.steps, run.error_l2, run.error_max);
  ASSERT_EQ(r.orders.size(), 2u);
  EXPECT_GE(r.orders.back().order_l2, 1.8);
  EXPECT_GE(r.orders.back().order_max, 1.8);
  EXPECT_GE(r.fitted_order_l2("eulerian"), 1.8);
}

TEST(TaylorGreen, SemiLagrangianConverges) {
  TaylorGreenSettings s;
  s.solvers = {"semi-lagrangian"};
  s.grids = {16, 32, 64};
  const TaylorGreenResult r = run_taylor_green(s);
  for (const TaylorGreenRun& run : r.runs)
    std::printf("  semi-lagrangian %3d²: L2 error %.3e\n", run.cells, run.error_l2);
  EXPECT_GE(r.fitted_order_l2("semi-lagrangian"), 0.8);
  EXPECT_LT(r.runs.back().error_l2, 0.05);
}

TEST(DrivenCavity, EulerianRe100MatchesGhiaGhiaShinAtEveryTabulatedPoint) {
  DrivenCavitySettings s;
  s.solver = "eulerian";
  s.reynolds = 100.0;
  s.cells = 64;
  const DrivenCavityResult r = run_driven_cavity(s);
  std::printf("  64² Re=100: t=%.2f s simulated, %d steps, steady=%d, wall %.2f s, max|u-ghia| %.4f, max|v-ghia| %.4f\n",
              r.simulated_time_s, r.steps, r.steady, r.wall_time_s, r.ghia->max_abs_u_error, r.ghia->max_abs_v_error);
  ASSERT_TRUE(r.ghia.has_value());
  EXPECT_TRUE(r.steady);
  for (std::size_t k = 0; k < fluid::kGhiaRe100CentrelineU.size(); ++k)
    EXPECT_LT(std::abs(r.ghia->u_error[k]), 0.02) << "u at y=" << fluid::kGhiaRe100CentrelineU[k].position;
  for (std::size_t k = 0; k < fluid::kGhiaRe100CentrelineV.size(); ++k)
    EXPECT_LT(std::abs(r.ghia->v_error[k]), 0.02) << "v at x=" << fluid::kGhiaRe100CentrelineV[k].position;
  EXPECT_LT(r.max_divergence_per_s, 1e-5);
}

TEST(DrivenCavity, SemiLagrangianStaysDivergenceFreeAndCirculates) {
  DrivenCavitySettings s;
  s.solver = "semi-lagrangian";
  s.cells = 32;
  s.max_time_s = 5.0;
  const DrivenCavityResult r = run_driven_cavity(s);
  EXPECT_LT(r.max_divergence_per_s, 1e-4);
  // The primary vortex: flow along the lid direction near the top, back-flow below the centre.
  EXPECT_GT(r.final_state.velocity.u.sample({0.5, 0.9}), 0.1);
  EXPECT_LT(r.final_state.velocity.u.sample({0.5, 0.3}), -0.05);
}

}  // namespace
}  // namespace jellysim::studies
