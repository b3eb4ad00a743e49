#pragma once
// What a tank run records per frame, as physics (no files, no pixels): the jellyfish's slices,
// the obstacles' fluid forces and outlines, the IB2d structures' centroids, optionally the
// tracers; the metrics of every jellyfish (thesis §8.3) and the run's summary figures computed
// from them. `experiments` writes them to files.
#include <string>
#include <vector>

#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::jellyfish {

struct SwimRecord {
  std::vector<double> frame_times;                  ///< s, one per recorded frame
  std::vector<SliceFrame> frames;                   ///< the first jellyfish (metrics.csv)
  std::vector<MetricsRow> metrics;
  std::vector<std::vector<SliceFrame>> others;      ///< jellyfish 2, 3, …
  std::vector<std::vector<MetricsRow>> other_metrics;  ///< their metrics
  std::vector<std::vector<Vec2>> obstacle_forces;   ///< per frame, per obstacle: fluid force, N/m
  std::vector<std::vector<std::vector<Vec2>>> obstacle_outlines;  ///< per frame, per obstacle: its markers, m
  std::vector<std::vector<Vec2>> structure_centroids;  ///< per frame, per IB2d structure: centroid without targets, m
  std::vector<std::vector<Vec2>> tracers;           ///< per frame, when recorded
};

/// Appends the simulation's current state as a frame (tracers when `with_tracers`).
void record_frame(const SwimSimulation& s, bool with_tracers, SwimRecord& rec);

/// Every jellyfish's metrics from its recorded frames; "" or, when a metric is not finite (a
/// divergence even where the state stayed finite), "numerical instability: …" naming the jellyfish.
std::string compute_school_metrics(const SwimSettings& settings, SwimRecord& rec);

/// The first jellyfish's swim in figures (SwimSettings::school not empty; zeros without metrics).
struct SwimSummary {
  double cycles = 0.0;
  double distance_m = 0.0;        ///< bell centroid travelled
  double lateral_drift_m = 0.0;
  double mean_speed_m_per_s = 0.0;
  double volume_frequency_hz = 0.0;  ///< dominant frequency of the bell volume
  double min_volume_ratio = 0.0;
  double min_aperture_ratio = 0.0;
  double daniel_distance_m = 0.0;  ///< Daniel's model (eq. 6.5)
};
SwimSummary summarize_swim(const SwimSettings& settings, const SwimRecord& rec, double simulated_seconds);

/// Per obstacle, the mean fluid force over the second half of the run (after the start-up transient).
std::vector<Vec2> mean_obstacle_forces(const SwimRecord& rec, std::size_t obstacle_count);

/// Per IB2d structure, its centroid's displacement from the first frame to the last.
std::vector<Vec2> structure_displacements(const SwimRecord& rec, std::size_t structure_count);

}  // namespace jellysim::jellyfish
