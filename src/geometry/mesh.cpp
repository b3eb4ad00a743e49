#include "jellysim/geometry/mesh.hpp"

#include <algorithm>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {

const MeshPart* Mesh::part(std::string_view name) const {
  for (const MeshPart& p : parts)
    if (p.name == name) return &p;
  return nullptr;
}

VertexRange vertex_range(const Mesh& mesh, const MeshPart& part) {
  if (part.index_count == 0) throw InputError("mesh part '" + part.name + "' has no triangles");
  const auto begin = mesh.indices.begin() + part.first_index;
  const auto [lo, hi] = std::minmax_element(begin, begin + part.index_count);
  return {*lo, *hi - *lo + 1};
}

bool same_topology(const Mesh& a, const Mesh& b) {
  if (a.positions.size() != b.positions.size() || a.normals.size() != b.normals.size() || a.indices != b.indices ||
      a.parts.size() != b.parts.size())
    return false;
  for (std::size_t k = 0; k < a.parts.size(); ++k) {
    const MeshPart &p = a.parts[k], &q = b.parts[k];
    if (p.name != q.name || p.first_index != q.first_index || p.index_count != q.index_count) return false;
  }
  return true;
}

Bounds bounds(const Mesh& mesh) {
  if (mesh.positions.empty()) return {};
  Bounds b{mesh.positions.front(), mesh.positions.front()};
  for (const Vec3& p : mesh.positions) {
    b.min = {std::min(b.min.x, p.x), std::min(b.min.y, p.y), std::min(b.min.z, p.z)};
    b.max = {std::max(b.max.x, p.x), std::max(b.max.y, p.y), std::max(b.max.z, p.z)};
  }
  return b;
}

void validate_animation(const Animation& animation) {
  if (animation.frames.empty()) throw InputError("animation has no frames");
  if (animation.times_s.size() != animation.frames.size())
    throw InputError("animation has " + std::to_string(animation.frames.size()) + " frames but " +
                     std::to_string(animation.times_s.size()) + " times");
  for (std::size_t k = 1; k < animation.frames.size(); ++k) {
    if (!(animation.times_s[k] > animation.times_s[k - 1]))
      throw InputError("animation times must increase (frame " + std::to_string(k) + ")");
    if (!same_topology(animation.frames[0], animation.frames[k]))
      throw InputError("animation frame " + std::to_string(k) + " has a different topology from frame 0");
  }
}

}  // namespace jellysim::geometry
