#pragma once
// The three kinds of surface variation of thesis §7.3 (Figure 8.19): structural (eqs. 7.10/7.11),
// compression (eqs. 7.13–7.15) and unstructured Perlin noise (eqs. 7.16–7.18). Each returns a
// displacement in metres along the surface normal.
#include <cstdint>
#include <vector>

#include "jellysim/geometry/perlin.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"

namespace jellysim::geometry {

struct NoiseSettings {
  /// Weights of Figure 8.19: c_sum = w_s c_structural + w_c c_compressed + w_u c_unstructured.
  double structural_weight = 0.01875;
  double compression_weight = 0.125;
  double unstructured_weight = 0.45;
  double structural_frequency = 9.0;  ///< f of eqs. 7.10/7.11 (Fig. 8.21: 9)
  bool structural_absolute = true;    ///< eq. 7.11 |sin fσ| (Fig. 8.19) instead of eq. 7.10
  /// Frequency of the ridge term of eq. 7.14. As printed it is 1 (sin σ_j), a single lobe around
  /// the bell, not ridges; 9 gives the ridges the text describes (docs/rendering.md).
  double compression_frequency = 9.0;
  double max_contraction = 0.56;      ///< γ of eq. 7.13 (§7.1: 0.56)
  double latitude_frequency = 2.0;    ///< eq. 7.18: Q_P(2 d_i, ·, ·)
  double longitude_frequency = 8.0;   ///< eq. 7.18: Q_P(·, 8 d_j, ·)
  /// Noise time coordinate per second: eq. 7.18's 0.01 t reads as 0.01 per frame at 30 frames/s.
  double time_frequency_hz = 0.3;
  /// The length the noise equations are measured in (ϑ of eqs. 7.10–7.15 and the unit of eq. 7.18),
  /// metres; 0 = the bell height of the first frame. With the thesis's ϑ = 0.02 cm the Fig. 8.19
  /// weights give micrometre ridges, so the weights are read as fractions of the bell size.
  double length_scale_m = 0.0;
  bool tentacles = true;              ///< apply the unstructured noise to tentacles too (§7.3)
  /// Unstructured noise moves each subumbrellar point with its exumbrellar partner (−c along its
  /// own, opposite normal), so the noise bends the bell instead of changing its thickness by 2c as
  /// the literal reading of eqs. 7.16/7.18 does (both sides at equal d_i, each along its own normal).
  bool bend_shell = true;
  std::uint64_t seed = 1;             ///< Perlin permutation (0 = Perlin's reference table)
};

/// Eq. 7.10 (ϑ sin fσ) or eq. 7.11 (ϑ |sin fσ|), metres.
double structural_noise(double length_m, double frequency, double sigma_rad, bool absolute);
/// How much of a ring's variation with `cycles_per_ring` cycles a ring of `disc_points` points can
/// draw as a smooth curve: 1 up to disc_points/8 (8 points a cycle), 0 from disc_points/4 (4 points
/// a cycle, where straight segments between samples read as a saw-tooth), a raised cosine between.
double resolvable_fraction(double cycles_per_ring, int disc_points);
/// The structural noise as a ring of `disc_points` points can draw it: eq. 7.10, or eq. 7.11 as its
/// Fourier series (|sin x| = 2/π − (4/π) Σ cos(2mx)/(4m² − 1)), each term scaled by its
/// resolvable_fraction (like a texture's mipmap: detail finer than the mesh fades to its mean).
/// With the default f = 9 and 64 points a ridge of |sin fσ| got 3.6 points, its cusps sampled as a
/// saw-toothed rim; now the 64-point ring keeps the ridges' mean offset (2/π of the amplitude) and
/// draws the ridges from ≈ 110 points on, fully from 144.
double structural_noise_resolved(double length_m, double frequency, double sigma_rad, bool absolute, int disc_points);

/// Amount of contraction of a muscle: 0 at l_c = l_r, 1 at l_c = γ l_r, clamped to [0, 1]. This is
/// 1 − eq. 7.13 (eq. 7.13 as printed is 1 when relaxed, against the text's "proportional to the
/// amount of contraction"; docs/rendering.md).
double contraction_amount(double length_m, double rest_length_m, double gamma);

/// Eq. 7.15: ϑ κ {0.34 + 0.17(½ sin(f_c σ) + ½)}, metres; exumbrellar side only.
double compression_noise(double length_m, double contraction, double frequency, double sigma_rad);
/// The braces of eq. 7.15, 0.34 + 0.17(½ sin(f_c σ) + ½): compression_noise = ϑ κ × this.
double compression_ridge(double frequency, double sigma_rad);

/// Eq. 7.16: d_i = min(|i − i_out|, |i − i_in|) / i_max.
double latitude_distance(int i, int i_out, int i_in, int i_max);
/// Eq. 7.17: d_j = min(j_max − j, j) / j_max.
double longitude_distance(int j, int j_max);

/// Eq. 7.18: d_i Q_P(a d_i, b d_j, ω t) · length, metres.
double unstructured_noise(const ImprovedNoise& noise, const NoiseSettings& settings, double length_m, double d_i,
                          double d_j, double time_s);

/// Contraction amount at umbrella parameter u ∈ [0, n − 1] (the point index on the simulated
/// umbrella). Each muscle sits at the mean index distance of its two ends from their aperture
/// tips; the amount is interpolated linearly in that distance and held constant beyond the
/// outermost muscles; 0 when there are no muscles. Both sides of the slice get the same value.
double contraction_at(const std::vector<jellyfish::MuscleState>& muscles, std::size_t umbrella_points, double u,
                      double gamma);

}  // namespace jellysim::geometry
