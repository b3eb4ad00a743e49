#pragma once
// Shared helpers for the SPH tests: a seeded random source.
#include "jellysim/math/vec2.hpp"

#include <random>

namespace jellysim::sph::test {

class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }
  Vec2 point(double half_width = 1.0) { return {uniform(-half_width, half_width), uniform(-half_width, half_width)}; }

 private:
  std::mt19937 engine_;
};

}  // namespace jellysim::sph::test
