#pragma once
// Keeping the simulation in real time: each frame the simulation owes the wall time that passed
// (times the target speed); the pacer takes adaptive steps until that debt is paid or the frame's
// step-time budget is spent. The budget is what is left of a frame at the lowest acceptable frame
// rate once the frame's other work (drawing) is done, so a costly simulation lowers the frame rate
// down to that floor before it falls behind real time. When the budget runs out first the frame is "behind": the unpaid debt
// is dropped (no spiral of ever longer frames) and the viewer says it cannot keep up.
// No window and no simulation: the step is a callback, so this is testable on its own.
#include <deque>
#include <functional>
#include <string>

namespace jellysim::viewer {

struct PacingSettings {
  double speed = 1.0;            ///< simulated seconds wanted per wall second
  double min_fps = 10.0;         ///< the frame rate the steps may slow the viewer down to
  double min_budget_s = 0.002;   ///< the steps always get at least this much per frame
  double max_frame_gap_s = 0.1;  ///< longer gaps between frames (a stall) count as this
};

/// Result of one simulation step as the pacer sees it.
struct PacedStep {
  double dt_s = 0.0;
  std::string failure;
};

struct FrameSteps {
  int steps = 0;
  double simulated_s = 0.0;
  bool behind = false;    ///< the budget ran out before the debt was paid
  std::string failure;    ///< a step failed: stop stepping
};

class Pacer {
 public:
  using StepFn = std::function<PacedStep(double max_dt_s)>;
  using Clock = std::function<double()>;  ///< wall seconds, monotonic

  Pacer(PacingSettings settings, Clock clock);

  /// Steps for a frame that began `wall_gap_s` after the previous one, whose other work takes
  /// about `other_work_s`.
  FrameSteps advance(double wall_gap_s, double other_work_s, const StepFn& step);
  /// The step-time budget of a frame whose other work takes `other_work_s`.
  double budget(double other_work_s) const;
  /// Forgets the debt (pause, reset, single steps).
  void reset_debt() { debt_s_ = 0.0; }
  PacingSettings& settings() { return settings_; }
  const PacingSettings& settings() const { return settings_; }

 private:
  PacingSettings settings_;
  Clock clock_;
  double debt_s_ = 0.0;  ///< simulated seconds still owed (may be slightly negative after a long step)
};

/// Frames per second and simulated-time rate over a sliding window of wall time.
class RateMeter {
 public:
  explicit RateMeter(double window_s = 1.0) : window_s_(window_s) {}
  void add(double wall_time_s, double sim_time_s, bool behind);
  double fps() const;
  double sim_rate() const;        ///< simulated seconds per wall second
  double behind_fraction() const; ///< share of frames in the window that were behind

 private:
  struct Sample {
    double wall, sim;
    bool behind;
  };
  double window_s_;
  std::deque<Sample> samples_;
};

}  // namespace jellysim::viewer
