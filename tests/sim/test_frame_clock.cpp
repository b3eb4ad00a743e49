// The shared frame clock and run loop (sim/frame_clock.hpp): frame times, the three ways a run ends,
// early stops and failures.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cmath>
#include <vector>

#include "jellysim/core/interrupt.hpp"
#include "jellysim/sim/frame_clock.hpp"

namespace {

using jellysim::sim::ClockedRun;
using jellysim::sim::FrameClock;
using jellysim::sim::run_frames;
using jellysim::sim::StepResult;

struct Recorded {
  std::vector<double> frames;  ///< times of the recorded frames
  double end = 0.0;
  std::int64_t steps = 0;
  bool stopped_early = false;
  std::string failure;
};

/// A runner whose natural step is `dt`: it steps min(dt, target − t) and lands on the target.
Recorded run_clock(FrameClock clock, double dt, double stop_at = INFINITY, double fail_at = INFINITY) {
  Recorded r;
  double t = 0.0;
  ClockedRun run;
  run.time = [&] { return t; };
  run.frame = [&](std::int64_t index) {
    EXPECT_EQ(index, static_cast<std::int64_t>(r.frames.size()));
    r.frames.push_back(t);
    return std::string();
  };
  run.step = [&](double target) -> StepResult {
    EXPECT_LE(t, target);
    if (t >= fail_at) return StepResult::failed_with("failed at " + std::to_string(t));
    t = t + dt >= target ? target : t + dt;
    if (t >= stop_at) return {StepResult::Kind::stop, {}};
    return {};
  };
  const auto outcome = run_frames(clock, run);
  r.end = t;
  r.steps = outcome.steps;
  r.stopped_early = outcome.stopped_early;
  r.failure = outcome.failure;
  return r;
}

void expect_times(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_NEAR(got[k], want[k], 1e-12) << "frame " << k;
}

TEST(FrameClock, FramesLandOnWholeIntervalsWhateverTheStep) {
  // A step of 0.03 against frames every 0.1 s: each frame is hit exactly, by shortened steps.
  const Recorded r = run_clock(FrameClock(0.1, 0.3, 1e-12), 0.03);
  expect_times(r.frames, {0.0, 0.1, 0.2, 0.3});
  EXPECT_DOUBLE_EQ(r.end, 0.3);
  EXPECT_EQ(r.steps, 12);  // 4 steps per frame: 0.03, 0.03, 0.03, 0.01
}

TEST(FrameClock, ARunEndsAsItsRunnerAlwaysEnded) {
  // Duration 0.25 with frames every 0.1 s (not a whole number of intervals).
  const Recorded at = run_clock(FrameClock(0.1, 0.25, 1e-12, FrameClock::Ending::at_duration), 0.07);
  expect_times(at.frames, {0.0, 0.1, 0.2, 0.25});
  EXPECT_DOUBLE_EQ(at.end, 0.25);
  const Recorded whole = run_clock(FrameClock(0.1, 0.25, 1e-12, FrameClock::Ending::whole_frames), 0.07);
  expect_times(whole.frames, {0.0, 0.1, 0.2});
  EXPECT_DOUBLE_EQ(whole.end, 0.25);
  // Nearest frame: the duration rounded to whole frames, the last frame on the grid (issue 39):
  // 2.5 intervals round to 3 (0.3 s, past the duration), 0.24 s to 2 (0.2 s).
  const Recorded up = run_clock(FrameClock(0.1, 0.25, 1e-12, FrameClock::Ending::nearest_frame), 0.07);
  expect_times(up.frames, {0.0, 0.1, 0.2, 0.3});
  EXPECT_EQ(up.end, 3 * 0.1);
  const Recorded down = run_clock(FrameClock(0.1, 0.24, 1e-12, FrameClock::Ending::nearest_frame), 0.07);
  expect_times(down.frames, {0.0, 0.1, 0.2});
  EXPECT_NEAR(down.end, 0.2, 1e-15);
  // At least one frame after the start, even for a duration under half an interval: on the grid.
  const Recorded shortest = run_clock(FrameClock(0.1, 0.02, 1e-12, FrameClock::Ending::nearest_frame), 0.07);
  expect_times(shortest.frames, {0.0, 0.1});
}

TEST(FrameClock, TheMainJobsLastFrameIsOnTheFrameGrid) {
  // 3 cycles at 0.7 Hz = 128.57 frames of 1/30 s: 129 frames after the start, the last at
  // 129/30 = 4.3 s (was 4.2857 s, off the grid: Blender's action ended at frame 128.57).
  const FrameClock clock(1.0 / 30.0, 3.0 / 0.7, 1e-12, FrameClock::Ending::nearest_frame);
  EXPECT_EQ(clock.end_time(), 129.0 * (1.0 / 30.0));
  EXPECT_NEAR(clock.end_time(), 4.3, 1e-15);
  const Recorded r = run_clock(clock, 0.011);
  ASSERT_EQ(r.frames.size(), 130u);
  EXPECT_EQ(r.frames.back(), clock.end_time());
}

TEST(FrameClock, AtRateFrameKIsKOverTheRate) {
  // 24 frames a second: frame k at k / 24 exactly (1/24 is not a double: k · (1/24) differs in
  // the last bit for some k), the last frame on the grid.
  const FrameClock clock = FrameClock::at_rate(24.0, 10.01, 1e-12, FrameClock::Ending::nearest_frame);
  int differ = 0;
  for (std::int64_t k = 0; k <= 240; ++k) {
    EXPECT_EQ(clock.frame_time(k), static_cast<double>(k) / 24.0);
    differ += static_cast<double>(k) * (1.0 / 24.0) != static_cast<double>(k) / 24.0;
  }
  EXPECT_GT(differ, 0);  // the test tells the two apart
  EXPECT_EQ(clock.end_time(), 240.0 / 24.0);
  const Recorded r = run_clock(clock, 0.013);
  ASSERT_EQ(r.frames.size(), 241u);
  for (std::size_t k = 0; k < r.frames.size(); ++k) EXPECT_EQ(r.frames[k], static_cast<double>(k) / 24.0);
  EXPECT_THROW(FrameClock::at_rate(0.0, 1.0, 1e-12), std::invalid_argument);
}

TEST(FrameClock, FrameTimesDoNotDrift) {
  // 1000 frames of 1/30 s: frame n is n/30 computed by multiplication, not a running sum.
  const FrameClock clock(1.0 / 30.0, 1000.0 / 30.0, 1e-12);
  EXPECT_EQ(clock.frame_time(999), 999.0 * (1.0 / 30.0));
  const Recorded r = run_clock(clock, 0.011);
  ASSERT_EQ(r.frames.size(), 1001u);
  for (std::size_t n = 0; n < r.frames.size(); ++n) EXPECT_EQ(r.frames[n], clock.frame_time(static_cast<std::int64_t>(n)));
}

TEST(FrameClock, AnEarlyStopRecordsTheLastStateAndAFailureStopsAtOnce) {
  const Recorded stopped = run_clock(FrameClock(0.1, 1.0, 1e-12), 0.04, 0.33);
  EXPECT_TRUE(stopped.stopped_early);
  expect_times(stopped.frames, {0.0, 0.1, 0.2, 0.3, 0.34});
  // Stopping exactly on a frame records it once.
  const Recorded on_frame = run_clock(FrameClock(0.1, 1.0, 1e-12), 0.05, 0.2);
  expect_times(on_frame.frames, {0.0, 0.1, 0.2});
  const Recorded failed = run_clock(FrameClock(0.1, 1.0, 1e-12), 0.05, INFINITY, 0.15);
  EXPECT_EQ(failed.failure.rfind("failed at 0.15", 0), 0u) << failed.failure;
  expect_times(failed.frames, {0.0, 0.1});
  // No frames asked for (interval 0): the start only; the run goes to the duration.
  const Recorded none = run_clock(FrameClock(0.0, 0.5, 1e-12), 0.2);
  expect_times(none.frames, {0.0});
  EXPECT_DOUBLE_EQ(none.end, 0.5);
}

}  // namespace

TEST(FrameClock, AStopRequestEndsTheLoopAtTheNextStepBoundaryAndSaysWhen) {
  FrameClock clock(0.1, 1.0, 1e-12, FrameClock::Ending::at_duration);
  double t = 0.0;
  int frames = 0;
  ClockedRun run;
  run.time = [&] { return t; };
  run.frame = [&](std::int64_t) {
    ++frames;
    return std::string();
  };
  run.step = [&](double target) -> StepResult {
    t = std::min(target, t + 0.05);
    if (t >= 0.3) jellysim::core::request_interrupt(SIGINT);  // as the handler would, mid-run
    return {};
  };
  const auto outcome = run_frames(clock, run);
  jellysim::core::clear_interrupt();
  EXPECT_TRUE(outcome.interrupted);
  EXPECT_NEAR(t, 0.3, 1e-12);  // no step after the request
  EXPECT_EQ(frames, 4);       // 0, 0.1, 0.2, 0.3: the state reached is recorded
  EXPECT_EQ(outcome.failure, "interrupted by SIGINT at t = 0.300000 s (step 6)");
}
