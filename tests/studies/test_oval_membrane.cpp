// The oval membrane test (thesis §8.1.3, Figures 8.8/8.9; Stockie & Wetton).
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/studies/oval_membrane.hpp"

namespace jellysim::studies {
using coupling::Scheme;
namespace {

OvalMembraneSettings thesis_settings(const std::string& solver) {
  OvalMembraneSettings s;  // 1 × 1 box, 30 × 30, ν = 0, κ_l = 10, Δt = 0.002 (Fig. 8.9)
  s.solver = solver;
  s.coupling.scheme = Scheme::explicit_euler;
  s.duration_s = 3.0;
  s.frame_interval_s = 0.5;
  return s;
}

TEST(OvalMembrane, EulerianRelaxesTowardACircleAndLosesLessThanThreePercent) {
  const MembraneRun run = run_oval_membrane(thesis_settings("eulerian"));
  ASSERT_TRUE(run.failure.empty()) << run.failure;
  const MembraneFrame& first = run.frames.front();
  const MembraneFrame& last = run.frames.back();
  EXPECT_NEAR(first.aspect_ratio, 0.35 / 0.25, 1e-3);
  EXPECT_LT(last.aspect_ratio, 1.1);
  const double lost = 1.0 - last.area / first.area;
  EXPECT_LT(std::abs(lost), 0.03) << "area lost " << lost;
}

TEST(OvalMembrane, SemiImplicitCouplingIsStableAtTenTimesTheStep) {
  OvalMembraneSettings s = thesis_settings("semi-lagrangian");
  s.coupling.scheme = Scheme::semi_implicit;
  s.dt_s = 0.02;
  const MembraneRun run = run_oval_membrane(s);
  ASSERT_TRUE(run.failure.empty()) << run.failure;
  EXPECT_LT(run.frames.back().aspect_ratio, 1.1);
  EXPECT_LT(std::abs(1.0 - run.frames.back().area / run.frames.front().area), 0.05);
}

}  // namespace
}  // namespace jellysim::studies
