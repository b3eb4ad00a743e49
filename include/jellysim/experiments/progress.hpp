#pragma once
// Machine-readable progress (`--progress json`, README "Using it"): one JSON object per line for each
// stage of a long command (simulated time, fraction, steps, ETA), throttled to five lines a second
// plus the last, and a closing status line. The add-on (blender/) and the Python module read them.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace jellysim::experiments {

/// The wall clock of one stage ("simulate", "render", "batch"): fraction done and ETA from the
/// reports, and a throttle of at most five reports a second, the last (fraction 1) always let through.
class ProgressTracker {
 public:
  using Clock = std::chrono::steady_clock;
  explicit ProgressTracker(std::string stage, double min_interval_s = 0.2);

  /// A simulation's report: simulated time t of `duration` s after `steps` steps. The line when the
  /// throttle lets it through, else null. A time below the previous one starts the stage again (an
  /// experiment of several runs: convergence's grids, a sweep's frequencies).
  nlohmann::ordered_json simulation(double t, double duration, std::int64_t steps);
  /// A count's report (frames rendered, batch runs finished): `done` of `total`, named `unit`.
  nlohmann::ordered_json count(std::size_t done, std::size_t total, const std::string& unit);

 private:
  /// Fills eta_seconds and elapsed_seconds; false when throttled.
  bool admit(double fraction, nlohmann::ordered_json& line);

  std::string stage_;
  double min_interval_s_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_{};
  double last_fraction_ = -1.0;  ///< none yet
  double first_fraction_ = 0.0;   ///< at start_
};

/// The closing line: {"status": "done"|"failed"|"interrupted", "exit_code", "out", "message"}.
nlohmann::ordered_json progress_status(int exit_code, const std::string& out, const std::string& message);

/// Writes one line (compact JSON and a newline) to stderr and flushes it, whole, under a lock (the
/// batch's worker threads report at once).
void write_progress_line(const nlohmann::ordered_json& line);

/// Whether write_progress_line wrote a status line in this process (the CLI then writes no other).
bool status_line_written();

}  // namespace jellysim::experiments
