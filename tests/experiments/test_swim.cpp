// The built-in jellyfish swims (thesis §8.2; Fig. 8.21's bell, resolved by 64 cells across): from
// the first stroke, along its axis, with one Krylov iteration per step, the same on half the tank as
// on the whole. Measured facts and the bounds asserted here are in docs/jellyfish.md ("Symmetry and
// lateral drift") and docs/convergence.md.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"

namespace jellysim::experiments {
namespace {

/// The built-in scene (64 cells across the bell), tracers off.
jellyfish::SwimSettings builtin_scene() {
  config::Config c = scene::builtin_jellyfish_scene();
  c.set("tank.tracers_per_side=0");
  return read_swim_settings(c);
}

/// The built-in scene on a grid four times coarser (96 × 192, 16 cells across the bell): the same
/// bell, tank and solvers, for the tests of the machinery (symmetry, half tank, the marker-space
/// solve), at a sixtieth of the cost. Its swimming is not the converged one (docs/convergence.md).
jellyfish::SwimSettings preview_scene() {
  config::Config c = scene::builtin_jellyfish_scene();
  c.set("tank.tracers_per_side=0");
  c.set("tank.cells=[96, 192]");
  return read_swim_settings(c);
}

double mirror_mismatch(const std::vector<Vec2>& u, double axis_x) {
  double mismatch = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const Vec2 a = u[k], b = u[u.size() - 1 - k];
    mismatch = std::max(mismatch, std::abs((a.x - axis_x) + (b.x - axis_x)) + std::abs(a.y - b.y));
  }
  return mismatch;
}

/// Position along the axis at the end of each whole cycle.
std::vector<double> positions_after_each_cycle(const SwimRecording& rec, double frequency_hz) {
  std::vector<double> out;
  for (int cycle = 1;; ++cycle) {
    const double t = cycle / frequency_hz;
    if (t > rec.metrics.back().t + 1e-9) return out;
    const auto nearest = std::min_element(rec.metrics.begin(), rec.metrics.end(), [t](const auto& a, const auto& b) {
      return std::abs(a.t - t) < std::abs(b.t - t);
    });
    out.push_back(nearest->position);
  }
}

/// Largest distance between corresponding umbrella points of two runs over all frames.
double largest_difference(const SwimRecording& a, const SwimRecording& b) {
  double d = 0.0;
  for (std::size_t f = 0; f < std::min(a.frames.size(), b.frames.size()); ++f)
    for (std::size_t k = 0; k < a.frames[f].umbrella.size(); ++k)
      d = std::max(d, norm(a.frames[f].umbrella[k] - b.frames[f].umbrella[k]));
  return d;
}

// Issue 35, item 7: densities far beyond the scene's allowed range (set here past the parameter
// table) make the state NaN at the first step (1e-308) or leave it finite with metrics that are not
// (1e308). Both are a failed run saying when and what, with finite metrics recorded up to the
// failure and charts that can be drawn (no "no finite data to plot" instead of a summary).
TEST(Swim, NonFiniteStatesAndMetricsAreDivergences) {
  config::Config c = scene::builtin_jellyfish_scene();
  c.set("tank.tracers_per_side=0");
  c.set("tank.cells=[24, 48]");
  c.set("duration=0.1");
  for (const double density : {1e-308, 1e308}) {
    jellyfish::SwimSettings s = read_swim_settings(c);
    s.tank.density_kg_per_m3 = density;
    const SwimRecording rec = run_swim(s, {}, nullptr, {});
    EXPECT_NE(rec.stats.failure.find("numerical instability"), std::string::npos) << density << ": " << rec.stats.failure;
    EXPECT_NE(rec.stats.failure.find("t = "), std::string::npos) << rec.stats.failure;
    if (density < 1.0) {
      EXPECT_EQ(jellyfish::non_finite_metric(rec.metrics), "") << "the NaN state was recorded";
    }
    EXPECT_FALSE(rec.metrics.empty());
  }
}

// The half tank (east half, a symmetry plane on the axis) against the whole tank, both keeping the
// mirror symmetry, over one cycle (the bell moves 0.9-1.1 cm on the preview grid; 1.6-1.7 cm with
// the tentacles' roots along the margin), for both fluid solvers and an exact and an iterative
// pressure solver: the same steps and the same umbrella at every frame, to round-off with the exact
// solvers (measured 3.86e-15 m Eulerian, 2.89e-15 m semi-Lagrangian; 1.09e-15 and 9.6e-15 m before;
// allowed 1e-14 and 2e-14 m) and to the multigrid tolerance (1e-8 of each pressure solve: measured
// 2.73e-10 m, 1.61e-9 m before; allowed 2e-9 m).
TEST(Swim, HalfTankMatchesTheWholeTank) {
  struct Case {
    const char* solver;
    const char* pressure;
    double bound_m;
  };
  for (const Case c : {Case{"eulerian", "fft", 1e-14}, Case{"semi-lagrangian", "fft", 2e-14},
                       Case{"eulerian", "multigrid", 2e-9}}) {
    jellyfish::SwimSettings s = preview_scene();
    s.duration_s = 1.0 / s.jellyfish().frequency_hz;
    s.tank.solver = c.solver;
    s.tank.pressure_solver = c.pressure;
    const SwimRecording half = run_swim(s, {}, nullptr, {});
    s.tank.half_tank = false;
    const SwimRecording whole = run_swim(s, {}, nullptr, {});
    ASSERT_TRUE(half.stats.failure.empty() && whole.stats.failure.empty()) << c.solver;
    EXPECT_TRUE(half.stats.half_tank);
    EXPECT_FALSE(whole.stats.half_tank);
    ASSERT_EQ(half.frames.size(), whole.frames.size());
    const double d = largest_difference(half, whole);
    std::printf("%s, %s: half against whole tank, one cycle: largest difference %.3g m, forward %.4g m\n", c.solver,
                c.pressure, d, half.metrics.back().position);
    EXPECT_LT(d, c.bound_m) << c.solver << ", " << c.pressure;
    EXPECT_EQ(half.stats.steps, whole.stats.steps);
  }
}

// The marker-space solve changes how GMRES gets there, not where: with the mobility preconditioner
// (one iteration per step) and with plain GMRES (91 per step on the preview grid) the end-of-step
// states agree within the Krylov tolerance (1e-6 of each step's correction: measured 4.67e-10 m over
// 14 steps, while the bell's margin moves about 1 mm).
TEST(Swim, MobilityPreconditionerGivesTheSameStepsAsPlainGmres) {
  jellyfish::SwimSettings s = preview_scene();
  s.duration_s = 0.2;
  s.frame_interval_s = 0.1;
  const SwimRecording preconditioned = run_swim(s, {}, nullptr, {});
  s.coupling.preconditioner = coupling::Preconditioner::none;
  const SwimRecording plain = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(preconditioned.stats.failure.empty() && plain.stats.failure.empty());
  std::printf("Krylov iterations: %ld preconditioned, %ld plain over %ld steps\n", preconditioned.stats.krylov_iterations,
              plain.stats.krylov_iterations, plain.stats.steps);
  EXPECT_EQ(preconditioned.stats.krylov_iterations, preconditioned.stats.steps);
  EXPECT_GT(plain.stats.krylov_iterations, 10 * plain.stats.steps);
  const double d = largest_difference(preconditioned, plain);
  std::printf("preconditioned against plain GMRES: largest difference %.3g m\n", d);
  EXPECT_LT(d, 1e-9);
}

// The built-in scene as `jellysim simulate` runs it: five contraction cycles at 64 cells across the
// bell (a centred bell in a symmetric tank: the mirror symmetry is kept, on half the tank). The bell
// stays structurally sound, swims forward by more than 0.55 bell heights in every cycle (measured
// 16.5, 28.6, 39.0, 45.7 mm in cycles 1–4: 0.59–1.6 heights,
// docs/convergence.md; 20.3 mm in the first before the tentacles' roots held against the aperture
// chord, docs/jellyfish.md "Tentacles that trail"), with no lateral drift beyond round-off
// (measured 4.2e-17 m over 18 cm; allowed 3e-16 m), one Krylov iteration per step, and its volume
// oscillates at the contraction frequency. Release only (about 40 s).
TEST(SlowSwim, BuiltInSceneIsResolvedAndSwimsForwardInEveryCycle) {
  const jellyfish::SwimSettings s = builtin_scene();
  ASSERT_NEAR(s.duration_s * s.jellyfish().frequency_hz, 5.0, 1e-9);
  const double cell = std::max(s.tank.width_m / s.tank.cells_x, s.tank.height_m / s.tank.cells_y);
  EXPECT_GE(s.jellyfish().diameter_m / cell, 64.0 - 1e-9);
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  EXPECT_TRUE(rec.stats.mirror_symmetric) << rec.stats.symmetry_note;
  EXPECT_TRUE(rec.stats.half_tank);
  const std::vector<double> at = positions_after_each_cycle(rec, s.jellyfish().frequency_hz);
  ASSERT_GE(at.size(), 4u);
  double previous = 0.0;
  for (std::size_t c = 0; c < at.size(); ++c) {
    std::printf("cycle %zu: %.4g m\n", c + 1, at[c] - previous);
    EXPECT_GT(at[c] - previous, 0.55 * s.jellyfish().height_m) << "cycle " << c + 1;
    previous = at[c];
  }
  const auto& last = rec.metrics.back();
  std::printf("five cycles: forward %.4g m, lateral %.3g m; %ld steps, %ld Krylov iterations\n", last.position,
              last.lateral, rec.stats.steps, rec.stats.krylov_iterations);
  EXPECT_LT(std::abs(last.lateral), 3e-16) << "lateral " << last.lateral;
  EXPECT_EQ(rec.stats.krylov_iterations, rec.stats.steps);
  std::vector<double> volume;
  for (const auto& r : rec.metrics) volume.push_back(r.volume);
  const double resolution = 1.0 / s.duration_s;
  EXPECT_NEAR(jellyfish::dominant_frequency(volume, s.frame_interval_s), s.jellyfish().frequency_hz, resolution);
}

// A symmetric bell in a symmetric tank stays mirror-symmetric by itself, on the whole tank without
// the symmetry kept (tank.symmetry = "none"): the exact marker-space solve leaves round-off as the
// only seed of asymmetry, and over two cycles on the preview grid the measured point mismatch is
// 1.2e-14 m and the centroid's lateral offset 2.7e-15 m (6.83e-14 and 1.48e-14 m with the tentacles'
// roots along the margin; on the thesis's coarse tank with plain GMRES at a 1e-6 tolerance they were
// 5e-7 and 3e-8 m). We allow 7e-13 and 1.5e-13 m. Keeping the mirror-symmetric part on half the tank
// ("auto") must then change nothing but that round-off: the two runs' umbrellas agree to 1.14e-14 m
// (3.61e-14 m before); we allow 4e-13 m.
TEST(Swim, SymmetricBellStaysSymmetricForTwoCycles) {
  jellyfish::SwimSettings s = preview_scene();
  s.duration_s = 2.0 / s.jellyfish().frequency_hz;
  s.school.front().aperture_centre_m.x = 0.5 * s.tank.width_m;
  s.tank.symmetry = coupling::MirrorSymmetry::none;
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  EXPECT_FALSE(rec.stats.mirror_symmetric);
  const double axis_x = 0.5 * s.tank.width_m;
  double mismatch = 0.0, lateral = 0.0;
  for (const auto& f : rec.frames) mismatch = std::max(mismatch, mirror_mismatch(f.umbrella, axis_x));
  for (const auto& r : rec.metrics) lateral = std::max(lateral, std::abs(r.lateral));
  std::printf("two cycles without the symmetry kept: point mismatch %.3g m, lateral offset %.3g m\n", mismatch, lateral);
  EXPECT_LT(mismatch, 7e-13);
  EXPECT_LT(lateral, 1.5e-13);

  s.tank.symmetry = coupling::MirrorSymmetry::automatic;
  const SwimRecording kept = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(kept.stats.mirror_symmetric) << kept.stats.symmetry_note;
  ASSERT_EQ(kept.frames.size(), rec.frames.size());
  double difference = 0.0;
  for (std::size_t f = 0; f < rec.frames.size(); ++f) {
    EXPECT_LT(mirror_mismatch(kept.frames[f].umbrella, axis_x), 1e-15) << f;
    for (std::size_t k = 0; k < rec.frames[f].umbrella.size(); ++k)
      difference = std::max(difference, norm(kept.frames[f].umbrella[k] - rec.frames[f].umbrella[k]));
  }
  std::printf("two cycles: largest difference between the runs with and without mirror symmetry %.3g m\n",
              difference);
  EXPECT_LT(difference, 4e-13);
  // It contracts in each cycle and re-expands in between.
  const double period = 1.0 / s.jellyfish().frequency_hz;
  for (int cycle = 0; cycle < 2; ++cycle) {
    double v_min = 1e9, v_max_after = 0.0, t_min = 0.0;
    for (const auto& r : rec.metrics)
      if (r.t >= cycle * period && r.t < (cycle + 1) * period && r.volume_ratio < v_min) {
        v_min = r.volume_ratio;
        t_min = r.t;
      }
    for (const auto& r : rec.metrics)
      if (r.t > t_min && r.t <= (cycle + 1) * period) v_max_after = std::max(v_max_after, r.volume_ratio);
    EXPECT_LT(v_min, 0.6) << "cycle " << cycle;
    EXPECT_GT(v_max_after, v_min + 0.15) << "cycle " << cycle;
  }
}

// Five cycles without the symmetry kept, Krylov tolerance 1e-10, on the preview grid: the wake
// amplifies the round-off asymmetry, and the largest left/right point mismatch measured 1.38e-10 m
// (1/290,000,000 of the diameter; 1.85e-10 m with the tentacles' roots along the margin; 5.9e-6 m on
// the thesis's coarse tank) and the largest lateral offset of the centroid 3.4e-11 m (2.9e-11 m
// before). We allow 1e-9 and 1e-10 m. A real symmetry bug (a one-sided
// force, a biased kernel) shows up as millimetres within a cycle. Release only.
TEST(SlowSwim, SymmetricBellStaysSymmetricForFiveCycles) {
  jellyfish::SwimSettings s = preview_scene();
  s.duration_s = 5.0 / s.jellyfish().frequency_hz;
  s.school.front().aperture_centre_m.x = 0.5 * s.tank.width_m;
  s.coupling.krylov_tolerance = 1e-10;
  s.tank.symmetry = coupling::MirrorSymmetry::none;  // the solver's own symmetry
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  const double axis_x = 0.5 * s.tank.width_m;
  double mismatch = 0.0, lateral = 0.0;
  for (const auto& f : rec.frames) mismatch = std::max(mismatch, mirror_mismatch(f.umbrella, axis_x));
  for (const auto& r : rec.metrics) lateral = std::max(lateral, std::abs(r.lateral));
  std::printf("five cycles: largest point mismatch %.3g m, lateral centroid offset %.3g m, forward %.3g m\n",
              mismatch, lateral, rec.metrics.back().position);
  EXPECT_LT(mismatch, 1e-9);
  EXPECT_LT(lateral, 1e-10);
}

/// How far a tentacle leans in under the bell (rad): the angle of its root-to-tip direction from
/// the trailing direction −axis, positive toward the axis. Strand 0 hangs from the left margin.
double inward_lean_rad(const jellyfish::SliceFrame& f, std::size_t strand) {
  const std::vector<Vec2>& t = f.tentacles[strand];
  const Vec2 d = t.back() - t.front();
  const Vec2 outward = strand == 0 ? Vec2{-f.axis.y, f.axis.x} : Vec2{f.axis.y, -f.axis.x};
  return std::atan2(-dot(d, outward), -dot(d, f.axis));
}

// Issue 39 item 5: the tentacles trail through the recovery stroke. Their root joints hold them
// against the aperture chord (jellyfish.tentacle_root = "axis", the continuum model's default),
// so when the re-expanding bell turns its margin inward they keep hanging along the swimming axis
// instead of continuing the margin's tangent under the bell. Three cycles of the built-in scene on
// the grid twice coarser (192 × 384, 32 cells across the bell), the recovery strokes of cycles 2
// and 3 (phase 0.3–1): the largest inward lean measured 11.7° (with "margin", the former root: 33.6°,
// and 11.6 mm of tip behind the root), and each tip stays at least 13.68 mm of its 14 mm behind
// its root along the axis. We allow 15° and 13.3 mm. (docs/jellyfish.md, "Tentacles that trail".)
TEST(Swim, TentaclesTrailThroughTheRecoveryStroke) {
  config::Config c = scene::builtin_jellyfish_scene();
  c.set("tank.tracers_per_side=0");
  c.set("tank.cells=[192, 384]");
  jellyfish::SwimSettings s = read_swim_settings(c);
  const double period = 1.0 / s.jellyfish().frequency_hz;
  s.duration_s = 3.0 * period;
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  double lean = -1.0, behind = 1.0;
  for (const jellyfish::SliceFrame& f : rec.frames) {
    const double phase = f.time_s / period;
    if (phase < 1.0 || phase - std::floor(phase) < s.jellyfish().profile.contract_fraction) continue;
    ASSERT_EQ(f.tentacles.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      lean = std::max(lean, inward_lean_rad(f, k));
      behind = std::min(behind, -dot(f.tentacles[k].back() - f.tentacles[k].front(), f.axis));
    }
  }
  const double degree = std::numbers::pi / 180.0;
  std::printf("recovery strokes of cycles 2-3: largest inward lean %.3g deg, tips at least %.4g m behind the roots\n",
              lean / degree, behind);
  EXPECT_LT(lean, 15.0 * degree);
  EXPECT_GT(behind, 0.0133);
}

}  // namespace
}  // namespace jellysim::experiments
