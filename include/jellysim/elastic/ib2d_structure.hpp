#pragma once
// A structure as IB2d describes it (github.com/nickabattista/IB2d: its .vertex, .spring,
// .d_spring, .beam, .nonInv_beam and .target files), before it becomes markers and springs of a
// Body. Pure data: io/ib2d_files.hpp reads and writes it, jellyfish/hoover_miller.hpp generates one.
// Indices are 0-based here (IB2d's files count from 1). Stiffnesses are IB2d's: its laws give a
// force density per unit length of the structure, which becomes a force on a marker when multiplied
// by the marker spacing ds (IB2d spreads f·ds; see docs/ib2d.md).
#include <vector>

#include "jellysim/math/vec2.hpp"

namespace jellysim::elastic {

/// A spring (.spring) or damped spring (.d_spring) from `master` to `slave`: tension
/// ½(α+1) k (l − RL)^α along the spring (α = 1: Hooke's law k (l − RL)).
struct Ib2dSpring {
  int master = 0, slave = 0;
  double stiffness = 0.0;    ///< k
  double rest_length = 0.0;  ///< RL, m
  double degree = 1.0;       ///< α, the optional fifth column of a .spring file
  double damping = 0.0;      ///< b, the fifth column of a .d_spring file
};

/// A torsional beam (.beam) through left, middle, right: resists changes of the cross product
/// c = (X_r − X_m) × (X_m − X_l) from its preferred value C (energy ½ k (c − C)²).
struct Ib2dBeam {
  int left = 0, middle = 0, right = 0;
  double stiffness = 0.0;  ///< k
  double curvature = 0.0;  ///< C, m²
};

/// A non-invariant beam (.nonInv_beam): resists changes of the second difference
/// D = X_l − 2 X_m + X_r from its preferred value (Cx, Cy) (energy ½ k |D − C|²).
struct Ib2dNonInvariantBeam {
  int left = 0, middle = 0, right = 0;
  double stiffness = 0.0;  ///< k
  Vec2 curvature{};        ///< (Cx, Cy), m
};

/// A target point (.target): the vertex is tied to where it starts by a force k (X_target − X).
struct Ib2dTarget {
  int point = 0;
  double stiffness = 0.0;  ///< k
};

struct Ib2dStructure {
  std::vector<Vec2> vertices;                      ///< .vertex, m
  std::vector<Ib2dSpring> springs;                 ///< .spring
  std::vector<Ib2dSpring> damped_springs;          ///< .d_spring
  std::vector<Ib2dBeam> beams;                     ///< .beam
  std::vector<Ib2dNonInvariantBeam> non_invariant_beams;  ///< .nonInv_beam
  std::vector<Ib2dTarget> targets;                 ///< .target
};

}  // namespace jellysim::elastic
