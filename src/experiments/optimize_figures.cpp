// The figures `jellysim optimize` judges a stroke by (docs/control.md, "Objectives"), measured on a
// swim's recording: the bell's progress per cycle after the first, the muscles' work, the cost of
// transport, an efficiency, the distance from an animator's mark, the peak muscle tension.
#include "jellysim/experiments/optimize.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/scene/resolve.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::experiments {
namespace {

constexpr double kGravity = 9.81;  ///< m/s², for the cost of transport

/// metrics' position at time t, linear between frames (clamped to the recording).
double position_at(const std::vector<jellyfish::MetricsRow>& rows, double t) {
  if (rows.empty()) return 0.0;
  if (t <= rows.front().t) return rows.front().position;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].t >= t) {
      const double s = (t - rows[k - 1].t) / (rows[k].t - rows[k - 1].t);
      return rows[k - 1].position + s * (rows[k].position - rows[k - 1].position);
    }
  }
  return rows.back().position;
}

Vec2 centroid(const jellyfish::SliceFrame& f) {
  Vec2 sum{};
  for (const Vec2& p : f.umbrella) sum += p;
  return f.umbrella.empty() ? sum : (1.0 / static_cast<double>(f.umbrella.size())) * sum;
}

/// The bell's centroid at time t, linear between recorded frames.
Vec2 centroid_at(const std::vector<jellyfish::SliceFrame>& frames, double t) {
  for (std::size_t k = 1; k < frames.size(); ++k) {
    if (frames[k].time_s >= t) {
      const double s = std::clamp((t - frames[k - 1].time_s) / (frames[k].time_s - frames[k - 1].time_s), 0.0, 1.0);
      return centroid(frames[k - 1]) + s * (centroid(frames[k]) - centroid(frames[k - 1]));
    }
  }
  return frames.empty() ? Vec2{} : centroid(frames.back());
}

/// The muscles' positive work from t_from on (docs/control.md): W = ∫ Σ_m T_m · max(0, −dl_m/dt) dt,
/// the work of muscles shortening under tension (T > 0), trapezoidal in T over each frame interval;
/// lengthening muscles are not credited (a muscle cannot take the work back). Per metre of depth
/// (planar slice, J/m) or of the whole body of revolution (rings: a ring muscle of hoop tension T
/// whose diameter l shrinks by dl does π T dl, so the sum carries π).
double muscle_work(const std::vector<jellyfish::SliceFrame>& frames, double t_from, bool rings) {
  double work = 0.0;
  for (std::size_t k = 1; k < frames.size(); ++k) {
    if (frames[k].time_s <= t_from) continue;
    const auto& a = frames[k - 1].muscles;
    const auto& b = frames[k].muscles;
    for (std::size_t m = 0; m < std::min(a.size(), b.size()); ++m) {
      const double tension = std::max(0.0, 0.5 * (a[m].tension_n + b[m].tension_n));
      work += tension * std::max(0.0, a[m].length_m - b[m].length_m);
    }
  }
  return rings ? std::numbers::pi * work : work;
}

/// The muscle sheet's largest total pull over the run: max over frames of Σ_m max(T_m, 0) (N per
/// metre of depth; rings: the planar spring forces). The sum, unlike one spring's tension, does not
/// depend on how many springs the marker spacing gives the sheet; over a fixed muscle cross-section
/// it is the peak mean muscle stress times that section.
double peak_tension(const std::vector<jellyfish::SliceFrame>& frames) {
  double peak = 0.0;
  for (const auto& f : frames) {
    double sum = 0.0;
    for (const auto& m : f.muscles) sum += std::max(0.0, m.tension_n);
    peak = std::max(peak, sum);
  }
  return peak;
}

/// The bell's mass (docs/control.md): tissue as dense as the water, ρ ϑ L per metre of depth for the
/// planar slice (L the umbrella's arc length), ρ ϑ ∫ 2π r ds for the body of revolution.
double bell_mass(const jellyfish::SwimSettings& settings, const jellyfish::SliceFrame& f) {
  const double rho = settings.tank.density_kg_per_m3;
  const bool rings = settings.jellyfish().rings;
  const double axis_x = 0.5 * (f.umbrella.front().x + f.umbrella.back().x);
  double measure = 0.0;
  for (std::size_t k = 1; k < f.umbrella.size(); ++k) {
    const double ds = norm(f.umbrella[k] - f.umbrella[k - 1]);
    const double r = std::abs(0.5 * (f.umbrella[k].x + f.umbrella[k - 1].x) - axis_x);
    measure += rings ? 2.0 * std::numbers::pi * r * ds : ds;
  }
  return rho * f.thickness_m * measure;
}

}  // namespace

std::map<std::string, double> stroke_figures(const jellyfish::SwimSettings& settings, const SwimRecording& rec,
                                             const std::optional<Vec2>& target, double target_time_s) {
  std::map<std::string, double> f;
  const double frequency = settings.jellyfish().frequency_hz;
  const double period = frequency > 0 ? 1.0 / frequency : INFINITY;
  const double cycles = std::floor(rec.stats.simulated_seconds * frequency + 1e-6);  // whole cycles recorded
  const double counted = cycles - 1.0;  // the cycles after the first
  const double travelled = counted >= 1 ? position_at(rec.metrics, cycles * period) - position_at(rec.metrics, period) : 0.0;
  f["distance_per_cycle"] = counted >= 1 ? travelled / counted : 0.0;
  f["speed"] = f["distance_per_cycle"] * frequency;
  const double work = rec.frames.empty() ? 0.0 : muscle_work(rec.frames, period, settings.jellyfish().rings);
  const double mass = rec.frames.empty() ? 0.0 : bell_mass(settings, rec.frames.front());
  f["muscle_work"] = work;
  f["cost_of_transport"] = travelled > 0 && mass > 0 ? work / (mass * kGravity * travelled) : INFINITY;
  // Kinetic-energy efficiency: ½ m U² per cycle (U the mean speed) over the muscle work per cycle.
  const double speed = f["speed"];
  f["efficiency"] = work > 0 && counted >= 1 ? 0.5 * mass * speed * speed / (work / counted) : 0.0;
  f["peak_muscle_tension"] = peak_tension(rec.frames);
  double vmin = INFINITY, amin = INFINITY;
  for (const auto& r : rec.metrics) {
    vmin = std::min(vmin, r.volume_ratio);
    amin = std::min(amin, r.aperture_ratio);
  }
  f["min_volume_ratio"] = rec.metrics.empty() ? 0.0 : vmin;
  f["min_aperture_ratio"] = rec.metrics.empty() ? 0.0 : amin;
  f["distance_travelled"] = rec.metrics.empty() ? 0.0 : rec.metrics.back().position;
  if (target) f["reach"] = norm(centroid_at(rec.frames, target_time_s) - *target);
  return f;
}

Evaluation evaluate_swim(const config::Config& config, const std::optional<Vec2>& target, double target_time_s) {
  const jellyfish::SwimSettings settings = read_swim_settings(config);
  SwimOutputOptions options = read_output_options(config);
  options.pictures = false;
  options.vtk = false;
  const SwimRecording rec = run_swim(settings, options, nullptr, {});
  Evaluation e;
  e.failed = !rec.stats.failure.empty() || rec.metrics.empty();
  if (!e.failed) e.figures = stroke_figures(settings, rec, target, target_time_s);
  for (const auto& [name, value] : e.figures) e.failed = e.failed || std::isnan(value);
  return e;
}

}  // namespace jellysim::experiments
