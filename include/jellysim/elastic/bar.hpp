#pragma once
// The swinging elastic bar of thesis Figure 8.1: a strand of length 0.45 and width 0.045 hanging
// from one pinned corner, point masses m = 24, springs κ_l = 75 m = 1800, gravity (0, -0.05).
#include "jellysim/elastic/body.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::elastic {

struct BarSpec {
  double length = 0.45;
  double width = 0.045;
  int segments = 10;            ///< cells along the bar, in [1, 10000]
  double point_mass = 24;
  double stiffness = 1800;      ///< κ_l of every linear spring
  double angular_stiffness = 0; ///< κ_θ of the springs along each row; 0 = none
  Vec2 pivot{0, 0};             ///< the pinned top-left corner
  double angle_rad = 0;         ///< bar direction; 0 = horizontal along +x
  Vec2 gravity{0, -0.05};
  double drag = 0;              ///< κ_d
};

/// Builds the bar at rest. Points 0..segments form the top row (point 0 at the pivot, pinned);
/// points segments+1..2 segments+1 form the bottom row, `width` below the top one (both rotated by
/// angle_rad about the pivot). Linear springs run along both rows, across every rung and along both
/// diagonals of each cell; angular springs run along each row when angular_stiffness > 0.
/// Throws std::invalid_argument naming the field and its allowed range for an invalid spec.
Body make_bar(const BarSpec& spec);

}  // namespace jellysim::elastic
