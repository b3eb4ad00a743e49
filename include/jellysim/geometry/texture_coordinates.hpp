#pragma once
// Texture coordinates (UVs) of the jellyfish meshes for the exported files (.glb TEXCOORD_0, .usda
// primvars:st, OBJ vt). They depend on the topology only, so they are the same in every frame.
#include <array>
#include <cstdint>
#include <vector>

#include "jellysim/geometry/extrapolation.hpp"

namespace jellysim::geometry {

/// (u, v), both in [0, 1].
using TexCoord = std::array<float, 2>;

/// One per vertex of `g.mesh` (its umbrella, then its tentacle tubes). Umbrella: u = j / disc_points
/// around the axis (σ_j of eq. 7.12), v along the profile from the apex (0) to the margin (1) on each
/// surface: the exumbrellar rows 0 … E at v = row / E, the subumbrellar rings from the margin (1) back
/// up to the subumbrellar apex (0), so both surfaces cover the same square (a two-sided decal); the
/// poles at u = ½. Tentacle tubes: u = s / tube_sides around the tube, v = m / (samples − 1) from the
/// root to the tip. A simulated surface's umbrella (surface_geometry.hpp) brings its own,
/// g.umbrella_uv. A bell without tentacles has none to add.
std::vector<TexCoord> texture_coordinates(const FrameGeometry& g);

/// The seam where u wraps from (n − 1)/n back to 0, split: a triangle whose corners' u span more than
/// ½ uses u + 1 at its corners with u below ½, at a duplicate of their vertex, so every triangle's
/// coordinates are continuous and u reaches 1 on the seam.
struct SeamSplit {
  std::vector<TexCoord> uv;             ///< the per-vertex coordinates, then the duplicates'
  std::vector<std::uint32_t> corners;   ///< per index of the range: the entry of `uv` it uses
  std::vector<std::uint32_t> duplicated;  ///< per duplicate (entry uv.size() of the input + d): its vertex
};

/// The split of the triangles indices[first_index, first_index + index_count) over per-vertex `uv`.
SeamSplit split_u_seam(const std::vector<TexCoord>& uv, const std::vector<std::uint32_t>& indices,
                       std::uint32_t first_index, std::uint32_t index_count);

}  // namespace jellysim::geometry
