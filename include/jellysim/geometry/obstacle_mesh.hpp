#pragma once
// Rigid obstacles of a 2D scene in the 3D animation. The simulation is a slice through bodies that
// are infinitely long across it, so an obstacle's outline becomes a prism: the outline extruded
// along z over a chosen depth, centred on the slice plane (z = 0), with flat caps at both ends.
#include <cstdint>
#include <vector>

#include "jellysim/geometry/mesh.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::geometry {

/// Triangles (index triples, counter-clockwise) covering a simple polygon given counter-clockwise,
/// by ear clipping: n − 2 triangles for n vertices, fewer when some vertices are collinear with
/// their neighbours (those are dropped without a triangle). Throws std::invalid_argument for fewer
/// than three vertices, a clockwise or degenerate polygon, or one that crosses itself.
std::vector<std::uint32_t> triangulate_polygon(const std::vector<Vec2>& polygon);

/// Builds the prisms of a scene's obstacles frame after frame with one topology: the outlines'
/// vertex counts and orientation, and the caps' triangulation, come from the first frame.
class ObstaclePrisms {
 public:
  /// `first`: each obstacle's closed outline (either orientation, not self-intersecting) in the
  /// first frame; `depth_m` > 0 is the prism's extent along z. Throws std::invalid_argument for a
  /// bad outline or depth.
  ObstaclePrisms(const std::vector<std::vector<Vec2>>& first, double depth_m);

  /// Appends every prism for these outlines (same counts as the first frame's) to `mesh` as the
  /// part "obstacles": side walls, smooth across gentle bends of the outline (a circle) and sharp
  /// at corners (a box), and the two caps. Throws std::invalid_argument when a count differs.
  void append(const std::vector<std::vector<Vec2>>& outlines, Mesh& mesh) const;

 private:
  struct Prism {
    std::size_t points = 0;
    bool reversed = false;                  ///< the outline was clockwise: walk it backwards
    std::vector<std::uint32_t> cap;         ///< triangulation of the counter-clockwise outline
  };
  std::vector<Prism> prisms_;
  double half_depth_m_ = 0.0;
};

}  // namespace jellysim::geometry
