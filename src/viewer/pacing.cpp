#include "pacing.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace jellysim::viewer {

Pacer::Pacer(PacingSettings settings, Clock clock) : settings_(settings), clock_(std::move(clock)) {}

double Pacer::budget(double other_work_s) const {
  return std::max(settings_.min_budget_s, 1.0 / settings_.min_fps - other_work_s);
}

FrameSteps Pacer::advance(double wall_gap_s, double other_work_s, const StepFn& step) {
  FrameSteps out;
  const double gap = std::clamp(wall_gap_s, 0.0, settings_.max_frame_gap_s);
  debt_s_ += gap * settings_.speed;
  // Never carry more than one long frame's worth: a slow frame must not make the next ones slower.
  debt_s_ = std::min(debt_s_, settings_.max_frame_gap_s * settings_.speed);
  const double start = clock_();
  const double budget_s = budget(other_work_s);
  while (debt_s_ > 0.0) {
    if (clock_() - start >= budget_s) {
      out.behind = true;
      debt_s_ = 0.0;
      break;
    }
    // Full-size steps (no short step to land on the wall clock, which would cost a whole coupled
    // solve for little time): the overshoot is carried as negative debt into the next frame.
    const PacedStep s = step(settings_.max_frame_gap_s * settings_.speed);
    if (!s.failure.empty()) {
      out.failure = s.failure;
      debt_s_ = 0.0;
      break;
    }
    ++out.steps;
    out.simulated_s += s.dt_s;
    debt_s_ -= s.dt_s;
    if (!(s.dt_s > 0.0)) break;  // no progress: do not spin
  }
  return out;
}

void RateMeter::add(double wall_time_s, double sim_time_s, bool behind) {
  samples_.push_back({wall_time_s, sim_time_s, behind});
  while (samples_.size() > 2 && samples_.back().wall - samples_.front().wall > window_s_) samples_.pop_front();
}

double RateMeter::fps() const {
  if (samples_.size() < 2) return 0.0;
  const double span = samples_.back().wall - samples_.front().wall;
  return span > 0.0 ? static_cast<double>(samples_.size() - 1) / span : 0.0;
}

double RateMeter::sim_rate() const {
  if (samples_.size() < 2) return 0.0;
  const double span = samples_.back().wall - samples_.front().wall;
  return span > 0.0 ? (samples_.back().sim - samples_.front().sim) / span : 0.0;
}

double RateMeter::behind_fraction() const {
  if (samples_.empty()) return 0.0;
  const auto n = std::count_if(samples_.begin(), samples_.end(), [](const Sample& s) { return s.behind; });
  return static_cast<double>(n) / static_cast<double>(samples_.size());
}

}  // namespace jellysim::viewer
