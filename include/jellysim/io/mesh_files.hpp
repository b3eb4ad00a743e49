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
#include "jellysim/geometry/texture_coordinates.hpp"
#include "jellysim/io/interchange.hpp"

namespace jellysim::io {

/// Wavefront OBJ: `v` and `vn` lines (shortest round-trip text of the float values), one `g`
/// group per mesh part with `f a//a b//b c//c` faces (1-based). With `object` given, one object of
/// that name whose parts are materials (`usemtl`) instead: importers then keep it one mesh with the
/// vertex order of the file, as a point cache needs. With `uv` (one per vertex for the first
/// uv.size() vertices), the parts whose vertices all have one get `vt` lines and `f a/t/a …` faces,
/// the u seam split per corner (geometry::split_u_seam; no vertex is duplicated).
std::string obj_text(const geometry::Mesh& mesh, const std::string& comment, const std::string& object = "",
                     const std::vector<geometry::TexCoord>& uv = {});

/// PLY, binary little endian: float x y z nx ny nz per vertex, faces as uchar-counted uint lists.
std::string ply_bytes(const geometry::Mesh& mesh, const std::string& comment);

struct GlbMaterial {
  std::string part;                 ///< mesh part it applies to
  std::array<double, 4> rgba{};     ///< base colour, linear, alpha < 1 → alphaMode BLEND
  double roughness = 0.5;
  /// > 0: the tissue of our renderer (render.transmission, render.attenuation_distance, the wall's
  /// thickness), written to the material's extras: in glTF the bell is alpha blending, as we draw it
  double transmission = 0.0;
  double attenuation_distance_m = 0.0;
  double thickness_m = 0.0;
  double ior = 0.0;                 ///< > 0: KHR_materials_ior
};

/// The materials of the exported look: umbrella (alpha-blended, its tissue in extras, ior),
/// tentacles, obstacles, snow.
std::vector<GlbMaterial> glb_materials(const ExportLook& look);

/// One animated body of a .glb: its mesh frame by frame relative to its pivot, and where the pivot
/// is in each frame (the root motion).
struct GlbBody {
  std::string name;                  ///< node name, e.g. "jellyfish_1"
  geometry::Mesh first;              ///< frame 0 (positions relative to the pivot, normals, parts)
  std::vector<std::vector<geometry::Vec3>> positions;  ///< every frame's, relative to the pivot
  std::vector<geometry::Vec3> root;  ///< per frame; empty: the pivot stays at the origin
  std::vector<geometry::TexCoord> uv;  ///< per vertex (TEXCOORD_0), or empty
  bool velocities = true;            ///< _VELOCITY in the base and in every morph target
};

/// glTF 2.0 binary. Per body a node (translation animated by the root motion) with a child node
/// holding its mesh, one primitive per part: frame 0's positions and normals as the base, and a
/// morph target for every `every`-th later frame and the last, holding position differences only
/// as normalized shorts (KHR_mesh_quantization; the mesh node's uniform scale S turns them back
/// into metres, difference = S · value / 32767, S the largest difference). One animation "swim":
/// the root motion at every frame, and morph weights that are 1 for one target at its frame's
/// time and 0 for the others (normalized bytes), interpolated linearly between the kept frames.
/// The normals are frame 0's; jellysim's HTML viewer recomputes them from the morphed positions.
/// Throws InputError when times do not increase, frame or root counts do not match the times,
/// a frame's vertex count differs, or a mesh's parts do not use disjoint, contiguous vertex ranges.
/// `frames_per_second` > 0 is written into asset.extras with the frame count (glTF has no field
/// for them) for tools that set a scene up from the file (blender_import.py).
/// Texture coordinates (body.uv): TEXCOORD_0, float VEC2, static (not in the morph targets); the u
/// seam's vertices are duplicated in the primitive (geometry::split_u_seam). Velocities
/// (body.velocities, vertex_velocities of the positions relative to the pivot, m/s): the custom
/// attribute _VELOCITY as normalized signed bytes (VEC3, 4-byte stride), frame 0's in the base and
/// each kept frame's minus frame 0's in its morph target, so the morphed attribute is the frame's
/// velocity; metres per second = value × the mesh's extras.velocity_scale_m_per_s.
/// `camera`, when it has frames: a node "camera" (perspective: yfov, aspectRatio, znear, zfar),
/// its translation and rotation animated in "swim" unless it stands still.
/// `closes_loop` (a seamless loop, render.loop): the last time is the loop's closing key, one frame
/// after its last frame: every body's positions there are frame 0's (relative to its root; else
/// InputError), the roots and camera may have moved on (a constant root motion). It gets no morph
/// target (its weights are all 0, the base), so a player that loops the clip over its duration
/// wraps without a jump; asset.extras say `loop: true` and `frame_count` leaves it out (the frames
/// to play, for frame-based tools).
std::string glb_bytes(const std::vector<GlbBody>& bodies, const std::vector<double>& times_s,
                      const std::vector<GlbMaterial>& materials, int every = 1, double frames_per_second = 0.0,
                      const ExportCamera& camera = {}, bool closes_loop = false);

/// One body named "jellyfish" that stays at the origin, every frame a morph target.
std::string glb_bytes(const geometry::Animation& animation, const std::vector<GlbMaterial>& materials);

/// The two chunks of a .glb file (for tests and tools); throws InputError for a malformed file.
struct GlbContents {
  nlohmann::json json;
  std::string bin;
};
GlbContents parse_glb(const std::string& bytes);

}  // namespace jellysim::io
