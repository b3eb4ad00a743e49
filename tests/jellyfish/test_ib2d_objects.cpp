// IB2d structures in the tank: the Hoover–Miller bell generated as IB2d's Make_Jelly_Geometry.m
// describes it (checked against the counts and values of IB2d's jelly256.* files; its files read back
// through the importer: tests/io/test_ib2d_files.cpp), and an IB2d structure turned into markers, springs,
// beams and targets with IB2d's force densities times the marker spacing ds.
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/elastic/spring_assembly.hpp"
#include "jellysim/jellyfish/hoover_miller.hpp"
#include "jellysim/jellyfish/ib2d_object.hpp"

namespace jellysim::jellyfish {
namespace {

// IB2d's jelly256.* (Re150/Res_256_320x96): 245 vertices (159 bell, 2 × 19 muscle, 48 blocker),
// 177 springs (158 bell at κ/ds = 6.4e8, then the 19 muscles at 1e5), 157 non-invariant beams
// at 2.5e5/ds³ = 6.5536e10, targets 198 … 245 at 2.5e6; point 80 at (1.02713, 1.75630); the first
// beam "1 2 3 6.5536e10 2.476e-05 -7.311e-04".
TEST(HooverMiller, MatchesIb2dsJelly256Files) {
  const HooverMillerBell bell = hoover_miller_bell({});
  const elastic::Ib2dStructure& s = bell.structure;
  EXPECT_EQ(s.vertices.size(), 245u);
  EXPECT_EQ(bell.bell_points, 159);
  EXPECT_EQ(bell.muscle_points, 19);
  EXPECT_EQ(bell.target_points, 48);
  ASSERT_EQ(s.springs.size(), 177u);
  EXPECT_EQ(bell.first_muscle_spring, 158);
  EXPECT_DOUBLE_EQ(s.springs[0].stiffness, 6.4e8);
  EXPECT_DOUBLE_EQ(s.springs[158].stiffness, 1e5);
  EXPECT_EQ(s.springs[158].master, 159);  // "160 179" in the file (from 1)
  EXPECT_EQ(s.springs[158].slave, 178);
  ASSERT_EQ(s.non_invariant_beams.size(), 157u);
  EXPECT_DOUBLE_EQ(s.non_invariant_beams[0].stiffness, 6.5536e10);
  EXPECT_NEAR(s.non_invariant_beams[0].curvature.x, 2.476e-05, 5e-9);
  EXPECT_NEAR(s.non_invariant_beams[0].curvature.y, -7.311e-04, 5e-8);
  ASSERT_EQ(s.targets.size(), 48u);
  EXPECT_EQ(s.targets.front().point, 197);
  EXPECT_EQ(s.targets.back().point, 244);
  EXPECT_DOUBLE_EQ(s.targets.front().stiffness, 2.5e6);
  EXPECT_DOUBLE_EQ(s.vertices[0].x, 1.5);
  EXPECT_DOUBLE_EQ(s.vertices[0].y, 2.75);
  EXPECT_NEAR(s.vertices[79].x, 1.02713, 5e-6);
  EXPECT_NEAR(s.vertices[79].y, 1.75630, 5e-6);
  EXPECT_NEAR(s.vertices[244].y, 9.9375, 1e-12);
  // The muscle markers start on the bell's lowest points, 62 … 80 and 141 … 159 (from 1).
  EXPECT_EQ(s.vertices[159], s.vertices[61]);
  EXPECT_EQ(s.vertices[178], s.vertices[140]);
}

// At t = 0 the bell is stress-free: every spring at its rest length, every beam at its preferred
// second difference (the muscles, rest length 0 in the file, are set by their schedule).
TEST(HooverMiller, StartsStressFree) {
  const HooverMillerBell bell = hoover_miller_bell({.resolution = 64});
  const elastic::Ib2dStructure& s = bell.structure;
  for (int k = 0; k < bell.first_muscle_spring; ++k) {
    const auto& sp = s.springs[static_cast<std::size_t>(k)];
    EXPECT_NEAR(norm(s.vertices[static_cast<std::size_t>(sp.slave)] - s.vertices[static_cast<std::size_t>(sp.master)]),
                sp.rest_length, 1e-15);
    // Markers about ds = half a mesh width apart (IB2d's angle steps ds/|dX/dθ| overshoot by up to 2.3 %).
    EXPECT_NEAR(sp.rest_length, 4.0 / 64, 0.025 * 4.0 / 64);
  }
  for (const auto& b : s.non_invariant_beams) {
    const Vec2 d = s.vertices[static_cast<std::size_t>(b.left)] - 2.0 * s.vertices[static_cast<std::size_t>(b.middle)] +
                   s.vertices[static_cast<std::size_t>(b.right)];
    EXPECT_EQ(d, b.curvature);
  }
  EXPECT_THROW(hoover_miller_bell({.resolution = 100}), std::invalid_argument);
}

// A 5-point structure in a body: a spring, a non-invariant beam, a torsional beam and a target,
// each force the hand-computed IB2d force density times ds.
TEST(Ib2dObject, ForcesAreIb2dsForceDensitiesTimesTheMarkerSpacing) {
  Ib2dObjectSpec spec;
  spec.name = "test";
  elastic::Ib2dStructure& s = spec.structure;
  s.vertices = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}};
  s.springs = {{0, 1, 10.0, 0.5}};                           // stretched by 0.5: pulls 0 toward 1
  s.non_invariant_beams = {{1, 2, 3, 4.0, Vec2{0.0, 0.1}}}; // D = (0, 0) − (0, 0.1)
  s.targets = {{4, 7.0}};
  const double ds = 0.25;
  elastic::Body body;
  const Ib2dParts parts = add_ib2d_object(spec, ds, body);
  ASSERT_EQ(body.points.size(), 6u);  // 5 markers + the target's pinned anchor
  EXPECT_EQ(body.points.kind[5], elastic::PointKind::Pinned);
  body.points.position[4] += Vec2{0.0, 0.2};  // the target point leaves its anchor
  std::vector<Vec2> f(body.points.size());
  elastic::add_spring_forces(body, body.points.position, f);
  // Spring: k (l − RL) x̂ = 10 · 0.5 = 5 toward point 1, times ds.
  EXPECT_NEAR(f[0].x, 5.0 * ds, 1e-14);
  // Beam: F_l = F_r = −k (D − C) = −4 · (0, −0.1) = (0, 0.4), F_m = (0, −0.8), times ds; point 1
  // also has the spring's −5 ds along x.
  EXPECT_NEAR(f[1].y, 0.4 * ds, 1e-14);
  EXPECT_NEAR(f[1].x, -5.0 * ds, 1e-14);
  EXPECT_NEAR(f[2].y, -0.8 * ds, 1e-14);
  EXPECT_NEAR(f[3].y, 0.4 * ds, 1e-14);
  // Target: k (X_target − X) = 7 · (0, −0.2), times ds.
  EXPECT_NEAR(f[4].y, -1.4 * ds, 1e-14);
  EXPECT_NEAR(f[4].x, 0.0, 1e-14);
  EXPECT_EQ(parts.tethers.size(), 1u);
}

