#pragma once
// Triangle meshes of the 3D jellyfish and an animation of them with one topology for every frame.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "jellysim/geometry/vec3.hpp"

namespace jellysim::geometry {

/// A named range of the triangle index list (e.g. "umbrella", "tentacles").
struct MeshPart {
  std::string name;
  std::uint32_t first_index = 0;  ///< into Mesh::indices (a multiple of 3)
  std::uint32_t index_count = 0;  ///< a multiple of 3
};

/// Indexed triangle mesh (metres), counter-clockwise seen from outside, unit per-vertex normals.
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<std::uint32_t> indices;  ///< triangle list
  std::vector<MeshPart> parts;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  /// The part with this name, or nullptr.
  const MeshPart* part(std::string_view name) const;
};

/// The block of vertices a part's triangles use: first vertex and count. The meshes built here
/// keep each part's vertices contiguous. Throws InputError for a part without triangles.
struct VertexRange {
  std::uint32_t first = 0, count = 0;
};
VertexRange vertex_range(const Mesh& mesh, const MeshPart& part);

/// Same vertex count, same index list and same parts: frames of one animation.
bool same_topology(const Mesh& a, const Mesh& b);

/// Axis-aligned bounds of the positions (empty mesh: both zero).
struct Bounds {
  Vec3 min, max;
  Vec3 centre() const { return 0.5 * (min + max); }
};
Bounds bounds(const Mesh& mesh);

/// Frames of a jellyfish animation; every frame has the first frame's topology.
struct Animation {
  std::vector<double> times_s;
  std::vector<Mesh> frames;
};

/// Throws InputError when the animation is empty, times and frames differ in count, times do not
/// increase, or a frame's topology differs from the first's.
void validate_animation(const Animation& animation);

}  // namespace jellysim::geometry
