#pragma once
// Helpers shared by the shell module's tests.
#include <random>

#include "jellysim/shell/shell_body.hpp"

namespace jellysim::shell::testing {

/// x with every coordinate moved by up to `amplitude` (m), deterministic for a seed.
inline Vector jiggled(const Vector& x, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += amplitude * u(rng);
  return y;
}

}  // namespace jellysim::shell::testing
