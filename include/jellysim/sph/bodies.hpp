#pragma once
// Spring-mass bodies for the particle-fluid scenes: the collision outline of the Figure 8.1 bar, and
// the contracting mosquito larva of Figure 8.5 (a strip with muscle springs that never collide).
#include "jellysim/elastic/bar.hpp"
#include "jellysim/elastic/body.hpp"
#include "jellysim/sph/collisions.hpp"

#include <functional>

namespace jellysim::sph {

/// Outline of a strip laid out like elastic::make_bar (top row 0..segments, bottom row
/// segments+1..2 segments+1, bottom row below the top one): bottom row left to right, then the top
/// row back, counter-clockwise.
CollisionOutline strip_outline(int segments);

struct LarvaSpec {
  Vec2 centre{0.5, 0.5};          ///< m
  double length_m = 0.4;
  double height_m = 0.05;         ///< the thesis uses h, so fluid on both sides does not interact
  int segments = 8;               ///< cells along the body, [1, 1000]
  double point_mass_kg = 1.0;
  double stiffness = 400.0;       ///< κ_l of the structural springs (N/m)
  double muscle_stiffness = 400.0;///< κ_l of the muscle springs (N/m)
  double contraction = 0.3;       ///< largest relative shortening of a muscle, [0, 0.9]
  double frequency_hz = 1.0;      ///< wriggle frequency
  double wave_cells = 0.0;        ///< phase lag per cell as a fraction of a cycle (0: whole-body bending)
};

struct Larva {
  elastic::Body body;
  CollisionOutline outline;
  std::vector<int> muscle_springs;  ///< indices into body.linear
  /// Sets the muscles' rest lengths at time t (s): each side contracts in turn.
  std::function<void(double, elastic::Body&)> muscles;
};

/// A horizontal strip centred at spec.centre with structural springs as make_bar (rows, rungs,
/// diagonals) and one muscle spring along each side per pair of cells (point c to c + 2): the top
/// ones contract with l_r(t) = l0 (1 − A (1 + sin φ)/2) and the bottom ones in antiphase, φ = 2π (f t
/// − c · wave_cells). Throws std::invalid_argument naming the field and range when invalid.
Larva make_larva(const LarvaSpec& spec);

}  // namespace jellysim::sph
