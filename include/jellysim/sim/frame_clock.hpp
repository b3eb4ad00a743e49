#pragma once
// The one frame clock and run loop of every runner: the ODE scenes (sim::integrate), the SPH scenes,
// the jellyfish tank (jellyfish::SwimSimulation::run) and the driven cavity. Output frames run on
// a clock of their own: frame n at n·interval (computed by multiplication, so frame times do not
// drift). Each runner says how it steps toward a time; the loop says when a frame is due and what
// to step toward. How a run ends when the duration is not a whole number of intervals differs by
// runner, as it did before the loops were one (FrameClock::Ending); making it one rule would
// change outputs, which the refactor that unified the loops was not to do (docs/architecture.md).
#include <cstdint>
#include <functional>
#include <string>

namespace jellysim::sim {

class FrameClock {
 public:
  enum class Ending {
    at_duration,    ///< run to the duration and record a frame there (the driven cavity)
    whole_frames,   ///< run to the duration; frames only at whole intervals (ODE and SPH scenes)
    nearest_frame,  ///< stop at the frame nearest the duration, at that frame's grid time (the
                    ///< duration rounded to whole frames; at least one frame): the jellyfish tank
  };
  /// interval_s <= 0: no frames but the first (and, on an early stop, the last). tolerance_s: a
  /// time within it of a frame time counts as on it (guards against round-off); end_tolerance_s
  /// the same for the end of the run (negative: tolerance_s). Throws std::invalid_argument when
  /// the duration holds more than 2^52 intervals.
  FrameClock(double interval_s, double duration_s, double tolerance_s, Ending ending = Ending::at_duration,
             double end_tolerance_s = -1.0);
  /// A clock of `frames_per_second` frames a second (> 0): frame n at n / frames_per_second,
  /// computed as that quotient (1/24 s frames are exactly the 1/24 grid, not a sum or a product of
  /// a rounded interval).
  static FrameClock at_rate(double frames_per_second, double duration_s, double tolerance_s,
                            Ending ending = Ending::at_duration, double end_tolerance_s = -1.0);

  double duration() const { return duration_; }
  /// Where the run ends: the duration, or with Ending::nearest_frame the last frame's time.
  double end_time() const { return end_; }
  double tolerance() const { return tolerance_; }
  /// Time of frame n: n·interval (or n / rate), capped at the duration (Ending::nearest_frame: at
  /// the last frame's grid time).
  double frame_time(std::int64_t n) const;
  /// The frames emitted so far (the next one is frame frames_emitted()).
  std::int64_t frames_emitted() const { return next_; }
  /// Time of the last frame emitted (−inf before the first).
  double last_frame_time() const;
  /// Whether t has reached the next frame.
  bool due(double t) const;
  /// Whether t has reached the duration and every frame up to it was emitted.
  bool finished(double t) const;
  /// What the next step must not pass: the next frame's time (or the duration).
  double target() const;
  /// The next frame's time n·interval, not capped at the duration (inf without frames).
  double scheduled_frame_time() const;
  void frame_emitted() { ++next_; }

 private:
  FrameClock(double interval_s, double rate_hz, double duration_s, double tolerance_s, Ending ending,
             double end_tolerance_s);
  double grid_time(std::int64_t n) const;

  double interval_, rate_, duration_, tolerance_, end_tolerance_;
  double cap_ = 0.0;       ///< no frame time beyond it
  std::int64_t last_ = 0;  ///< index of the last frame
  double end_ = 0.0;
  std::int64_t next_ = 0;
};

/// How one step went: go on, stop early (e.g. a steady state: the loop then records a last frame),
/// or fail (the message says when and where; the loop stops without another frame).
struct StepResult {
  enum class Kind { ok, stop, failed } kind = Kind::ok;
  std::string failure;
  static StepResult failed_with(std::string why) { return {Kind::failed, std::move(why)}; }
};

/// What a runner gives the loop.
struct ClockedRun {
  std::function<double()> time;
  /// One step toward t_target, never beyond it (landing on it when the step reaches it).
  std::function<StepResult(double t_target)> step;
  /// Records the current state as frame `index`; returns "" or why the run stops (a failure).
  std::function<std::string(std::int64_t index)> frame;
  /// Optional: called once per pass after the frame check (e.g. the SPH emitter).
  std::function<void()> after_frame_check{};
};

struct ClockOutcome {
  std::string failure;       ///< empty: the run reached its duration or stopped early
  bool stopped_early = false;
  bool interrupted = false;  ///< stopped by SIGINT/SIGTERM (core::interrupt_signal); failure says when
  std::int64_t steps = 0;    ///< steps taken by the loop
};

/// Called after every step (for progress display).
using ProgressCallback = std::function<void(double t, double duration, std::int64_t steps)>;

/// The loop: a frame whenever one is due (the first at the start), then a step toward the next
/// frame, until the duration; on an early stop, a last frame unless one was just recorded.
ClockOutcome run_frames(FrameClock& clock, const ClockedRun& run, const ProgressCallback& progress = {});

}  // namespace jellysim::sim
