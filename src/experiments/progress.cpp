#include "jellysim/experiments/progress.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>

namespace jellysim::experiments {

ProgressTracker::ProgressTracker(std::string stage, double min_interval_s)
    : stage_(std::move(stage)), min_interval_s_(min_interval_s) {}

bool ProgressTracker::admit(double fraction, nlohmann::ordered_json& line) {
  // Fills eta_seconds and elapsed_seconds. The clock starts at the stage's first report, or again
  // when the fraction goes back (the next run of an experiment of several); the ETA is the rate
  // since then (null until the fraction has moved).
  const Clock::time_point now = Clock::now();
  if (last_fraction_ < 0.0 || fraction < last_fraction_) {
    start_ = now;
    first_fraction_ = fraction;
  }
  last_fraction_ = fraction;
  const bool last = fraction >= 1.0;
  if (!last && std::chrono::duration<double>(now - last_).count() < min_interval_s_) return false;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  line["eta_seconds"] = nullptr;
  if (last) line["eta_seconds"] = 0.0;
  else if (fraction > first_fraction_ && elapsed > 0.0)
    line["eta_seconds"] = elapsed * (1.0 - fraction) / (fraction - first_fraction_);
  line["elapsed_seconds"] = elapsed;
  return true;
}

nlohmann::ordered_json ProgressTracker::simulation(double t, double duration, std::int64_t steps) {
  // A frame time within a few ulps of the duration counts as the end (its line is never throttled).
  double fraction = duration > 0.0 && std::isfinite(t) ? std::clamp(t / duration, 0.0, 1.0) : 1.0;
  if (fraction > 1.0 - 1e-9) fraction = 1.0;
  nlohmann::ordered_json line = nlohmann::ordered_json::object();
  if (!admit(fraction, line)) return nullptr;
  nlohmann::ordered_json ordered{{"stage", stage_}, {"time", t}, {"duration", duration}, {"fraction", fraction},
                                 {"steps", steps}, {"eta_seconds", line["eta_seconds"]},
                                 {"elapsed_seconds", line["elapsed_seconds"]}};
  return ordered;
}

nlohmann::ordered_json ProgressTracker::count(std::size_t done, std::size_t total, const std::string& unit) {
  const double fraction = total > 0 ? std::min(1.0, static_cast<double>(done) / static_cast<double>(total)) : 1.0;
  nlohmann::ordered_json line = nlohmann::ordered_json::object();
  if (!admit(fraction, line)) return nullptr;
  nlohmann::ordered_json ordered{{"stage", stage_}, {unit, done}, {unit + "_total", total}, {"fraction", fraction},
                                 {"eta_seconds", line["eta_seconds"]}, {"elapsed_seconds", line["elapsed_seconds"]}};
  return ordered;
}

nlohmann::ordered_json progress_status(int exit_code, const std::string& out, const std::string& message) {
  // Exit codes (README): 0 done, 1 a failed run, 2 bad input, 128 + signal interrupted.
  const char* status = exit_code == 0 ? "done" : exit_code > 128 ? "interrupted" : "failed";
  return {{"status", status}, {"exit_code", exit_code}, {"out", out}, {"message", message}};
}

namespace {
std::atomic<bool> g_status_written{false};  // one process, one command: one status line
}  // namespace

bool status_line_written() { return g_status_written.load(); }

void write_progress_line(const nlohmann::ordered_json& line) {
  static std::mutex lock;
  const std::string text = line.dump() + "\n";
  const std::lock_guard<std::mutex> guard(lock);
  if (line.contains("status")) g_status_written = true;
  std::fwrite(text.data(), 1, text.size(), stderr);
  std::fflush(stderr);
}

}  // namespace jellysim::experiments
