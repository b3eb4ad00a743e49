#pragma once
// The simulated 3D bell as rendering geometry (issue 40 part 4, docs/rendering.md "The simulated 3D
// surface"): the 3D swimmer simulates the bell's surface itself, so the extrapolation of a 2D slice
// (§7.2–7.3, extrapolation.hpp) is skipped and the surface is drawn as it was simulated.
//
// The simulated surface is taken as the subumbrella. The bell wall is closed around the mesoglea
// as the slice pipeline's umbrella is: the exumbrella is the subumbrella offset by the wall's
// thickness ϑ along its smooth vertex normals, away from the cavity (the eq. 7.6–7.7 offset of the
// slice, in 3D), and the two surfaces are joined at the margin by a rim band of quads. No noise: the
// simulated surface is the physics. Tentacles (the rods' nodes) are resampled as the slice's are and
// drawn as the slice pipeline's tubes (append_tentacle_tubes).
//
// Plain data: this module knows nothing of the swimmer or the shell (the caller copies the points).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/vec3.hpp"

namespace jellysim::geometry {

/// A simulated bell, frame by frame (the 3D swimmer, swim3d::Swimmer3d).
struct SurfaceFrames {
  std::vector<double> time_s;                                   ///< per frame, increasing (s)
  std::vector<std::array<std::uint32_t, 3>> triangles;          ///< the subumbrellar surface, one orientation
  std::vector<std::vector<Vec3>> surface;                       ///< per frame: its vertex positions (m)
  std::vector<std::vector<std::vector<Vec3>>> tentacles;        ///< per frame, per strand: nodes from the root (m)
  double thickness_m = 0.0015;                                  ///< the bell wall drawn (the slice's ϑ, render only)
};

/// Throws InputError naming what is wrong: no frames; times not increasing; a frame whose vertex or
/// strand counts differ from frame 0's; an index out of range; a triangle with a repeated vertex;
/// triangles not consistently oriented (an edge used twice in one direction) or an edge shared by
/// more than two; no margin (a closed surface); a point that is not finite; ϑ not in (0, ∞).
void validate_surface_frames(const SurfaceFrames& frames);

/// Builds frames of one simulated bell: the wall's topology, its orientation and texture coordinates
/// are fixed from frame 0, so every frame has one mesh topology (morph targets, point caches).
/// Keeps a reference to `frames`, which must outlive it.
class SurfaceGeometryBuilder {
 public:
  /// Validates (InputError) and prepares the wall's topology.
  SurfaceGeometryBuilder(const SurfaceFrames& frames, const GeometrySettings& settings);

  /// Frame `frame`'s mesh: part "umbrella" (vertices [0, N): the subumbrella, [N, 2N): the
  /// exumbrella; its triangles counter-clockwise seen from outside the wall), then part "tentacles";
  /// `umbrella_uv` set, `umbrella` (the slice's ring layout) empty. Reuses `out`'s buffers.
  void build(std::size_t frame, FrameGeometry& out) const;
  FrameGeometry build(std::size_t frame) const;

  std::size_t frame_count() const { return frames_.surface.size(); }
  /// +1 when the given triangles' normals (right-hand rule) point away from the cavity, −1 when into it.
  int orientation() const { return orientation_; }

 private:
  const SurfaceFrames& frames_;
  GeometrySettings settings_;
  int orientation_ = 1;
  std::vector<std::uint32_t> wall_indices_;           ///< the closed wall's triangles
  std::vector<std::array<float, 2>> wall_uv_;         ///< per wall vertex
};

/// One frame (a builder made for it): the convenience form for a single picture.
FrameGeometry surface_frame_geometry(const SurfaceFrames& frames, std::size_t frame, const GeometrySettings& settings);

/// The signed volume (m³) of the surface closed by a fan from its margin's centroid (the aperture),
/// the fan oriented against the surface's margin edges: positive when the triangles' normals point
/// out of the enclosed cavity. Throws InputError for a surface without a margin.
double signed_cavity_volume(const std::vector<Vec3>& positions,
                            const std::vector<std::array<std::uint32_t, 3>>& triangles);

/// Every point of every frame (surface and tentacles) in one box: the path the bell took.
std::array<Vec3, 2> surface_path_bounds(const SurfaceFrames& frames);

/// Appends a frame at `time_s` from a simulation's points (anything indexable by [0], [1], [2], in
/// metres, e.g. the 3D swimmer's): the surface's vertices are points [0, vertex_count), each strand's
/// nodes the points it lists (from its root).
template <class Point>
void append_surface_frame(SurfaceFrames& frames, double time_s, const std::vector<Point>& points,
                          std::size_t vertex_count, const std::vector<std::vector<int>>& strands) {
  const auto at = [&](std::size_t i) { return Vec3{points[i][0], points[i][1], points[i][2]}; };
  frames.time_s.push_back(time_s);
  std::vector<Vec3>& surface = frames.surface.emplace_back(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) surface[i] = at(i);
  std::vector<std::vector<Vec3>>& lines = frames.tentacles.emplace_back(strands.size());
  for (std::size_t s = 0; s < strands.size(); ++s)
    for (int i : strands[s]) lines[s].push_back(at(static_cast<std::size_t>(i)));
}

}  // namespace jellysim::geometry
