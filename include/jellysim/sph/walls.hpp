#pragma once
// Static straight boundaries (thesis §5.1.3): half-planes that keep particles and body points on
// their inner side. Fluid particles within h of a mirroring wall see a mirrored twin (position and
// velocity reflected), whose pressure pushes them off the wall and whose viscosity aligns them with
// it; anything that still reaches the wall collides elastically with it (infinite mass).
#include "jellysim/math/vec2.hpp"

#include <vector>

namespace jellysim::sph {

struct Wall {
  Vec2 point;             ///< a point on the wall line (m)
  Vec2 normal{0.0, 1.0};  ///< unit normal pointing into the allowed side
  bool mirror = true;     ///< create mirrored particles for SPH (eq. §5.1.3)

  /// Signed distance of x from the wall line, positive on the allowed side (m).
  double distance(Vec2 x) const { return dot(x - point, normal); }
  /// Reflection of a position across the wall line.
  Vec2 mirror_position(Vec2 x) const { return x - 2.0 * distance(x) * normal; }
  /// Reflection of a velocity (normal component negated, tangential kept).
  Vec2 mirror_velocity(Vec2 v) const { return v - 2.0 * dot(v, normal) * normal; }
};

/// The four walls of an axis-aligned box [lo, hi] (m), normals pointing inwards.
std::vector<Wall> box_walls(Vec2 lo, Vec2 hi, bool mirror = true);

/// Elastic collision of a point with the walls (infinite wall mass): a point behind a wall is
/// reflected back across it and, when moving outwards, its normal velocity is reversed. Energy is
/// conserved. Returns true when something changed.
bool reflect_from_walls(const std::vector<Wall>& walls, Vec2& position, Vec2& velocity);

}  // namespace jellysim::sph
