#include "jellysim/jellyfish/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

namespace jellysim::jellyfish {

namespace {

constexpr double kPi = std::numbers::pi;

/// Central differences of y(t) (one-sided at the ends).
std::vector<double> derivative(const std::vector<double>& t, const std::vector<double>& y) {
  const std::size_t n = y.size();
  std::vector<double> d(n, 0.0);
  if (n < 2) return d;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 == n ? k : k + 1;
    d[k] = (y[b] - y[a]) / (t[b] - t[a]);
  }
  return d;
}

/// du/dt of Daniel's model for given V, A, thrust and u.
double daniel_acceleration(double u, double volume, double aperture, double thrust, const MetricsSettings& s) {
  if (!(volume > 0.0) || !(aperture > 0.0)) return 0.0;
  const double shape = 1.5 * volume / aperture * std::sqrt(kPi / aperture);  // h/r
  const double added_mass = std::pow(shape, 1.4);
  const double r = std::sqrt(aperture / kPi);
  double drag = 0.0;
  if (u != 0.0) {
    const double re = 2.0 * r * std::abs(u) / s.viscosity_m2_per_s;
    const double cd = 24.0 * std::pow(re, -0.7);
    drag = 0.5 * s.density_kg_per_m3 * cd * aperture * u * std::abs(u);
  }
  return (thrust - drag) / (s.density_kg_per_m3 * volume * (1.0 + added_mass));
}

}  // namespace

BellShape measure_bell(const std::vector<Vec2>& umbrella) {
  BellShape b;
  const std::size_t n = umbrella.size();
  if (n < 3) return b;
  for (Vec2 p : umbrella) b.centroid += p;
  b.centroid = b.centroid / static_cast<double>(n);
  const Vec2 aperture = 0.5 * (umbrella.front() + umbrella.back());
  const Vec2 apex = umbrella[n / 2];
  const Vec2 axis = apex - aperture;
  b.axis = norm(axis) > 0.0 ? axis / norm(axis) : Vec2{0.0, 1.0};
  // Levels from the aperture (k = 0) to the apex: radius = half the width of opposing points,
  // height = position of their midpoint along the axis. Frustums between levels (solid of revolution).
  double volume = 0.0;
  double prev_r = 0.5 * norm(umbrella.back() - umbrella.front());
  double prev_h = 0.0;
  for (std::size_t k = 1; k <= n / 2; ++k) {
    const Vec2 a = umbrella[k], c = umbrella[n - 1 - k];
    const double r = k == n / 2 ? 0.0 : 0.5 * norm(c - a);
    const double h = dot(0.5 * (a + c) - aperture, b.axis);
    volume += kPi / 3.0 * (h - prev_h) * (prev_r * prev_r + prev_r * r + r * r);
    prev_r = r;
    prev_h = h;
  }
  b.volume_m3 = std::abs(volume);
  const double r0 = 0.5 * norm(umbrella.back() - umbrella.front());
  b.aperture_area_m2 = kPi * r0 * r0;
  double twice = 0.0;  // shoelace over the umbrella closed by the aperture chord
  for (std::size_t k = 0; k < n; ++k) twice += cross(umbrella[k], umbrella[(k + 1) % n]);
  b.cavity_area_m2 = 0.5 * std::abs(twice);
  return b;
}

std::vector<double> daniel_velocity(const std::vector<double>& t, const std::vector<double>& volume,
                                    const std::vector<double>& aperture, const std::vector<double>& thrust,
                                    const MetricsSettings& s) {
  std::vector<double> u(t.size(), 0.0);
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    const double h = t[k + 1] - t[k];
    auto lerp = [&](const std::vector<double>& y, double w) { return (1.0 - w) * y[k] + w * y[k + 1]; };
    auto f = [&](double w, double uu) {
      return daniel_acceleration(uu, lerp(volume, w), lerp(aperture, w), lerp(thrust, w), s);
    };
    // Classical RK4 (as Dabiri & Gharib integrated eq. 6.5).
    const double k1 = f(0.0, u[k]);
    const double k2 = f(0.5, u[k] + 0.5 * h * k1);
    const double k3 = f(0.5, u[k] + 0.5 * h * k2);
    const double k4 = f(1.0, u[k] + h * k3);
    u[k + 1] = u[k] + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return u;
}

