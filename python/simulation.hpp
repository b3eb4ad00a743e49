#pragma once
// The state behind jellysim.Simulation (docs/python.md): a jellyfish scene stepped on the frame
// clock of `jellysim simulate`, so that advance(seconds) from t = 0 takes exactly the steps of
// `jellysim simulate --duration seconds` and records the same frames (the rows of metrics.csv and
// slices.csv). Plain C++: the pybind11 layer (module.cpp) only converts.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"

namespace jellysim::python {

/// A resolved and validated jellyfish scene: what `jellysim simulate` runs.
struct Scene {
  config::Config config;
  jellyfish::SwimSettings settings;
  experiments::SwimOutputOptions output;
};

/// The built-in jellyfish scene (simulate's defaults), `overlay` (a scene file or TOML text; its
/// `scene`, if given, must be "jellyfish") and the key=value overrides, resolved by
/// scene::resolve_config and validated as `simulate` validates them; throws InputError with the
/// CLI's messages.
Scene resolve_scene(const config::Config* overlay, const std::string& overlay_name, const std::vector<std::string>& sets);

class Simulation {
 public:
  explicit Simulation(const Scene& scene);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// One coupled step toward the next frame time (simulate's landing rule); records the frame when
  /// the step lands on it. Throws RunError when the run cannot go on.
  void step();
  /// Steps to the frame nearest the duration asked for so far (the sum of every advance's seconds,
  /// from the time step() reached if beyond it) as `simulate --duration` does; throws RunError.
  /// `stop` (optional) is asked after every frame: true ends the call there (e.g. Ctrl-C), and the
  /// next advance counts from the time reached. Returns false when stopped.
  bool advance(double seconds, const std::function<bool()>& stop = {});

  double time_s() const { return sim_->time_s(); }
  long steps() const { return sim_->steps(); }
  /// The time of the frame the advance() calls so far end on (their progress reports' duration).
  double target_s() const {
    const double interval = scene_.settings.frame_interval_s;
    return static_cast<double>(std::llround(requested_s_ / interval)) * interval;
  }
  const Scene& scene() const { return scene_; }
  const jellyfish::SwimSimulation& swim() const { return *sim_; }
  /// Jellyfish j's markers as slices.csv lists them: the umbrella (left tip, apex, right tip),
  /// then each tentacle strand.
  std::vector<Vec2> markers(std::size_t jellyfish) const;
  /// Recorded frames of the first jellyfish (frame 0 at t = 0, then one per frame_interval).
  const std::vector<jellyfish::SliceFrame>& frames() const { return frames_; }
  /// metrics.csv's rows for the recorded frames (jellyfish::compute_metrics, as simulate).
  std::vector<jellyfish::MetricsRow> metrics() const;
  /// The 3D mesh `jellysim run` builds for recorded frame k (default render settings).
  geometry::FrameGeometry mesh(std::size_t frame) const;

  /// Simulations alive now (the Python tests check that dropped ones are freed).
  static long live_count() { return live_.load(); }

 private:
  /// One step toward frame_time with the landing rule of SwimSimulation::run.
  std::string step_toward(double frame_time);
  void record_frame();

  Scene scene_;
  std::unique_ptr<jellyfish::SwimSimulation> sim_;
  std::vector<jellyfish::SliceFrame> frames_;
  std::int64_t frames_emitted_ = 0;
  double requested_s_ = 0.0;  ///< the duration the advance() calls so far asked for
  std::string failure_;  ///< why the run cannot go on ("" while it can)
  mutable std::unique_ptr<geometry::GeometryBuilder> builder_;
  static std::atomic<long> live_;
};

}  // namespace jellysim::python
