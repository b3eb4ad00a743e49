// The driven cavity with the second-order schemes of issue 20 against Ghia, Ghia & Shin (1982):
// tolerances the thesis's first-order schemes fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "jellysim/studies/driven_cavity.hpp"

namespace jellysim::studies {
namespace {

DrivenCavityResult cavity(const std::string& solver, fluid::ConvectionScheme convection,
                          fluid::AdvectionScheme advection, double re, int cells, double steady_tolerance) {
  DrivenCavitySettings s;
  s.solver = solver;
  s.reynolds = re;
  s.cells = cells;
  s.convection = convection;
  s.advection = advection;
  s.steady_tolerance = steady_tolerance;
  const DrivenCavityResult r = run_driven_cavity(s);
  std::printf("  %s Re %.0f %d²: t = %.1f s, %d steps, steady %d, wall %.1f s, max |u - Ghia| %.4f, max |v - Ghia| %.4f, "
              "vortex (%.4f, %.4f) psi %.5f\n",
              solver.c_str(), re, cells, r.simulated_time_s, r.steps, r.steady, r.wall_time_s,
              r.ghia ? r.ghia->max_abs_u_error : -1.0, r.ghia ? r.ghia->max_abs_v_error : -1.0,
              r.primary_vortex.centre_m.x, r.primary_vortex.centre_m.y, r.primary_vortex.stream_function_m2_per_s);
  return r;
}

// Re 100 on 64², semi-Lagrangian: measured largest differences u 0.0028, v 0.0071 with
// MacCormack (steady to 1e-6 at t = 22 s), against 0.0146 and 0.0134 with linear advection.
TEST(CavitySchemes, SemiLagrangianMacCormackMatchesGhiaAtRe100On64Cells) {
  const DrivenCavityResult r = cavity("semi-lagrangian", fluid::ConvectionScheme::donor_cell,
                                      fluid::AdvectionScheme::maccormack, 100.0, 64, 1e-6);
  ASSERT_TRUE(r.ghia.has_value());
  EXPECT_TRUE(r.steady);
  EXPECT_LT(r.ghia->max_abs_u_error, 0.0045);
  EXPECT_LT(r.ghia->max_abs_v_error, 0.009);
  const DrivenCavityResult linear = cavity("semi-lagrangian", fluid::ConvectionScheme::donor_cell,
                                           fluid::AdvectionScheme::linear, 100.0, 64, 1e-5);
  EXPECT_GT(linear.ghia->max_abs_u_error, 0.012);  // the tolerance above fails the thesis's scheme
}

// Re 100 on 64², Eulerian with Koren's scheme: u 0.0048, v 0.0083 measured (the γ blend is nearly
// central here, 0.0037 and 0.0071: at Re 100 this grid's error is not the convection's).
TEST(CavitySchemes, EulerianKorenMatchesGhiaAtRe100On64Cells) {
  const DrivenCavityResult r =
      cavity("eulerian", fluid::ConvectionScheme::koren, fluid::AdvectionScheme::linear, 100.0, 64, 1e-6);
  ASSERT_TRUE(r.ghia.has_value());
  EXPECT_TRUE(r.steady);
  EXPECT_LT(r.ghia->max_abs_u_error, 0.007);
  EXPECT_LT(r.ghia->max_abs_v_error, 0.011);
}

// Re 1000 on 128² (Release only: about 40 s): MacCormack measured u 0.0082, v 0.0061, the primary
// vortex at (0.5315, 0.5662), ψ_min −0.11662 against Ghia's (0.5313, 0.5625), −0.117929. The
// γ-blend Eulerian solver is off by 0.065 here (issue 20).
TEST(SlowCavitySchemes, SemiLagrangianMacCormackMatchesGhiaAtRe1000On128Cells) {
  const DrivenCavityResult r = cavity("semi-lagrangian", fluid::ConvectionScheme::donor_cell,
                                      fluid::AdvectionScheme::maccormack, 1000.0, 128, 1e-5);
  ASSERT_TRUE(r.ghia.has_value());
  EXPECT_TRUE(r.steady);
  EXPECT_LT(r.ghia->max_abs_u_error, 0.011);
  EXPECT_LT(r.ghia->max_abs_v_error, 0.009);
  EXPECT_NEAR(r.primary_vortex.centre_m.x, 0.5313, 0.003);
  EXPECT_NEAR(r.primary_vortex.centre_m.y, 0.5625, 0.006);
  EXPECT_NEAR(r.primary_vortex.stream_function_m2_per_s, -0.117929, 0.002);
}

}  // namespace
}  // namespace jellysim::studies
