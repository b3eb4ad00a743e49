#include "jellysim/jellyfish/swim_record.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::jellyfish {

void record_frame(const SwimSimulation& s, bool with_tracers, SwimRecord& rec) {
  rec.frame_times.push_back(s.time_s());
  if (s.jellyfish_count() > 0) rec.frames.push_back(s.jellyfish().slice_frame(s.time_s()));
  if (rec.others.size() + 1 < s.jellyfish_count()) rec.others.resize(s.jellyfish_count() - 1);
  for (std::size_t j = 1; j < s.jellyfish_count(); ++j) rec.others[j - 1].push_back(s.jellyfish(j).slice_frame(s.time_s()));
  std::vector<Vec2> forces;
  std::vector<std::vector<Vec2>> outlines;
  for (std::size_t o = 0; o < s.obstacle_count(); ++o) {
    forces.push_back(s.obstacle_force(o));
    outlines.push_back(s.obstacle_outline(o));
  }
  rec.obstacle_forces.push_back(std::move(forces));
  rec.obstacle_outlines.push_back(std::move(outlines));
  std::vector<Vec2> centroids;
  for (std::size_t k = 0; k < s.structure_count(); ++k) centroids.push_back(s.structure_centroid(k));
  rec.structure_centroids.push_back(std::move(centroids));
  if (with_tracers) rec.tracers.push_back(s.tracers().positions());
}

std::string compute_school_metrics(const SwimSettings& settings, SwimRecord& rec) {
  const MetricsSettings fluid{settings.tank.density_kg_per_m3, std::max(settings.tank.viscosity_m2_per_s, 1e-9)};
  if (!rec.frames.empty()) rec.metrics = compute_metrics(rec.frames, fluid);
  for (const auto& frames : rec.others) rec.other_metrics.push_back(compute_metrics(frames, fluid));
  for (std::size_t j = 0; j <= rec.other_metrics.size(); ++j)
    if (const std::string problem = non_finite_metric(j == 0 ? rec.metrics : rec.other_metrics[j - 1]); !problem.empty())
      return "numerical instability: " + problem + " for jellyfish " + std::to_string(j + 1);
  return {};
}

SwimSummary summarize_swim(const SwimSettings& settings, const SwimRecord& rec, double simulated_seconds) {
  SwimSummary sum;
  sum.cycles = cycles(simulated_seconds, settings.jellyfish().frequency_hz);
  sum.distance_m = rec.metrics.empty() ? 0.0 : rec.metrics.back().position;
  sum.lateral_drift_m = rec.metrics.empty() ? 0.0 : rec.metrics.back().lateral;
  sum.mean_speed_m_per_s = simulated_seconds > 0 ? sum.distance_m / simulated_seconds : 0.0;
  std::vector<double> volume;
  for (const auto& r : rec.metrics) volume.push_back(r.volume);
  sum.volume_frequency_hz = dominant_frequency(volume, settings.frame_interval_s);
  double vmin = INFINITY, amin = INFINITY;
  for (const auto& r : rec.metrics) {
    vmin = std::min(vmin, r.volume_ratio);
    amin = std::min(amin, r.aperture_ratio);
  }
  sum.min_volume_ratio = rec.metrics.empty() ? 0.0 : vmin;
  sum.min_aperture_ratio = rec.metrics.empty() ? 0.0 : amin;
  sum.daniel_distance_m = rec.metrics.empty() ? 0.0 : rec.metrics.back().daniel_position;
  return sum;
}

std::vector<Vec2> mean_obstacle_forces(const SwimRecord& rec, std::size_t obstacle_count) {
  std::vector<Vec2> means;
  for (std::size_t o = 0; o < obstacle_count; ++o) {
    Vec2 sum{};
    std::size_t n = 0;
    for (std::size_t f = rec.obstacle_forces.size() / 2; f < rec.obstacle_forces.size(); ++f, ++n) sum += rec.obstacle_forces[f][o];
    means.push_back(n > 0 ? (1.0 / static_cast<double>(n)) * sum : Vec2{});
  }
  return means;
}

std::vector<Vec2> structure_displacements(const SwimRecord& rec, std::size_t structure_count) {
  std::vector<Vec2> moved;
  for (std::size_t k = 0; k < structure_count; ++k)
    moved.push_back(rec.structure_centroids.back()[k] - rec.structure_centroids.front()[k]);
  return moved;
}

}  // namespace jellysim::jellyfish
