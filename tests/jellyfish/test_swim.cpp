// The default jellyfish swims (thesis §8.2; Fig. 8.21's scene). Measured facts and the bounds
// asserted here are in docs/jellyfish.md ("Symmetry and lateral drift").
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/experiment.hpp"
#include "experiments/jellyfish_runs.hpp"

namespace jellysim::experiments {
namespace {

jellyfish::SwimSettings default_scene() {
  io::Config c = default_config(find_experiment("jellyfish"));
  c.set("tank.tracers_per_side=0");
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

// Ten contraction cycles of the default scene (a centred bell in a symmetric tank, so the
// simulation keeps its mirror symmetry, tank.symmetry = "auto"): the bell stays structurally sound,
// moves along its axis by more than one bell height (measured 18.0 cm, 6.4 bell heights) with a
// lateral drift under the 5 % of that (measured 6e-17 m: round-off of the centroid), and
// its volume oscillates at the contraction frequency.
TEST(SlowSwim, DefaultJellyfishSwimsAlongItsAxis) {
  const jellyfish::SwimSettings s = default_scene();
  ASSERT_NEAR(s.duration_s * s.jellyfish().frequency_hz, 10.0, 1e-9);
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  EXPECT_TRUE(rec.stats.mirror_symmetric) << rec.stats.symmetry_note;
  const auto& last = rec.metrics.back();
  std::printf("ten cycles: forward %.4g m, lateral %.3g m\n", last.position, last.lateral);
  EXPECT_GT(last.position, s.jellyfish().height_m) << "distance " << last.position;
  EXPECT_LT(std::abs(last.lateral), 0.05 * std::abs(last.position)) << "lateral " << last.lateral;
  std::vector<double> volume;
  for (const auto& r : rec.metrics) volume.push_back(r.volume);
  const double resolution = 1.0 / s.duration_s;
  EXPECT_NEAR(jellyfish::dominant_frequency(volume, s.frame_interval_s), s.jellyfish().frequency_hz, resolution);
}

// A symmetric bell in a symmetric tank stays mirror-symmetric while asymmetry is at solver-tolerance
// level: the semi-implicit solve stops at a 1e-6 relative GMRES residual, and over two cycles the
// measured point mismatch stays below 5e-7 m and the centroid's lateral offset below 3e-8 m. We
// allow 1e-6 m (1/40,000 of the diameter) and 1e-7 m. Later the wake instability amplifies the
// asymmetry (docs/jellyfish.md). This is the solver's own symmetry: tank.symmetry = "none".
// Keeping the mirror-symmetric part ("auto") must then change nothing but that asymmetry: the two
// runs' umbrellas agree to within the same 1e-6 m (measured 2e-7 m).
TEST(Swim, SymmetricBellStaysSymmetricForTwoCycles) {
  jellyfish::SwimSettings s = default_scene();
  s.duration_s = 2.0 / s.jellyfish().frequency_hz;
  s.school.front().aperture_centre_m.x = 0.5 * s.tank.width_m;
  s.tank.symmetry = jellyfish::MirrorSymmetry::none;
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  EXPECT_FALSE(rec.stats.mirror_symmetric);
  const double axis_x = 0.5 * s.tank.width_m;
  for (const auto& f : rec.frames) EXPECT_LT(mirror_mismatch(f.umbrella, axis_x), 1e-6) << f.time_s;
  for (const auto& r : rec.metrics) EXPECT_LT(std::abs(r.lateral), 1e-7) << r.t;

  s.tank.symmetry = jellyfish::MirrorSymmetry::automatic;
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
  EXPECT_LT(difference, 1e-6);
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

// The five cycles. Asymmetry enters at the level of the solver tolerances and the wake
// amplifies it about 40-fold per cycle. The pressure solves are exact (FFT), so with a Krylov
// tolerance of 1e-10 the largest left/right point mismatch over five cycles measured 5.9e-6 m
// (1/6,800 of the diameter) and the largest lateral offset of the centroid 1.2e-6 m. We allow
// 3e-5 m for both. A real symmetry bug (a one-sided force, a biased kernel) shows up as millimetres within a
// cycle. Release only: seven simulated seconds.
TEST(SlowSwim, SymmetricBellStaysSymmetricForFiveCycles) {
  jellyfish::SwimSettings s = default_scene();
  s.duration_s = 5.0 / s.jellyfish().frequency_hz;
  s.school.front().aperture_centre_m.x = 0.5 * s.tank.width_m;
  s.coupling.krylov_tolerance = 1e-10;
  s.tank.symmetry = jellyfish::MirrorSymmetry::none;  // the solver's own symmetry
  const SwimRecording rec = run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  const double axis_x = 0.5 * s.tank.width_m;
  double mismatch = 0.0, lateral = 0.0;
  for (const auto& f : rec.frames) mismatch = std::max(mismatch, mirror_mismatch(f.umbrella, axis_x));
  for (const auto& r : rec.metrics) lateral = std::max(lateral, std::abs(r.lateral));
  std::printf("five cycles: largest point mismatch %.3g m, lateral centroid offset %.3g m, forward %.3g m\n",
              mismatch, lateral, rec.metrics.back().position);
  EXPECT_LT(mismatch, 3e-5);
  EXPECT_LT(lateral, 3e-5);
}

}  // namespace
}  // namespace jellysim::experiments
