#pragma once
// Ken Perlin's improved noise (2002, "Improving Noise", SIGGRAPH; reference Java implementation
// ImprovedNoise.java), reproduced operation for operation so that it returns the reference's
// doubles bit for bit (build with -ffp-contract=off). Thesis §7.3 uses it as Q_P(x, y, z).
#include <array>
#include <cstdint>

namespace jellysim::geometry {

class ImprovedNoise {
 public:
  /// seed 0: Perlin's published permutation (the reference). Any other seed: that permutation
  /// shuffled by a Fisher–Yates pass driven by splitmix64(seed) — a different, equally valid
  /// noise field (a different individual jellyfish), identical on every platform.
  explicit ImprovedNoise(std::uint64_t seed = 0);

  /// Q_P(x, y, z) ∈ [−1, 1] (in practice about ±0.9), zero at integer lattice points, C2.
  double operator()(double x, double y, double z) const;

  std::uint64_t seed() const { return seed_; }

 private:
  std::uint64_t seed_;
  std::array<int, 512> p_{};
};

/// Perlin's reference noise (seed 0).
double perlin_noise(double x, double y, double z);

}  // namespace jellysim::geometry
