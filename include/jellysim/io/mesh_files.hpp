#pragma once
// Mesh files of the 3D jellyfish: Wavefront OBJ and binary PLY per frame, and one animated glTF 2.0
// binary (.glb) of a whole animation with morph targets. Pure writers: they take geometry, not
// physics; every function returns the file's bytes (write them with OutputDir for atomicity).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jellysim/geometry/mesh.hpp"

namespace jellysim::io {

/// Wavefront OBJ: `v` and `vn` lines (shortest round-trip text of the float values), one `g`
/// group per mesh part with `f a//a b//b c//c` faces (1-based). With `object` given, one object of
/// that name whose parts are materials (`usemtl`) instead: importers then keep it one mesh with the
/// vertex order of the file, as a point cache needs.
std::string obj_text(const geometry::Mesh& mesh, const std::string& comment, const std::string& object = "");

/// PLY, binary little endian: float x y z nx ny nz per vertex, faces as uchar-counted uint lists.
std::string ply_bytes(const geometry::Mesh& mesh, const std::string& comment);

struct GlbMaterial {
  std::string part;                 ///< mesh part it applies to
  std::array<double, 4> rgba{};     ///< base colour, linear, alpha < 1 → alphaMode BLEND
  double roughness = 0.5;
};

/// glTF 2.0 binary of the animation: one node, one mesh with one primitive per part (frame 0's
/// positions and normals), one morph target per later frame (position and normal differences from
/// frame 0), and an animation of the morph weights: at time t_k − t_0 target k has weight 1 and the
/// others 0, interpolated linearly (so it plays back frame by frame). Throws InputError for an
/// invalid animation (geometry::validate_animation) or a mesh whose parts do not use disjoint,
/// contiguous vertex ranges.
std::string glb_bytes(const geometry::Animation& animation, const std::vector<GlbMaterial>& materials);

/// The two chunks of a .glb file (for tests and tools); throws InputError for a malformed file.
struct GlbContents {
  nlohmann::json json;
  std::string bin;
};
GlbContents parse_glb(const std::string& bytes);

}  // namespace jellysim::io
