// The seamless loop's pieces (issue 39 item 3): the loop's frame rate, the periodicity check at
// cycle starts, and the cut with the root motion removed or kept, on a stroke with a known answer.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jellysim/core/errors.hpp"
#include "jellysim/jellyfish/stroke_loop.hpp"

namespace jellysim::jellyfish {
namespace {

constexpr double kPi = std::numbers::pi;

/// A synthetic stroke: a periodic pulse of a five-point umbrella about a centroid that swims at a
/// constant speed with a periodic surge, plus two transients decaying over tau: a shape pattern
/// (zero mean: the centroid keeps its path) and a speed.
struct Stroke {
  double frequency = 0.5, rate = 10.0, diameter = 0.04, tau = 3.0;
  double speed = 0.01, surge = 0.002, transient_shape = 0.004, transient_speed = 0.006;
  std::vector<Vec2> base{{-0.02, 0.0}, {-0.014, 0.012}, {0.0, 0.016}, {0.014, 0.012}, {0.02, 0.0}};
  std::vector<Vec2> pattern{{1, 0}, {0, -1}, {0, 2}, {0, -1}, {-1, 0}};  // sums to zero

  double decay(double t) const { return std::exp(-t / tau); }
  Vec2 centroid_path(double t) const {
    return {0.1, 0.1 + speed * t + surge * std::sin(2 * kPi * frequency * t) + transient_speed * tau * (1 - decay(t))};
  }
  SliceFrame frame(std::int64_t k) const {
    SliceFrame f;
    f.time_s = static_cast<double>(k) / rate;
    const double pulse = 1.0 - 0.3 * std::pow(std::sin(kPi * frequency * f.time_s), 2);
    for (std::size_t i = 0; i < base.size(); ++i)
      f.umbrella.push_back(centroid_path(f.time_s) + pulse * base[i] + transient_shape * decay(f.time_s) * pattern[i]);
    f.tentacles = {{f.umbrella.front(), f.umbrella.front() + Vec2{0.0, -0.03}}};
    return f;
  }
  std::vector<SliceFrame> frames(std::int64_t count) const {
    std::vector<SliceFrame> v;
    for (std::int64_t k = 0; k < count; ++k) v.push_back(frame(k));
    return v;
  }
  /// The exact mismatch of the frame at t1 against the frame at t0 (central differences as measured).
  StrokeMismatch expected_between(double t0, double t1) const {
    const double h = 1.0 / rate;
    double rms = 0.0;
    for (const Vec2& w : pattern) rms += norm_squared(w);
    rms = std::sqrt(rms / static_cast<double>(pattern.size()));
    const auto transient_velocity = [&](double t) {
      return transient_speed * tau * (decay(t - h) - decay(t + h)) / (2 * h);
    };
    StrokeMismatch m;
    m.shape = transient_shape * std::abs(decay(t1) - decay(t0)) * rms / diameter;
    m.speed = std::abs(transient_velocity(t1) - transient_velocity(t0)) / (diameter * frequency);
    return m;
  }
  /// Cycle c's start against cycle (c − cycles)'s.
  StrokeMismatch expected(int c, int cycles = 1) const {
    StrokeMismatch m = expected_between((c - cycles) / frequency, c / frequency);
    m.cycle = c;
    return m;
  }
};

TEST(StrokeLoop, MismatchAtCycleStartsIsTheTransientsChange) {
  const Stroke s;
  const int per_cycle = frames_per_cycle(s.rate, s.frequency);
  ASSERT_EQ(per_cycle, 20);
  const std::vector<SliceFrame> frames = s.frames(12 * per_cycle + 2);
  for (int c = 2; c <= 12; ++c) {
    const StrokeMismatch m =
        stroke_mismatch(frames, static_cast<std::size_t>((c - 1) * per_cycle), static_cast<std::size_t>(c * per_cycle),
                        s.diameter, s.frequency);
    const StrokeMismatch e = s.expected(c);
    EXPECT_NEAR(m.shape, e.shape, 1e-12 + 1e-9 * e.shape) << c;
    EXPECT_NEAR(m.speed, e.speed, 1e-11 + 1e-8 * e.speed) << c;
  }
}

// The check is the loop's own closure: a loop of two cycles closes at cycle c when c's start
// matches the start of c − 2; the loop is then cycles c − 2 and c − 1.
TEST(StrokeLoop, SearchStopsAtTheFirstClosingCycleWithinTheToleranceAndRecordsTheLoop) {
  const Stroke s;
  const int per_cycle = frames_per_cycle(s.rate, s.frequency);
  LoopSettings loop;
  loop.enabled = true;
  loop.cycles = 2;
  loop.tolerance = 0.02;
  loop.max_cycles = 10;
  int first_pass = 0;
  for (int c = 3; c <= loop.max_cycles && first_pass == 0; ++c)
    if (s.expected(c, 2).largest() <= loop.tolerance) first_pass = c;
  ASSERT_GT(first_pass, 3);  // the transients make the early cycles fail
  const std::vector<SliceFrame> frames = s.frames(loop.max_cycles * per_cycle + 2);
  const LoopSearch search = search_loop(frames, per_cycle, loop, s.diameter, s.frequency);
  EXPECT_EQ(search.periodic_cycle, first_pass);
  EXPECT_EQ(search.start_cycle(), first_pass - 2);
  ASSERT_EQ(search.checked.size(), static_cast<std::size_t>(first_pass - 2));  // cycles 3 … first_pass
  EXPECT_EQ(search.checked.front().cycle, 3);
  EXPECT_GT(search.checked.front().largest(), loop.tolerance);
  const StrokeMismatch e = s.expected(first_pass, 2);
  EXPECT_NEAR(search.loop_check()->speed, e.speed, 1e-11 + 1e-8 * e.speed);
  // Recorded once the frame after the closing frame (for its speed) is there.
  const auto needed = static_cast<std::size_t>(first_pass * per_cycle + 2);
  EXPECT_FALSE(search.recorded(needed - 1, per_cycle));
  EXPECT_TRUE(search.recorded(needed, per_cycle));
  // Without a pass the loop starts at the best match.
  loop.tolerance = 1e-9;
  const LoopSearch none = search_loop(frames, per_cycle, loop, s.diameter, s.frequency);
  EXPECT_EQ(none.periodic_cycle, 0);
  EXPECT_EQ(none.start_cycle(), loop.max_cycles - 2);  // the transients decay: the last cycles match best
  EXPECT_FALSE(none.recorded(frames.size(), per_cycle));
}

TEST(StrokeLoop, RemovedRootMotionMakesTheFrameAfterTheLastTheFirst) {
  const Stroke s;
  const int per_cycle = frames_per_cycle(s.rate, s.frequency);
  const std::vector<SliceFrame> frames = s.frames(9 * per_cycle + 2);
  const std::size_t first = 6 * per_cycle, count = 3 * per_cycle;
  const LoopClip clip = cut_loop(frames, first, count, s.rate, RootMotion::remove, s.diameter, s.frequency);
  ASSERT_EQ(clip.frames.size(), count + 1);
  for (std::size_t k = 0; k <= count; ++k) EXPECT_EQ(clip.frames[k].time_s, static_cast<double>(k) / s.rate) << k;
  EXPECT_EQ(clip.duration_s, 6.0);
  const double t0 = frames[first].time_s, t1 = frames[first + count].time_s;
  const Vec2 travel = s.centroid_path(t1) - s.centroid_path(t0);
  EXPECT_NEAR(clip.travel.x, 0.0, 1e-15);
  EXPECT_NEAR(clip.travel.y, travel.y, 1e-15);
  EXPECT_NEAR(clip.travel.y, 0.06, 0.002);  // 6 s at 1 cm/s and what is left of the transient
  // The closing frame is the first but for the shape transient's decay over the loop.
  const double decayed = s.transient_shape * (s.decay(t1) - s.decay(t0));
  for (std::size_t i = 0; i < s.base.size(); ++i) {
    const Vec2 d = clip.frames.back().umbrella[i] - clip.frames.front().umbrella[i];
    EXPECT_NEAR(d.x, decayed * s.pattern[i].x, 1e-15) << i;
    EXPECT_NEAR(d.y, decayed * s.pattern[i].y, 1e-15) << i;
  }
  const Vec2 tip = clip.frames.back().tentacles[0][1] - clip.frames.front().tentacles[0][1];
  EXPECT_NEAR(norm(tip - decayed * s.pattern[0]), 0.0, 1e-15);
  EXPECT_NEAR(norm(umbrella_centroid(clip.frames.back()) - umbrella_centroid(clip.frames.front())), 0.0, 1e-15);
  // The midpoint is moved back by half the travel.
  EXPECT_NEAR(norm(clip.frames[count / 2].umbrella[2] - (frames[first + count / 2].umbrella[2] - 0.5 * travel)), 0.0,
              1e-15);
  const StrokeMismatch e = s.expected_between(t0, t1);  // cycle 9's start against cycle 6's
  EXPECT_NEAR(clip.closure.shape, e.shape, 1e-12);
  EXPECT_NEAR(clip.closure.speed, e.speed, 1e-10);
}

TEST(StrokeLoop, ConstantRootMotionKeepsTheTravel) {
  const Stroke s;
  const std::vector<SliceFrame> frames = s.frames(8 * 20 + 2);
  const LoopClip clip = cut_loop(frames, 140, 20, s.rate, RootMotion::constant, s.diameter, s.frequency);
  for (std::size_t k = 0; k <= 20; ++k)
    for (std::size_t i = 0; i < s.base.size(); ++i) EXPECT_EQ(clip.frames[k].umbrella[i], frames[140 + k].umbrella[i]);
  const Vec2 moved = umbrella_centroid(clip.frames.back()) - umbrella_centroid(clip.frames.front());
  EXPECT_NEAR(norm(moved - clip.travel), 0.0, 1e-16);
  EXPECT_THROW(cut_loop(frames, 141, 20, s.rate, RootMotion::constant, s.diameter, s.frequency), std::out_of_range);
}

TEST(StrokeLoop, LoopSearchPutsEveryCycleStartOnAFrameAndRunsToTheCap) {
  SwimSettings settings;
  settings.school.emplace_back();  // 0.7 Hz
  settings.frame_interval_s = 1.0 / 30.0;
  LoopSettings loop;
  loop.cycles = 2;
  loop.max_cycles = 10;
  const SwimSettings s = loop_search_settings(settings, loop);
  EXPECT_EQ(frames_per_cycle(30.0, 0.7), 43);  // 42.86 frames of 1/30 s a cycle
  EXPECT_EQ(s.frames_per_second, 43 * 0.7);
  EXPECT_EQ(s.frame_interval_s, 1.0 / (43 * 0.7));
  const sim::FrameClock clock = s.frame_clock(s.duration_s);
  EXPECT_EQ(clock.end_time(), static_cast<double>(10 * 43 + 1) / (43 * 0.7));  // the last closing frame and one
  for (int c = 1; c <= 10; ++c) EXPECT_NEAR(clock.frame_time(43 * c), c / 0.7, 4e-16 * c / 0.7) << c;
  settings.frames_per_second = 24.0;  // output.fps: 34 frames a cycle, 23.8 frames a second
  EXPECT_EQ(loop_search_settings(settings, loop).frames_per_second, 34 * 0.7);
  loop.cycles = 10;  // a loop as long as the cap can never close
  try {
    loop_search_settings(settings, loop);
    FAIL() << "a loop of render.loop_max_cycles accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("render.loop_cycles"), std::string::npos) << e.what();
  }
  loop.cycles = 2;
  settings.school.emplace_back();
  try {
    loop_search_settings(settings, loop);
    FAIL() << "two jellyfish accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("render.loop"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace jellysim::jellyfish
