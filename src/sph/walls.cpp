#include "jellysim/sph/walls.hpp"

namespace jellysim::sph {

std::vector<Wall> box_walls(Vec2 lo, Vec2 hi, bool mirror) {
  return {Wall{lo, {1.0, 0.0}, mirror}, Wall{hi, {-1.0, 0.0}, mirror}, Wall{lo, {0.0, 1.0}, mirror},
          Wall{hi, {0.0, -1.0}, mirror}};
}

bool reflect_from_walls(const std::vector<Wall>& walls, Vec2& position, Vec2& velocity) {
  bool changed = false;
  for (const Wall& w : walls) {
    const double d = w.distance(position);
    if (d >= 0.0) continue;
    position = w.mirror_position(position);
    if (dot(velocity, w.normal) < 0.0) velocity = w.mirror_velocity(velocity);
    changed = true;
  }
  return changed;
}

}  // namespace jellysim::sph
