#pragma once
// Point caches of an animated mesh for VFX pipelines: PC2 and MDD (read by Blender's Mesh Cache
// modifier, Maya, Houdini, 3ds Max) beside a rest mesh, and a USD stage in its text form (.usda,
// no library needed) with one prim per body: a transform carrying the root motion and a mesh with
// time-sampled points around it. Pure writers: every function returns the file's bytes.
#include <array>
#include <string>
#include <vector>

#include "jellysim/geometry/mesh.hpp"
#include "jellysim/geometry/texture_coordinates.hpp"
#include "jellysim/io/interchange.hpp"

namespace jellysim::io {

/// Vertex positions of one mesh, frame after frame (every frame the same count).
using PointFrames = std::vector<std::vector<geometry::Vec3>>;

/// PC2 (Blender's point cache 2): "POINTCACHE2\0", version 1, point count, start frame, one
/// sample per frame, sample count (little-endian int32/float32), then float32 x y z per point
/// per sample. Throws InputError when the frames are empty or differ in point count.
std::string pc2_bytes(const PointFrames& frames, double start_frame);

/// MDD (big-endian): frame count, point count (int32), each frame's time in seconds (float32),
/// then float32 x y z per point per frame.
std::string mdd_bytes(const PointFrames& frames, const std::vector<double>& times_s);

/// One body of a USD stage: `root` per frame (the prim's translation) and the mesh's points per
/// frame relative to it; the triangles of frame 0's topology; parts become GeomSubsets.
struct UsdBody {
  std::string name;             ///< a USD identifier: letters, digits, '_' (not first a digit)
  geometry::Mesh topology;      ///< indices and parts (positions unused)
  std::vector<geometry::Vec3> root;  ///< per frame
  PointFrames points;           ///< per frame, relative to root
  std::array<double, 3> colour{0.8, 0.9, 1.0};
  std::vector<geometry::TexCoord> uv;  ///< per vertex (primvars:st, face-varying), or empty
  bool velocities = true;              ///< `velocities` time samples
};

/// A .usda stage, Y up, metres, `fps` time codes per second, frames 0 … n−1, all bodies under
/// /jellysim. Per mesh: `primvars:st` (face-varying with indices, the u seam split per corner, no
/// vertex duplicated) when the body has UVs; `velocities` time samples (m/s, relative to the prim's
/// root: vertex_velocities of the points at t = frame / fps, central differences); its parts'
/// GeomSubsets bound to UsdPreviewSurface materials under /jellysim/Looks (from `look`: umbrella,
/// tentacles, obstacles, snow). `camera`, when it has frames: a Camera prim /jellysim/camera
/// (xformOp:transform, time-sampled unless it stands still; focalLength and apertures giving its
/// vertical field of view and aspect; clippingRange). Throws InputError for bodies whose frame
/// counts disagree, names that are not identifiers, or a camera with another frame count.
std::string usda_text(const std::vector<UsdBody>& bodies, double fps, const std::string& comment,
                      const ExportLook& look = {}, const ExportCamera& camera = {});

}  // namespace jellysim::io
