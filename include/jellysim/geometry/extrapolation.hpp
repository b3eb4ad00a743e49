#pragma once
// 3D extrapolation of the 2D rendering model (thesis §7.3, Figure 7.6) with the surface noise of
// §7.3 and the per-vertex normals of eq. 7.9 (recomputed after the noise, §7.4).
//
// Layout: the slice plane is z = 0. Each opposing pair (a = left, b = right) of a resampled surface
// spans a disc about the axis through its midpoint c, orthogonal to b − a, in the plane of
// ê = (b − a)/|b − a| and ẑ:  x(σ) = c + r (cos σ ê − sin σ ẑ),  r = |b − a|/2,  σ_j = 2π j/j_max
// (eq. 7.12), so j = 0 is the right slice point and j = j_max/2 the left one.
// Umbrella rows i = 0 … rows − 1: row 0 is the exumbrellar apex (a pole vertex), then exumbrellar
// rings from the apex down to the rim, subumbrellar rings from the rim up, and the subumbrellar
// apex (pole) last — a closed surface around the mesoglea.
#include <array>
#include <cstdint>
#include <vector>

#include "jellysim/geometry/mesh.hpp"
#include "jellysim/geometry/perlin.hpp"
#include "jellysim/geometry/rendering_model.hpp"
#include "jellysim/geometry/spline.hpp"
#include "jellysim/geometry/surface_noise.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"

namespace jellysim::geometry {

struct GeometrySettings {
  int latitude_samples = 65;           ///< rendering-model samples per umbrella surface (odd ≥ 5)
  int disc_points = 64;                ///< j_max: points around each disc (≥ 8)
  int tentacle_samples = 40;           ///< samples along each tentacle (≥ 2)
  int tentacle_count = 16;             ///< 3D tentacles around the rim per opposing pair of slice tentacles
  int tube_sides = 6;                  ///< tentacle tube cross-section (≥ 3)
  double tentacle_radius_m = 0.00025;  ///< tube radius at the root, tapering to 30 % at the tip
  Interpolant interpolant = Interpolant::catmull_rom;
  NoiseSettings noise;
};

/// Throws InputError naming the field and its allowed range.
void validate_geometry_settings(const GeometrySettings& settings);

/// Where the umbrella's vertices are: vertex 0 is the exumbrellar apex, ring r ∈ [1, rows − 2]
/// holds disc_points vertices, and the subumbrellar apex is last. The slice pipeline's: a simulated
/// surface (surface_geometry.hpp) has no rings and leaves it empty (rows = 0); what every umbrella
/// has is its mesh part (umbrella_vertex_count).
struct UmbrellaLayout {
  int rows = 0;              ///< latitude rows including both poles
  int disc_points = 0;       ///< j_max
  int exumbrella_rings = 0;  ///< rings 1 … exumbrella_rings are exumbrellar, the rest subumbrellar
  std::uint32_t vertex(int row, int j) const;
  std::uint32_t vertex_count() const { return static_cast<std::uint32_t>(2 + (rows - 2) * disc_points); }
};

/// One frame of 3D geometry. mesh.parts: "umbrella" (vertices [0, umbrella_vertex_count(g))) and,
/// when the slice has tentacles, "tentacles" (thin tubes around tentacle_lines).
struct FrameGeometry {
  double time_s = 0.0;
  Mesh mesh;
  UmbrellaLayout umbrella;  ///< the slice pipeline's rings; empty for a simulated surface
  /// A simulated surface's texture coordinates, one (u, v) per umbrella vertex (the slice pipeline's
  /// follow from its ring layout and leave this empty; texture_coordinates.hpp).
  std::vector<std::array<float, 2>> umbrella_uv;
  std::vector<std::vector<Vec3>> tentacle_lines;  ///< tentacles as polylines (after noise)
};

/// The umbrella's vertices [0, count): those of its mesh part (0 without one).
std::uint32_t umbrella_vertex_count(const FrameGeometry& g);

/// Thin tubes around the tentacle polylines appended to `mesh` as its part "tentacles" (tube_sides,
/// tentacle_radius_m tapering to 30 % at the tip, parallel-transported frames): the slice's strands
/// and a simulated bell's rods alike.
void append_tentacle_tubes(const std::vector<std::vector<Vec3>>& lines, const GeometrySettings& settings, Mesh& mesh);

/// Builds frames with one noise field (one individual) and one noise length scale.
class GeometryBuilder {
 public:
  /// `length_scale_m` > 0: the length unit of the noise (NoiseSettings::length_scale_m resolved).
  GeometryBuilder(const GeometrySettings& settings, double length_scale_m);

  /// Validates the slice (InputError) and builds its mesh.
  FrameGeometry build(const jellyfish::SliceFrame& frame) const;
  /// The same into `out`, reusing its buffers: no allocation of the mesh arrays once `out` has
  /// held a frame of this topology (for per-frame use in an interactive loop). Same values.
  void build(const jellyfish::SliceFrame& frame, FrameGeometry& out) const;

  const GeometrySettings& settings() const { return settings_; }
  double length_scale_m() const { return length_scale_m_; }

 private:
  GeometrySettings settings_;
  double length_scale_m_;
  ImprovedNoise noise_;
};

/// NoiseSettings::length_scale_m if positive, else the bell height of `first_frame`.
double resolve_noise_length(const NoiseSettings& noise, const jellyfish::SliceFrame& first_frame);

/// Eq. 7.9 normals of an umbrella grid: n = (x_{i+1,j} − x_{i−1,j}) × (x_{i,j+1} − x_{i,j−1}),
/// normalised; at the poles the normalised sum of the fan's face normals.
void umbrella_normals(const UmbrellaLayout& layout, const std::vector<Vec3>& positions, std::vector<Vec3>& normals);

/// Every frame through one builder (noise length from the first frame); same topology throughout.
Animation build_animation(const std::vector<jellyfish::SliceFrame>& frames, const GeometrySettings& settings);

}  // namespace jellysim::geometry