std::string non_finite_metric(const std::vector<MetricsRow>& rows) {
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const MetricsRow& r = rows[k];
    const std::pair<const char*, double> values[] = {
        {"t", r.t}, {"position", r.position}, {"lateral", r.lateral}, {"velocity", r.velocity},
        {"acceleration", r.acceleration}, {"volume", r.volume}, {"aperture_area", r.aperture_area},
        {"volume_ratio", r.volume_ratio}, {"aperture_ratio", r.aperture_ratio}, {"thrust", r.thrust},
        {"daniel_velocity", r.daniel_velocity}, {"daniel_position", r.daniel_position}};
    for (const auto& [name, value] : values)
      if (!std::isfinite(value)) {
        std::ostringstream s;
        s << "the metric '" << name << "' is not finite (" << value << ") at t = " << r.t << " s (frame " << k << ")";
        return s.str();
      }
  }
  return {};
}

std::vector<MetricsRow> compute_metrics(const std::vector<SliceFrame>& frames, const MetricsSettings& s) {
  std::vector<MetricsRow> rows(frames.size());
  if (frames.empty()) return rows;
  const BellShape rest = measure_bell(frames.front().umbrella);
  const Vec2 axis0 = frames.front().axis;
  const Vec2 across = {axis0.y, -axis0.x};
  std::vector<double> t, pos, vol, ap;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const BellShape b = measure_bell(frames[k].umbrella);
    MetricsRow& r = rows[k];
    r.t = frames[k].time_s;
    r.position = dot(b.centroid - rest.centroid, axis0);
    r.lateral = dot(b.centroid - rest.centroid, across);
    r.volume = b.volume_m3;
    r.aperture_area = b.aperture_area_m2;
    r.volume_ratio = rest.volume_m3 > 0 ? b.volume_m3 / rest.volume_m3 : 0.0;
    r.aperture_ratio = rest.aperture_area_m2 > 0 ? b.aperture_area_m2 / rest.aperture_area_m2 : 0.0;
    t.push_back(r.t);
    pos.push_back(r.position);
    vol.push_back(r.volume);
    ap.push_back(r.aperture_area);
  }
  const std::vector<double> vel = derivative(t, pos);
  const std::vector<double> acc = derivative(t, vel);
  const std::vector<double> dvdt = derivative(t, vol);
  std::vector<double> thrust(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    rows[k].velocity = vel[k];
    rows[k].acceleration = acc[k];
    // Eq. 6.4, F_T = ρ (dV/dt)² / A, signed: forward while V decreases (water expelled).
    const double magnitude = ap[k] > 0 ? s.density_kg_per_m3 * dvdt[k] * dvdt[k] / ap[k] : 0.0;
    thrust[k] = dvdt[k] < 0 ? magnitude : -magnitude;
    rows[k].thrust = thrust[k];
  }
  const std::vector<double> u = daniel_velocity(t, vol, ap, thrust, s);
  double x = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (k > 0) x += 0.5 * (u[k] + u[k - 1]) * (t[k] - t[k - 1]);
    rows[k].daniel_velocity = u[k];
    rows[k].daniel_position = x;
  }
  return rows;
}

double cycles(double t_end_s, double frequency_hz) { return t_end_s * frequency_hz; }

double dominant_frequency(const std::vector<double>& values, double dt) {
  const std::size_t n = values.size();
  if (n < 4) return 0.0;
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(n);
  double best_power = -1.0, best_f = 0.0;
  for (std::size_t k = 1; k <= n / 2; ++k) {
    double re = 0.0, im = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double a = 2.0 * kPi * static_cast<double>(k * j) / static_cast<double>(n);
      re += (values[j] - mean) * std::cos(a);
      im -= (values[j] - mean) * std::sin(a);
    }
    const double power = re * re + im * im;
    if (power > best_power) {
      best_power = power;
      best_f = static_cast<double>(k) / (static_cast<double>(n) * dt);
    }
  }
  return best_f;
}

}  // namespace jellysim::jellyfish
