#pragma once
// Marine snow: the 2D simulation's tracer particles, carried by the simulated flow, brought into
// the 3D picture around the bell's axis as §7.3 does for the slice: tracer i at (x, y) in the slice
// plane becomes (a + (x − a) cos θ_i, y, (x − a) sin θ_i), a the axis's x, θ_i a fixed angle per
// particle (golden-angle steps, so neighbours spread around the axis). Each particle is a tiny
// tetrahedron in the mesh part "snow", so every renderer and file that draws meshes draws it.
// Motion reads against them even when the camera follows the bell.
#include <array>
#include <vector>

#include "jellysim/geometry/mesh.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::geometry {

class MarineSnow {
 public:
  /// Keeps the particles whose 3D place in the first frame lies inside `box` (lower, upper corner),
  /// and of those the fraction `density` ∈ [0, 1], evenly spread over their order (the k-th when
  /// ⌊(k + 1) density⌋ > ⌊k density⌋); `radius_m` > 0 is each speck's size.
  MarineSnow(const std::vector<Vec2>& first_frame, double axis_x_m, const std::array<Vec3, 2>& box, double radius_m,
             double density = 1.0);

  /// Appends this frame's specks to `mesh` as part "snow" (same particles, same order every frame).
  void append(const std::vector<Vec2>& tracers, Mesh& mesh) const;
  std::size_t count() const { return kept_.size(); }

 private:
  Vec3 place(std::size_t particle, Vec2 slice) const;
  double axis_x_;
  double radius_;
  std::vector<std::size_t> kept_;  ///< tracer indices
};

}  // namespace jellysim::geometry