// IB2d's update_Springs.m for the jellyfish: rest length |cos(π f t)| on the muscle springs.
TEST(Ib2dObject, SchedulesSetTheirColumnFromTheLaw) {
  Ib2dObjectSpec spec;
  spec.name = "test";
  spec.structure.vertices = {{0, 0}, {1, 0}, {2, 0}};
  spec.structure.springs = {{0, 1, 10.0, 1.0}, {1, 2, 10.0, 1.0}};
  SpringSchedule rest;
  rest.first = rest.last = 1;
  rest.law = ScheduleLaw::abs_cos;
  rest.frequency_hz = 1.0;
  rest.amplitude = 0.8;
  SpringSchedule stiff;
  stiff.first = 0;
  stiff.last = 1;
  stiff.stiffness = true;
  stiff.law = ScheduleLaw::sine;
  stiff.mean = 20.0;
  stiff.amplitude = 5.0;
  stiff.frequency_hz = 0.5;
  spec.schedules = {rest, stiff};
  validate(spec);
  elastic::Body body;
  const Ib2dParts parts = add_ib2d_object(spec, 0.1, body);
  actuate_schedules(spec, parts, 1.25, body);
  EXPECT_NEAR(body.linear.rest_length[1], 0.8 * std::abs(std::cos(M_PI * 1.25)), 1e-15);
  EXPECT_EQ(body.linear.rest_length[0], 1.0);
  EXPECT_NEAR(body.linear.stiffness[0], 0.1 * (20.0 + 5.0 * std::sin(2 * M_PI * 0.5 * 1.25)), 1e-13);
  spec.schedules[0].last = 2;  // past the last spring
  EXPECT_THROW(validate(spec), std::invalid_argument);
  spec.schedules[0].last = 1;
  spec.schedules[1].mean = 4.0;  // a sine swinging below zero
  EXPECT_THROW(validate(spec), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::jellyfish
