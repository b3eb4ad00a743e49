#include "jellysim/sim/frame_clock.hpp"

#include "jellysim/core/interrupt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace jellysim::sim {

FrameClock::FrameClock(double interval_s, double duration_s, double tolerance_s, Ending ending, double end_tolerance_s)
    : FrameClock(interval_s, 0.0, duration_s, tolerance_s, ending, end_tolerance_s) {}

FrameClock FrameClock::at_rate(double frames_per_second, double duration_s, double tolerance_s, Ending ending,
                               double end_tolerance_s) {
  if (!(frames_per_second > 0.0) || !std::isfinite(frames_per_second))
    throw std::invalid_argument("frame rate " + std::to_string(frames_per_second) + " /s is not a positive number");
  return FrameClock(1.0 / frames_per_second, frames_per_second, duration_s, tolerance_s, ending, end_tolerance_s);
}

FrameClock::FrameClock(double interval_s, double rate_hz, double duration_s, double tolerance_s, Ending ending,
                       double end_tolerance_s)
    : interval_(interval_s),
      rate_(rate_hz),
      duration_(duration_s),
      tolerance_(tolerance_s),
      end_tolerance_(end_tolerance_s < 0.0 ? tolerance_s : end_tolerance_s),
      cap_(duration_s),
      end_(duration_s) {
  if (interval_ <= 0.0) return;
  const double frames = rate_ > 0.0 ? duration_ * rate_ : duration_ / interval_;
  if (!(frames <= 4503599627370496.0))  // 2^52: frame indices stay exact
    throw std::invalid_argument("frame interval " + std::to_string(interval_) + " s is too small for a duration of " +
                                std::to_string(duration_) + " s");
  switch (ending) {
    case Ending::at_duration:  // the frame at the duration, or capped at it
      last_ = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil((duration_ - tolerance_) / interval_)));
      break;
    case Ending::whole_frames:
      last_ = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor((duration_ + tolerance_) / interval_)));
      break;
    case Ending::nearest_frame:  // the duration rounded to whole frames: the last frame on the grid
      last_ = std::max<std::int64_t>(1, std::llround(frames));
      cap_ = end_ = grid_time(last_);
      break;
  }
}

double FrameClock::grid_time(std::int64_t n) const {
  return rate_ > 0.0 ? static_cast<double>(n) / rate_ : static_cast<double>(n) * interval_;
}

double FrameClock::frame_time(std::int64_t n) const {
  if (interval_ <= 0.0) return n == 0 ? 0.0 : duration_;
  return std::min(grid_time(n), cap_);
}

double FrameClock::last_frame_time() const {
  return next_ == 0 ? -std::numeric_limits<double>::infinity() : frame_time(next_ - 1);
}

bool FrameClock::due(double t) const {
  if (interval_ <= 0.0) return next_ == 0;
  return next_ <= last_ && t >= frame_time(next_) - tolerance_;
}

bool FrameClock::finished(double t) const {
  return t >= end_ - end_tolerance_ && (interval_ <= 0.0 || next_ > last_);
}

double FrameClock::scheduled_frame_time() const {
  return interval_ <= 0.0 ? std::numeric_limits<double>::infinity() : grid_time(next_);
}

double FrameClock::target() const {
  return interval_ <= 0.0 || next_ > last_ ? end_ : frame_time(next_);
}

ClockOutcome run_frames(FrameClock& clock, const ClockedRun& run, const ProgressCallback& progress) {
  ClockOutcome outcome;
  while (true) {
    if (clock.due(run.time())) {
      if (std::string stop = run.frame(clock.frames_emitted()); !stop.empty()) {
        outcome.failure = std::move(stop);
        return outcome;
      }
      clock.frame_emitted();
    }
    if (run.after_frame_check) run.after_frame_check();
    if (clock.finished(run.time())) return outcome;
    if (const int signal = core::interrupt_signal()) {  // SIGINT/SIGTERM: stop at this step boundary
      outcome.failure = "interrupted by " + core::signal_name(signal) + " at t = " + std::to_string(run.time()) +
                        " s (step " + std::to_string(outcome.steps) + ")";
      outcome.interrupted = true;
      return outcome;
    }
    const StepResult r = run.step(clock.target());
    if (r.kind == StepResult::Kind::failed) {
      outcome.failure = r.failure;
      return outcome;
    }
    ++outcome.steps;
    if (progress) progress(run.time(), clock.duration(), outcome.steps);
    if (r.kind == StepResult::Kind::stop) {
      outcome.stopped_early = true;
      if (run.time() > clock.last_frame_time()) {
        if (std::string stop = run.frame(clock.frames_emitted()); !stop.empty()) outcome.failure = std::move(stop);
        clock.frame_emitted();
      }
      return outcome;
    }
  }
}

}  // namespace jellysim::sim
