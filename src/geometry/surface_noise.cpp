#include "jellysim/geometry/surface_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <utility>

namespace jellysim::geometry {

double structural_noise(double length_m, double frequency, double sigma_rad, bool absolute) {
  const double s = std::sin(frequency * sigma_rad);
  return length_m * (absolute ? std::abs(s) : s);  // eq. 7.11 / eq. 7.10
}

double resolvable_fraction(double cycles_per_ring, int disc_points) {
  const double full = 0.125 * disc_points, none = 0.25 * disc_points;  // 8 and 4 samples per cycle
  if (cycles_per_ring <= full) return 1.0;
  if (cycles_per_ring >= none) return 0.0;
  return 0.5 * (1.0 + std::cos(std::numbers::pi * (cycles_per_ring - full) / (none - full)));
}

double structural_noise_resolved(double length_m, double frequency, double sigma_rad, bool absolute,
                                 int disc_points) {
  const double f = std::abs(frequency);
  if (!absolute) return length_m * resolvable_fraction(f, disc_points) * std::sin(frequency * sigma_rad);
  // |sin x| = 2/π − (4/π) Σ_{m ≥ 1} cos(2 m x) / (4 m² − 1): its m-th term has 2 m f cycles per ring.
  double sum = 2.0 / std::numbers::pi;
  for (int m = 1; f > 0.0; ++m) {
    const double fraction = resolvable_fraction(2.0 * m * f, disc_points);
    if (fraction == 0.0) break;
    sum -= fraction * (4.0 / std::numbers::pi) * std::cos(2.0 * m * f * sigma_rad) / (4.0 * m * m - 1.0);
  }
  return length_m * (f > 0.0 ? sum : 0.0);
}

double contraction_amount(double length_m, double rest_length_m, double gamma) {
  const double printed = (length_m - gamma * rest_length_m) / (rest_length_m - gamma * rest_length_m);  // eq. 7.13
  return std::clamp(1.0 - printed, 0.0, 1.0);
}

double compression_ridge(double frequency, double sigma_rad) {
  const double where = 0.5 * std::sin(frequency * sigma_rad) + 0.5;  // eq. 7.14
  return 0.34 + 0.17 * where;                                        // eq. 7.15's braces
}

double compression_noise(double length_m, double contraction, double frequency, double sigma_rad) {
  return length_m * contraction * compression_ridge(frequency, sigma_rad);  // eq. 7.15
}

double latitude_distance(int i, int i_out, int i_in, int i_max) {
  return static_cast<double>(std::min(std::abs(i - i_out), std::abs(i - i_in))) / i_max;  // eq. 7.16
}

double longitude_distance(int j, int j_max) {
  return static_cast<double>(std::min(j_max - j, j)) / j_max;  // eq. 7.17
}

double unstructured_noise(const ImprovedNoise& noise, const NoiseSettings& s, double length_m, double d_i, double d_j,
                          double time_s) {
  // Eq. 7.18: c = d_i Q_P(2 d_i, 8 d_j, 0.01 t); the d_i factor attenuates the noise at the apex.
  return length_m * d_i *
         noise(s.latitude_frequency * d_i, s.longitude_frequency * d_j, s.time_frequency_hz * time_s);
}

double contraction_at(const std::vector<jellyfish::MuscleState>& muscles, std::size_t umbrella_points, double u,
                      double gamma) {
  if (muscles.empty()) return 0.0;
  // Each muscle sits at the distance (in point indices) of its ends from the aperture tips.
  const double last = static_cast<double>(umbrella_points - 1);
  std::vector<std::pair<double, double>> samples;  // (distance from the tip, contraction)
  for (const auto& m : muscles) {
    const double from_tip = 0.5 * (std::min(m.a, m.b) + (last - std::max(m.a, m.b)));
    samples.emplace_back(from_tip, contraction_amount(m.length_m, m.rest_length_m, gamma));
  }
  std::sort(samples.begin(), samples.end());
  const double x = std::min(u, last - u);  // this sample's distance from the nearer tip
  if (x <= samples.front().first) return samples.front().second;
  if (x >= samples.back().first) return samples.back().second;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    if (x <= samples[k].first) {
      const auto [x0, c0] = samples[k - 1];
      const auto [x1, c1] = samples[k];
      return x1 > x0 ? c0 + (c1 - c0) * (x - x0) / (x1 - x0) : c1;
    }
  }
  return samples.back().second;
}

}  // namespace jellysim::geometry
