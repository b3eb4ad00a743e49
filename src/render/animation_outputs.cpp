#include "jellysim/render/animation_outputs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "jellysim/core/interrupt.hpp"
#include "jellysim/geometry/marine_snow.hpp"
#include "jellysim/geometry/obstacle_mesh.hpp"
#include "jellysim/geometry/rendering_model.hpp"
#include "jellysim/geometry/texture_coordinates.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/io/mesh_files.hpp"
#include "jellysim/io/point_caches.hpp"
#include "jellysim/render/exr_frames.hpp"
#include "jellysim/render/video.hpp"

#ifndef JELLYSIM_WEB_DIR
#define JELLYSIM_WEB_DIR "web"
#endif

namespace jellysim::render {

using geometry::Vec3;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string frame_name(std::size_t k, const char* extension) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04zu.%s", k, extension);
  return buf;
}

/// The middle of the umbrella's box (part "umbrella" uses vertices from 0) — the camera frames it.
Vec3 umbrella_centre(const geometry::FrameGeometry& g) {
  Vec3 lo = g.mesh.positions[0], hi = lo;
  for (std::uint32_t v = 0, n = geometry::umbrella_vertex_count(g); v < n; ++v) {
    const Vec3 p = g.mesh.positions[v];
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return 0.5 * (lo + hi);
}

Vec3 view_direction(const PipelineSettings& s) {
  const double el = s.camera_elevation_deg * std::numbers::pi / 180.0;
  const double az = s.camera_azimuth_deg * std::numbers::pi / 180.0;
  return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

/// Follows the jellyfish: the target moves a fraction of the way toward the umbrella's centre
/// (shifted down to take in the tentacles) each frame; distance and direction stay fixed.
class FollowCamera {
 public:
  FollowCamera(const PipelineSettings& s, const geometry::Mesh& first) : settings_(s) {
    const geometry::Bounds b = geometry::bounds(first);
    const Vec3 size = b.max - b.min;
    extent_ = std::max({size.x, size.y, size.z});
  }
  /// `centre`: the middle of the umbrella(s) this frame.
  Camera next(Vec3 centre) {
    const Vec3 goal = centre - Vec3{0.0, 0.15 * extent_, 0.0};
    target_ = started_ ? target_ + settings_.camera_follow * (goal - target_) : goal;
    started_ = true;
    return camera_looking_at(target_, view_direction(settings_), camera_distance_for(settings_, extent_),
                             settings_.fov_y_deg);
  }

 private:
  const PipelineSettings& settings_;
  double extent_ = 1.0;
  Vec3 target_;
  bool started_ = false;
};

/// The box (slice plane z = 0, bells revolved about their axes) that holds every jellyfish in every
/// recorded frame: the umbrellas and tentacles in x and y, and ± the widest umbrella's half width in z.
std::array<Vec3, 2> path_bounds(const std::vector<std::vector<jellyfish::SliceFrame>>& school) {
  Vec3 lo{INFINITY, INFINITY, 0.0}, hi{-INFINITY, -INFINITY, 0.0};
  double half_width = 0.0;
  auto take = [&](Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), 0.0};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), 0.0};
  };
  for (const auto& frames : school)
    for (const jellyfish::SliceFrame& f : frames) {
      for (Vec2 p : f.umbrella) take(p);
      for (const auto& strand : f.tentacles)
        for (Vec2 p : strand) take(p);
      if (!f.umbrella.empty()) half_width = std::max(half_width, 0.5 * norm(f.umbrella.back() - f.umbrella.front()));
    }
  lo.z = -half_width;
  hi.z = half_width;
  return {lo, hi};
}

}  // namespace

double camera_distance_for(const PipelineSettings& s, double extent_m) {
  return s.camera_distance > 0.0 ? s.camera_distance * extent_m : s.camera_distance_m;
}

/// One camera for the whole animation: looking at the middle of the path's box from the configured
/// direction. In metres (the default) at camera_distance_m, so a bigger bell looks bigger; in
/// mesh extents (camera_distance > 0) at that distance or further, so that the box's bounding
/// sphere fits the picture's height. The bell then moves across the picture as it swims.
Camera fixed_camera(const std::vector<std::vector<jellyfish::SliceFrame>>& school, const PipelineSettings& s,
                    const geometry::Mesh& first) {
  return fixed_camera(path_bounds(school), s, first);
}

Camera fixed_camera(const std::array<Vec3, 2>& path_box, const PipelineSettings& s, const geometry::Mesh& first) {
  const auto [lo, hi] = path_box;
  const geometry::Bounds b = geometry::bounds(first);
  const Vec3 size = b.max - b.min;
  const double extent = std::max({size.x, size.y, size.z});
  double distance = camera_distance_for(s, extent);
  if (s.camera_distance > 0.0) {
    const double radius = 0.5 * geometry::norm(hi - lo);
    const double half_fov = 0.5 * s.fov_y_deg * std::numbers::pi / 180.0;
    distance = std::max(distance, 1.05 * radius / std::sin(half_fov));
  }
  return camera_looking_at(0.5 * (lo + hi), view_direction(s), distance, s.fov_y_deg);
}

namespace {

/// Appends part `name` of `mesh` (its block of vertices and its triangles) to `out`'s vertices and
/// indices; returns the number of indices appended (0 when the mesh has no such part).
std::uint32_t append_part(const geometry::Mesh& mesh, const std::string& name, geometry::Mesh& out) {
  const geometry::MeshPart* part = mesh.part(name);
  if (part == nullptr || part->index_count == 0) return 0;
  const geometry::VertexRange r = geometry::vertex_range(mesh, *part);
  const auto offset = static_cast<std::uint32_t>(out.positions.size());
  out.positions.insert(out.positions.end(), mesh.positions.begin() + r.first, mesh.positions.begin() + r.first + r.count);
  out.normals.insert(out.normals.end(), mesh.normals.begin() + r.first, mesh.normals.begin() + r.first + r.count);
  for (std::uint32_t k = part->first_index; k < part->first_index + part->index_count; ++k)
    out.indices.push_back(mesh.indices[k] - r.first + offset);
  return part->index_count;
}

/// Part `name` of `mesh` as a mesh of its own, or an empty mesh.
geometry::Mesh part_mesh(const geometry::Mesh& mesh, const std::string& name) {
  geometry::Mesh sub;
  if (const std::uint32_t count = append_part(mesh, name, sub); count > 0) sub.parts.push_back({name, 0, count});
  return sub;
}

/// Gathers each body's vertices frame by frame for the point caches and the USD stage: every
/// jellyfish with its root (the middle of its umbrella), and the obstacles (root at the origin).
class CacheRecorder {
 public:
  explicit CacheRecorder(std::size_t jellyfish) : bodies_(jellyfish) {
    for (std::size_t j = 0; j < jellyfish; ++j) bodies_[j].name = "jellyfish_" + std::to_string(j + 1);
  }
  void add(const std::vector<geometry::FrameGeometry>& parts, const geometry::Mesh& merged) {
    for (std::size_t j = 0; j < parts.size(); ++j) {
      if (bodies_[j].frames.empty()) bodies_[j].uv = geometry::texture_coordinates(parts[j]);
      record(bodies_[j], parts[j].mesh, umbrella_centre(parts[j]));
    }
    geometry::Mesh obstacles = part_mesh(merged, "obstacles");
    if (!obstacles.positions.empty()) {
      if (obstacle_body_.empty()) obstacle_body_.push_back({"obstacles", {}, {}, {}, {}});
      record(obstacle_body_.front(), obstacles, Vec3{});
    }
    geometry::Mesh snow = part_mesh(merged, "snow");
    if (!snow.positions.empty()) {
      if (snow_body_.empty()) snow_body_.push_back({"marine_snow", {}, {}, {}, {}});
      record(snow_body_.front(), snow, Vec3{});
    }
  }
  /// The bodies of the .glb: each jellyfish about its pivot with its root motion, the obstacles
  /// at the origin.
  std::vector<io::GlbBody> glb_bodies(bool velocities) const {
    std::vector<io::GlbBody> bodies;
    for (const Body& b : bodies_) {
      io::GlbBody g{b.name, b.rest, {}, b.roots, b.uv, velocities};
      for (Vec3& p : g.first.positions) p = p - b.roots.front();
      for (std::size_t k = 0; k < b.frames.size(); ++k) {
        std::vector<Vec3> local = b.frames[k];
        for (Vec3& p : local) p = p - b.roots[k];
        g.positions.push_back(std::move(local));
      }
      bodies.push_back(std::move(g));
    }
    // Velocities for the jellyfish only: the obstacles hardly move and the snow drifts slowly; each
    // body with them costs 4 bytes per vertex and morph target (docs/rendering.md).
    for (const Body& b : obstacle_body_) bodies.push_back({b.name, b.rest, b.frames, {}, {}, false});
    for (const Body& b : snow_body_) bodies.push_back({b.name, b.rest, b.frames, {}, {}, false});
    return bodies;
  }
  void write(const PipelineSettings& s, const std::vector<double>& times, const io::OutputDir& out,
             const io::ExportCamera& camera, AnimationOutputs& result) const {
    std::vector<const Body*> all;
    for (const Body& b : bodies_) all.push_back(&b);
    for (const Body& b : obstacle_body_) all.push_back(&b);
    if (s.pc2 || s.mdd) {
      const io::OutputDir caches = out.subdirectory("caches");
      for (const Body* b : all) {
        const std::string comment = "jellysim rest mesh (frame 0) of " + b->name + "; metres, y up";
        caches.write_text(b->name + ".obj", io::obj_text(b->rest, comment, b->name, b->uv));
        result.files.push_back("caches/" + b->name + ".obj");
        if (s.pc2) {
          caches.write_text(b->name + ".pc2", io::pc2_bytes(b->frames, 0.0));
          result.files.push_back("caches/" + b->name + ".pc2");
        }
        if (s.mdd) {
          caches.write_text(b->name + ".mdd", io::mdd_bytes(b->frames, times));
          result.files.push_back("caches/" + b->name + ".mdd");
        }
      }
    }
    if (s.usda) write_usda(s, all, out, camera, result);
  }

 private:
  struct Body {
    std::string name;
    geometry::Mesh rest;            ///< frame 0 (world positions)
    io::PointFrames frames;         ///< world positions per frame
    std::vector<Vec3> roots;        ///< per frame
    std::vector<geometry::TexCoord> uv;  ///< per vertex (jellyfish), or empty
  };
  static void write_usda(const PipelineSettings& s, const std::vector<const Body*>& all, const io::OutputDir& out,
                         const io::ExportCamera& camera, AnimationOutputs& result) {
    {
      std::vector<io::UsdBody> stage;
      for (const Body* b : all) {
        io::UsdBody u{b->name, b->rest, b->roots, {}, {0.8, 0.9, 1.0}, b->uv, s.vertex_velocities};
        if (b->name == "obstacles") u.colour = {0.23, 0.2, 0.17};
        for (std::size_t k = 0; k < b->frames.size(); ++k) {
          std::vector<Vec3> local = b->frames[k];
          for (Vec3& p : local) p = p - b->roots[k];
          u.points.push_back(std::move(local));
        }
        stage.push_back(std::move(u));
      }
      out.write_text("jellyfish.usda", io::usda_text(stage, s.fps, "jellysim: one prim per jellyfish and for the obstacles",
                                                     s.look, camera));
      result.files.push_back("jellyfish.usda");
    }
  }
  static void record(Body& b, const geometry::Mesh& mesh, Vec3 root) {
    if (b.frames.empty()) b.rest = mesh;
    b.frames.push_back(mesh.positions);
    b.roots.push_back(root);
  }
  std::vector<Body> bodies_;
  std::vector<Body> obstacle_body_;  ///< empty or one
  std::vector<Body> snow_body_;      ///< empty or one: in the .glb only (not a body to cache)
};

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const auto b0 = static_cast<unsigned char>(bytes[i]);
    const auto b1 = i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) : 0u;
    const auto b2 = i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0u;
    const unsigned v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

constexpr const char* kViewerHtml = R"(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>jellysim — jellyfish</title>
<style>
  html, body { margin: 0; height: 100%; overflow: hidden; background: #021522; color: #cfe6ef; font: 13px sans-serif; }
  #info { position: absolute; left: 12px; top: 10px; pointer-events: none; }
</style>
</head>
<body>
<div id="info">jellysim: drag to orbit, scroll to zoom, space to pause</div>
<!-- three.js is bundled in jellyfish-viewer.js (web/ in the jellysim sources). The animation is
     jellyfish.glb beside this page, fetched (serve the folder: browsers refuse fetches from
     file://), or embedded as base64 in jellyfish.glb.js with render.page_embed = true. -->
@EMBED@<script src="jellyfish-viewer.js"></script>
<script>
  const info = document.getElementById("info");
  if (window.JellyfishViewer) {
    JellyfishViewer.start({ glbBase64: window.JELLYSIM_GLB_BASE64, glbUrl: "jellyfish.glb" }).catch((e) => {
      info.textContent = location.protocol === "file:"
        ? "Browsers do not load jellyfish.glb from file://. Serve this folder (python3 -m http.server) and open " +
          "http://localhost:8000/viewer.html, or run jellysim with --set render.page_embed=true."
        : "Cannot show jellyfish.glb: " + e.message;
    });
  } else {
    info.textContent = "jellyfish-viewer.js is missing: build it with `npm ci && npm run build` in jellysim's web/ folder.";
  }
</script>
</body>
</html>
)";

// Written beside jellyfish.glb: sets Blender's scene to the simulation's frame rate and range
// (from the .glb's asset extras) and imports it.
constexpr const char* kBlenderImport = R"py(# Opens jellysim's animation in Blender with the simulation's frame rate and frame range (glTF has
# no place for them, so jellysim writes them into jellyfish.glb's asset extras and this script
# sets the scene from there before importing), looking through the exported film camera at the
# rendered frames' size:
#   blender --python blender_import.py          (or Scripting > Open > Run in a running Blender)
# The materials (glTF PBR, alpha-blended, with IOR) arrive through Blender's importer.
import json
import os
import struct

import bpy

here = os.path.dirname(os.path.abspath(__file__))
path = os.path.join(here, "jellyfish.glb")
with open(path, "rb") as f:
    f.read(12)
    length, _ = struct.unpack("<II", f.read(8))
    document = json.loads(f.read(length))
extras = document["asset"].get("extras", {})
fps = extras.get("frames_per_second", 30.0)
frames = int(extras.get("frame_count", 1))
scene = bpy.context.scene
scene.render.fps = max(1, round(fps))
scene.render.fps_base = scene.render.fps / fps
bpy.ops.import_scene.gltf(filepath=path, import_shading="SMOOTH")
# The importer puts the first sample at frame 0 when the scene starts there.
scene.frame_start = 0
scene.frame_end = frames - 1
# The film camera: the picture's size from its extras, so the shot is framed as jellysim's frames.
cameras = [o for o in scene.objects if o.type == "CAMERA"]
if cameras:
    scene.camera = cameras[0]
    size = document.get("cameras", [{}])[0].get("extras", {})
    if size.get("width_px") and size.get("height_px"):
        scene.render.resolution_x, scene.render.resolution_y = size["width_px"], size["height_px"]
        scene.render.resolution_percentage = 100
print(f"jellysim: {frames} frames at {fps:g} fps (scene {scene.frame_start}-{scene.frame_end})"
      + (f", camera {scene.camera.name}" if cameras else ""))
)py";

void write_viewer(const PipelineSettings& s, const std::string& glb, const io::OutputDir& out,
                  AnimationOutputs& result) {
  std::string page = kViewerHtml;
  const std::string embed = s.page_embed ? "<script src=\"jellyfish.glb.js\"></script>\n" : "";
  page.replace(page.find("@EMBED@"), 7, embed);
  out.write_text("viewer.html", page);
  result.files.push_back("viewer.html");
  if (s.page_embed) {
    out.write_text("jellyfish.glb.js", "window.JELLYSIM_GLB_BASE64 = \"" + base64(glb) + "\";\n");
    result.files.push_back("jellyfish.glb.js");
  }
  std::ifstream script(s.viewer_script, std::ios::binary);
  if (!script) return;
  std::stringstream text;
  text << script.rdbuf();
  out.write_text("jellyfish-viewer.js", text.str());
  result.files.push_back("jellyfish-viewer.js");
  result.viewer_has_script = true;
}

}  // namespace

std::filesystem::path default_viewer_script() {
  const std::filesystem::path in_source = std::filesystem::path(JELLYSIM_WEB_DIR) / "dist" / "jellyfish-viewer.js";
  if (std::filesystem::is_regular_file(in_source)) return in_source;
  // An installed program (cmake --install, the .deb): PREFIX/bin/jellysim (or the interpreter running
  // the Python module, PREFIX/bin/python3) beside PREFIX/share/jellysim/web (cmake/install.cmake).
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return in_source;
  const std::filesystem::path installed = exe.parent_path().parent_path() / "share/jellysim/web/jellyfish-viewer.js";
  return std::filesystem::is_regular_file(installed) ? installed : in_source;
}

io::ExportLook export_look(const RenderStyle& style) {
  io::ExportLook look;
  look.bell_color = {style.umbrella[0], style.umbrella[1], style.umbrella[2]};
  look.umbrella_opacity = style.umbrella[3];
  look.tentacle_color = {style.tentacles[0], style.tentacles[1], style.tentacles[2]};
  look.tentacle_opacity = style.tentacles[3];
  look.obstacle_rgba = style.obstacles;
  look.snow_rgba = style.snow;
  look.transmission = style.transmission;  // render.transmission, render.attenuation_distance
  look.attenuation_distance_m = style.attenuation_distance_m;
  return look;
}

nlohmann::ordered_json AnimationOutputs::figures() const {
  nlohmann::ordered_json j;
  j["frames"] = frames;
  j["vertices_per_frame"] = vertices;
  j["triangles_per_frame"] = triangles;
  j["geometry_ms_per_frame"] = 1e3 * geometry_seconds_per_frame;
  j["render_ms_per_frame"] = 1e3 * render_seconds_per_frame;
  j["glb_bytes"] = glb_bytes;
  j["renderer"] = renderer;
  j["viewer_has_script"] = viewer_has_script;
  j["bell_screen_travel"] = bell_screen_travel;
  j["marine_snow_specks"] = marine_snow_specks;
  j["files"] = files;
  return j;
}

AnimationOutputs write_animation_outputs(const std::vector<jellyfish::SliceFrame>& frames,
                                         const PipelineSettings& s, const io::OutputDir& out,
                                         const FrameProgress& progress) {
  return write_animation_outputs(std::vector<std::vector<jellyfish::SliceFrame>>{frames},
                                 std::vector<std::uint64_t>{s.geometry.noise.seed}, s, out, progress);
}

namespace {

/// One mesh for several jellyfish: every umbrella first (so part "umbrella" still starts at vertex
/// 0 and is one index range), then every tentacle tube. The topology is fixed frame to frame.
void merge_meshes(const std::vector<geometry::FrameGeometry>& parts, geometry::Mesh& merged) {
  merged.positions.clear();
  merged.normals.clear();
  merged.indices.clear();
  merged.parts.clear();
  for (const char* name : {"umbrella", "tentacles"}) {
    const auto first_index = static_cast<std::uint32_t>(merged.indices.size());
    for (const geometry::FrameGeometry& g : parts) append_part(g.mesh, name, merged);
    const auto count = static_cast<std::uint32_t>(merged.indices.size()) - first_index;
    if (count > 0) merged.parts.push_back({name, first_index, count});
  }
}

/// The texture coordinates of merge_meshes's mesh: every umbrella's, then every tentacle tube's.
std::vector<geometry::TexCoord> merged_texture_coordinates(const std::vector<geometry::FrameGeometry>& parts) {
  std::vector<std::vector<geometry::TexCoord>> uv;
  for (const geometry::FrameGeometry& g : parts) uv.push_back(geometry::texture_coordinates(g));
  std::vector<geometry::TexCoord> merged;
  for (const char* name : {"umbrella", "tentacles"})
    for (std::size_t j = 0; j < parts.size(); ++j)
      if (const geometry::MeshPart* part = parts[j].mesh.part(name); part && part->index_count > 0) {
        const geometry::VertexRange r = geometry::vertex_range(parts[j].mesh, *part);
        merged.insert(merged.end(), uv[j].begin() + r.first, uv[j].begin() + r.first + r.count);
      }
  return merged;
}

}  // namespace

namespace {

using School = std::vector<std::vector<jellyfish::SliceFrame>>;

void check_recorded_frames(const School& school, const std::vector<std::uint64_t>& seeds,
                           const ObstacleFrames& obstacles) {
  if (school.empty() || school.front().empty()) throw InputError("no slice frames to render");
  if (seeds.size() != school.size()) throw InputError("one noise seed per jellyfish is needed");
  for (const auto& series : school)
    if (series.size() != school.front().size())
      throw InputError("every jellyfish needs the same number of recorded frames");
  if (!obstacles.empty() && obstacles.size() != school.front().size())
    throw InputError("the obstacles need one outline set per recorded frame");
}

std::unique_ptr<geometry::ObstaclePrisms> obstacle_prisms(const ObstacleFrames& obstacles, const PipelineSettings& s) {
  if (obstacles.empty() || obstacles.front().empty()) return nullptr;
  try {
    return std::make_unique<geometry::ObstaclePrisms>(obstacles.front(), s.obstacle_depth_m);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("cannot draw the obstacles: ") + e.what());
  }
}

/// The marine snow's specks near the path the jellyfish took: its box grown by its own size on
/// every side; none without tracers or when not asked for.
std::unique_ptr<geometry::MarineSnow> marine_snow(const School& school, const std::vector<std::vector<Vec2>>& tracers,
                                                  const PipelineSettings& s) {
  if (!tracers.empty() && tracers.size() != school.front().size())
    throw InputError("the marine snow needs one tracer set per recorded frame");
  if (!s.marine_snow || tracers.empty() || tracers.front().empty()) return nullptr;
  const auto [lo, hi] = path_bounds(school);
  const Vec3 margin = hi - lo;
  const jellyfish::SliceFrame& first = school.front().front();
  const double axis_x = 0.5 * (first.umbrella.front().x + first.umbrella.back().x);
  return std::make_unique<geometry::MarineSnow>(tracers.front(), axis_x, std::array<Vec3, 2>{lo - margin, hi + margin},
                                                s.snow_size_m, s.snow_density);
}

std::vector<geometry::GeometryBuilder> geometry_builders(const School& school, const std::vector<std::uint64_t>& seeds,
                                                         const PipelineSettings& s) {
  std::vector<geometry::GeometryBuilder> builders;
  for (std::size_t j = 0; j < school.size(); ++j) {
    geometry::GeometrySettings gs = s.geometry;
    gs.noise.seed = seeds[j];
    builders.emplace_back(gs, geometry::resolve_noise_length(gs.noise, school[j].front()));
  }
  return builders;
}

/// Where the shared writer's jellyfish come from: recorded slices extrapolated to 3D (with the
/// scene's obstacles and marine snow), or a simulated 3D surface. Everything after the geometry
/// (camera, pixels, video, meshes, caches, .glb, viewer) is one path for both (AnimationWriter).
class JellyfishFrames {
 public:
  virtual ~JellyfishFrames() = default;
  virtual std::size_t frame_count() const = 0;
  virtual std::size_t jellyfish_count() const = 0;
  /// Frame k's geometry of each jellyfish into parts[j] (reused buffers).
  virtual void build(std::size_t k, std::vector<geometry::FrameGeometry>& parts) = 0;
  /// What else frame k shows (obstacles, marine snow), appended to its merged mesh.
  virtual void add_surroundings(std::size_t k, geometry::Mesh& mesh) const = 0;
  /// The box that holds every jellyfish in every frame: what the fixed camera frames.
  virtual std::array<Vec3, 2> path_box() const = 0;
  /// The bell wall's thickness (m): the tissue's in the renderer and the exported look.
  virtual double tissue_thickness_m() const = 0;
  virtual std::size_t marine_snow_specks() const = 0;
};

/// The slice pipeline's jellyfish: each jellyfish's slices through its own GeometryBuilder (§7.2–7.4).
class SliceSchool final : public JellyfishFrames {
 public:
  SliceSchool(const School& school, const std::vector<std::uint64_t>& seeds, const PipelineSettings& s,
              const ObstacleFrames& obstacles, const std::vector<std::vector<Vec2>>& tracers)
      : school_(school),
        obstacles_(obstacles),
        tracers_(tracers),
        prisms_(obstacle_prisms(obstacles, s)),
        snow_(marine_snow(school, tracers, s)),
        builders_(geometry_builders(school, seeds, s)) {}

  std::size_t frame_count() const override { return school_.front().size(); }
  std::size_t jellyfish_count() const override { return school_.size(); }
  void build(std::size_t k, std::vector<geometry::FrameGeometry>& parts) override {
    for (std::size_t j = 0; j < school_.size(); ++j) builders_[j].build(school_[j][k], parts[j]);
  }
  void add_surroundings(std::size_t k, geometry::Mesh& mesh) const override {
    if (prisms_) {
      try {
        prisms_->append(obstacles_[k], mesh);
      } catch (const std::invalid_argument& e) {
        throw InputError("frame " + std::to_string(k) + ": cannot draw the obstacles: " + e.what());
      }
    }
    if (snow_) snow_->append(tracers_[k], mesh);
  }
  std::array<Vec3, 2> path_box() const override { return path_bounds(school_); }
  double tissue_thickness_m() const override { return school_.front().front().thickness_m; }
  std::size_t marine_snow_specks() const override { return snow_ ? snow_->count() : 0; }

 private:
  const School& school_;
  const ObstacleFrames& obstacles_;
  const std::vector<std::vector<Vec2>>& tracers_;
  std::unique_ptr<geometry::ObstaclePrisms> prisms_;
  std::unique_ptr<geometry::MarineSnow> snow_;
  std::vector<geometry::GeometryBuilder> builders_;
};

/// A simulated bell (the 3D swimmer): its surface drawn as simulated (geometry/surface_geometry.hpp),
/// no extrapolation and no noise. Slice-only things are not drawn: obstacles and marine snow come
/// from the 2D tank's markers and tracers, which the 3D swimmer does not record.
class SimulatedBell final : public JellyfishFrames {
 public:
  SimulatedBell(const geometry::SurfaceFrames& frames, const PipelineSettings& s)
      : frames_(frames), builder_(frames, s.geometry) {}

  std::size_t frame_count() const override { return builder_.frame_count(); }
  std::size_t jellyfish_count() const override { return 1; }
  void build(std::size_t k, std::vector<geometry::FrameGeometry>& parts) override { builder_.build(k, parts.front()); }
  void add_surroundings(std::size_t, geometry::Mesh&) const override {}
  std::array<Vec3, 2> path_box() const override { return geometry::surface_path_bounds(frames_); }
  double tissue_thickness_m() const override { return frames_.thickness_m; }
  std::size_t marine_snow_specks() const override { return 0; }

 private:
  const geometry::SurfaceFrames& frames_;
  geometry::SurfaceGeometryBuilder builder_;
};

/// What writes each frame's pixels and meshes: the renderer, the video's file then its encoder
/// (stopped first when the run fails: the file is removed), and folders only for what is written
/// (an empty folder would be a surprise).
struct FrameWriters {
  FrameWriters(const PipelineSettings& s, const io::OutputDir& out) : pixels(s.png_frames || s.video || s.exr) {
    if (pixels) renderer = std::make_unique<OffscreenRenderer>(s.width_px, s.height_px, s.samples);
    if (s.video) {
      video_file.emplace(out.temporary_for("jellyfish.mp4"));
      video = std::make_unique<Mp4Writer>(video_file->path(), video_file->fd(), s.width_px, s.height_px, s.fps);
    }
    if (s.png_frames || s.exr) frame_dir.emplace(out.subdirectory("frames"));
    if (s.obj || s.ply) mesh_dir.emplace(out.subdirectory("meshes"));
  }
  bool pixels;
  std::unique_ptr<OffscreenRenderer> renderer;
  std::optional<io::PendingFile> video_file;
  std::unique_ptr<Mp4Writer> video;
  std::optional<io::OutputDir> frame_dir;
  std::optional<io::OutputDir> mesh_dir;
};

/// The cameras: one following the jellyfish (made on the first frame, framing the jellyfish only)
/// and, for camera = "fixed", one over the whole path; and where the bell first was on screen.
struct Cameras {
  std::unique_ptr<FollowCamera> follow;
  std::optional<Camera> fixed;
  std::optional<std::array<double, 2>> first_on_screen;
};

/// The frames' writer: write_animation_outputs in steps (geometry, view, files; then the
/// animation's own files).
class AnimationWriter {
 public:
  AnimationWriter(JellyfishFrames& source, const PipelineSettings& s, const io::OutputDir& out)
      : source_(source),
        s_(s),
        out_(out),
        writers_(s, out),
        parts_(source.jellyfish_count()),
        caches_(source.jellyfish_count()),
        caching_(s.pc2 || s.mdd || s.usda || s.glb) {
    result_.marine_snow_specks = source.marine_snow_specks();
    style_ = s.style;
    style_.tissue_thickness_m = source.tissue_thickness_m();
    result_.renderer = writers_.renderer ? writers_.renderer->renderer_name() : "";
  }

  void add_frame(std::size_t k) {
    auto t0 = Clock::now();
    geometry::FrameGeometry g = jellyfish_geometry(k);
    if (!cameras_.follow) cameras_.follow = std::make_unique<FollowCamera>(s_, g.mesh);
    if (s_.camera == "fixed" && !cameras_.fixed) cameras_.fixed = fixed_camera(source_.path_box(), s_, g.mesh);
    source_.add_surroundings(k, g.mesh);
    if (caching_) caches_.add(parts_, g.mesh);
    geometry_s_ += seconds_since(t0);
    if (k > 0 && !geometry::same_topology(animation_.frames.front(), g.mesh))
      throw InputError("frame " + std::to_string(k) + " changes the mesh topology (point counts differ)");
    const Camera view = next_view();
    result_.cameras.push_back(view);
    if (k == 0 && s_.obj) frame_uv_ = merged_texture_coordinates(parts_);
    if (writers_.pixels) render_frame(k, g.mesh, view);
    write_frame_meshes(k, g.time_s, g.mesh);
    result_.vertices = g.mesh.vertex_count();
    result_.triangles = g.mesh.triangle_count();
    animation_.times_s.push_back(g.time_s);
    if (k == 0) animation_.frames.push_back(std::move(g.mesh));  // the topology every frame must keep
  }

  AnimationOutputs finish(std::size_t rendered) {
    if (writers_.video) {
      writers_.video->finish();
      writers_.video_file->commit();
      result_.files.push_back("jellyfish.mp4");
    }
    if (caching_) caches_.write(s_, animation_.times_s, out_, export_camera(), result_);
    if (s_.glb) write_glb();
    result_.frames = rendered;
    const auto per_frame = static_cast<double>(std::max<std::size_t>(rendered, 1));
    result_.geometry_seconds_per_frame = geometry_s_ / per_frame;
    result_.render_seconds_per_frame = writers_.pixels ? render_s_ / per_frame : 0.0;
    return result_;
  }

 private:
  /// Frame k's jellyfish (several merged into one mesh).
  geometry::FrameGeometry jellyfish_geometry(std::size_t k) {
    source_.build(k, parts_);
    if (parts_.size() == 1) return parts_.front();
    geometry::FrameGeometry g;
    g.time_s = parts_.front().time_s;
    merge_meshes(parts_, g.mesh);
    return g;
  }

  /// The camera of this frame (the follow camera moves every frame, also when the fixed one is
  /// used) and how far the bell has moved on screen since the first frame.
  Camera next_view() {
    Vec3 centre{};
    for (const auto& part : parts_) centre = centre + (1.0 / static_cast<double>(parts_.size())) * umbrella_centre(part);
    const Camera followed = cameras_.follow->next(centre);
    const Camera view = cameras_.fixed ? *cameras_.fixed : followed;
    const std::array<double, 2> on_screen = screen_position(view, centre);
    if (!cameras_.first_on_screen) cameras_.first_on_screen = on_screen;
    const auto& first = *cameras_.first_on_screen;
    result_.bell_screen_travel = std::hypot(on_screen[0] - first[0], on_screen[1] - first[1]);
    return view;
  }

  /// Frame k's pixels: the PNG (RGBA over a transparent background, else RGB), the video's frame
  /// and, with render.exr, the EXR (beauty and the depth and velocity passes).
  void render_frame(std::size_t k, const geometry::Mesh& mesh, const Camera& view) {
    const auto t0 = Clock::now();
    const bool transparent = s_.style.background == Background::transparent;
    OffscreenRenderer& renderer = *writers_.renderer;
    renderer.draw(mesh, view, style_);
    if ((s_.png_frames && transparent) || s_.exr) renderer.read_back(rgba_);
    if (writers_.video || (s_.png_frames && !transparent)) renderer.read_back(image_);
    if (s_.exr) {
      renderer.draw_passes(mesh, previous_.positions.empty() ? mesh.positions : previous_.positions, view,
                           previous_.camera.value_or(view), passes_);
      previous_ = {mesh.positions, view};
    }
    render_s_ += seconds_since(t0);
    if (s_.png_frames) {
      const std::string name = frame_name(k, "png");
      writers_.frame_dir->write_text(name, transparent ? png_bytes(rgba_) : png_bytes(image_));
      result_.files.push_back("frames/" + name);
    }
    if (s_.exr) {
      const std::string name = frame_name(k, "exr");
      writers_.frame_dir->write_text(name, exr_bytes(rgba_, passes_));
      result_.files.push_back("frames/" + name);
    }
    if (writers_.video) writers_.video->add(image_);
  }

  void write_frame_meshes(std::size_t k, double time_s, const geometry::Mesh& mesh) {
    const std::string comment = "jellysim frame " + std::to_string(k) + " t = " + io::format_double(time_s) + " s";
    if (s_.obj) {
      writers_.mesh_dir->write_text(frame_name(k, "obj"), io::obj_text(mesh, comment, "", frame_uv_));
      result_.files.push_back("meshes/" + frame_name(k, "obj"));
    }
    if (s_.ply) {
      writers_.mesh_dir->write_text(frame_name(k, "ply"), io::ply_bytes(mesh, comment));
      result_.files.push_back("meshes/" + frame_name(k, "ply"));
    }
  }

  void write_glb() {
    std::vector<io::GlbBody> bodies = caches_.glb_bodies(s_.vertex_velocities);
    std::vector<double> times = animation_.times_s;
    io::ExportCamera camera = export_camera();
    if (s_.loop_travel_m) close_loop(bodies, times, camera);
    const std::string glb = io::glb_bytes(bodies, times, io::glb_materials(look()), s_.glb_every, s_.fps, camera,
                                          s_.loop_travel_m.has_value());
    out_.write_text("jellyfish.glb", glb);
    out_.write_text("blender_import.py", kBlenderImport);
    result_.files.insert(result_.files.end(), {"jellyfish.glb", "blender_import.py"});
    result_.glb_bytes = glb.size();
    if (s_.viewer) write_viewer(s_, glb, out_, result_);
  }

  /// A loop's closing key for the .glb: frame 0 again one frame after the last (at N / fps on the
  /// frame clock), the jellyfish's roots and a follow camera moved on by the loop's travel.
  void close_loop(std::vector<io::GlbBody>& bodies, std::vector<double>& times, io::ExportCamera& camera) const {
    const Vec3 travel = *s_.loop_travel_m;
    for (io::GlbBody& b : bodies) {
      b.positions.push_back(b.positions.front());
      if (!b.root.empty()) b.root.push_back(b.root.front() + travel);
    }
    times.push_back(times.front() + static_cast<double>(times.size()) / s_.fps);
    if (camera.frames.empty()) return;
    io::CameraFrame c = camera.frames.front();
    if (s_.camera == "follow") c = {c.eye + travel, c.target + travel, c.up};
    camera.frames.push_back(c);
  }

  /// The settings' look, the tissue thickness from the first slice unless set.
  io::ExportLook look() const {
    io::ExportLook look = s_.look;
    if (!(look.tissue_thickness_m > 0.0)) look.tissue_thickness_m = source_.tissue_thickness_m();
    return look;
  }

  /// The cameras the frames were rendered with, for the .glb and .usda.
  io::ExportCamera export_camera() const {
    io::ExportCamera c;
    for (const Camera& v : result_.cameras) c.frames.push_back({v.eye, v.target, v.up});
    if (!result_.cameras.empty()) c.fov_y_deg = result_.cameras.front().fov_y_deg;
    c.aspect = static_cast<double>(s_.width_px) / s_.height_px;
    c.width_px = s_.width_px;
    c.height_px = s_.height_px;
    return c;
  }

  JellyfishFrames& source_;
  const PipelineSettings& s_;
  const io::OutputDir& out_;
  FrameWriters writers_;
  AnimationOutputs result_;
  geometry::Animation animation_;
  Cameras cameras_;
  double geometry_s_ = 0.0, render_s_ = 0.0;
  RgbImage image_;  // reused frame to frame
  RgbaImage rgba_;
  FramePasses passes_;
  /// The previous frame's vertices and camera (the velocity pass).
  struct {
    std::vector<Vec3> positions;
    std::optional<Camera> camera;
  } previous_;
  RenderStyle style_;  ///< s.style with the tissue's thickness from the first slice
  std::vector<geometry::FrameGeometry> parts_;
  std::vector<geometry::TexCoord> frame_uv_;  ///< the merged jellyfish's (per-frame OBJ)
  CacheRecorder caches_;
  bool caching_;
};

/// The one path from a source's geometry to the files: every frame through the writer, then the
/// animation's own files.
AnimationOutputs write_frames(JellyfishFrames& source, const PipelineSettings& s, const io::OutputDir& out,
                              const FrameProgress& progress) {
  AnimationWriter writer(source, s, out);
  const std::size_t frames = source.frame_count();
  std::size_t rendered = 0;
  for (std::size_t k = 0; k < frames; ++k, ++rendered) {
    if (k > 0 && core::interrupt_signal() != 0) break;  // SIGINT/SIGTERM: keep the frames so far
    writer.add_frame(k);
    if (progress) progress(k + 1, frames);
  }
  return writer.finish(rendered);
}

}  // namespace

AnimationOutputs write_animation_outputs(const School& school, const std::vector<std::uint64_t>& seeds,
                                         const PipelineSettings& s, const io::OutputDir& out,
                                         const FrameProgress& progress, const ObstacleFrames& obstacles,
                                         const std::vector<std::vector<Vec2>>& tracers) {
  check_recorded_frames(school, seeds, obstacles);
  SliceSchool source(school, seeds, s, obstacles, tracers);
  return write_frames(source, s, out, progress);
}

AnimationOutputs write_surface_animation_outputs(const geometry::SurfaceFrames& frames, const PipelineSettings& s,
                                                 const io::OutputDir& out, const FrameProgress& progress) {
  // The loop search (render.loop) lives with the slice runs (experiments/animation.cpp) and is not
  // done here; a loop_travel_m in the settings closes the .glb's loop as for slices.
  SimulatedBell source(frames, s);
  return write_frames(source, s, out, progress);
}

// ---- Figure 8.19 ------------------------------------------------------------------------------

namespace {

constexpr Rgb kPanelBackground{8, 30, 48};
constexpr Rgb kLabel{214, 232, 240};

/// Maps slice coordinates (m) into a panel with equal scales, y up.
struct SliceView {
  Vec2 centre;
  double pixels_per_m = 1.0;
  int width = 0, height = 0;
  Vec2 operator()(Vec2 p) const {
    return {0.5 * width + (p.x - centre.x) * pixels_per_m, 0.5 * height - (p.y - centre.y) * pixels_per_m};
  }
};

void draw_polyline(RgbImage& img, const SliceView& v, const std::vector<Vec2>& pts, double width, Rgb c) {
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Vec2 a = v(pts[i - 1]), b = v(pts[i]);
    draw_segment(img, a.x, a.y, b.x, b.y, width, c);
  }
}

RgbImage physics_panel(const jellyfish::SliceFrame& f, const SliceView& v) {
  RgbImage img(v.width, v.height, kPanelBackground);
  for (const auto& m : f.muscles) {
    const Vec2 a = v(f.umbrella[static_cast<std::size_t>(m.a)]), b = v(f.umbrella[static_cast<std::size_t>(m.b)]);
    draw_segment(img, a.x, a.y, b.x, b.y, 1.0, {200, 90, 90});
  }
  draw_polyline(img, v, f.umbrella, 1.6, {170, 210, 230});
  for (const auto& t : f.tentacles) {
    draw_polyline(img, v, t, 1.2, {230, 170, 190});
    for (const Vec2& p : t) draw_disc(img, v(p).x, v(p).y, 2.0, {230, 170, 190});
  }
  for (const Vec2& p : f.umbrella) draw_disc(img, v(p).x, v(p).y, 2.6, {240, 250, 255});
  return img;
}

RgbImage rendering_model_panel(const jellyfish::SliceFrame& f, const PipelineSettings& s, const SliceView& v) {
  RgbImage img(v.width, v.height, kPanelBackground);
  const geometry::RenderingSlice r = geometry::make_rendering_slice(f, s.geometry.latitude_samples,
                                                                    s.geometry.tentacle_samples, s.geometry.interpolant);
  std::vector<Vec2> hull = geometry::closed_hull(r.subumbrella, r.exumbrella);
  hull.push_back(hull.front());
  draw_polyline(img, v, hull, 1.6, {190, 225, 240});
  for (const auto& t : r.tentacles) draw_polyline(img, v, t, 1.2, {230, 170, 190});
  return img;
}

/// The geometry settings of one 3D stage: no noise, one kind, or all.
geometry::GeometrySettings stage_geometry(const PipelineSettings& s, int stage) {
  geometry::GeometrySettings g = s.geometry;
  geometry::NoiseSettings& n = g.noise;
  if (stage != 6) {
    n.structural_weight = stage == 3 ? s.geometry.noise.structural_weight : 0.0;
    n.unstructured_weight = stage == 4 ? s.geometry.noise.unstructured_weight : 0.0;
    n.compression_weight = stage == 5 ? s.geometry.noise.compression_weight : 0.0;
  }
  return g;
}

}  // namespace

std::vector<std::string> stage_names() {
  return {"2D physics model", "2D rendering model", "Extrapolated to 3D", "Structural noise",
          "Perlin noise", "Compression noise", "All noises"};
}

RgbImage render_stages_picture(const jellyfish::SliceFrame& expanded, const jellyfish::SliceFrame& contracted,
                               const PipelineSettings& s, int panel_w, int panel_h) {
  geometry::validate_slice(expanded);
  geometry::validate_slice(contracted);
  const double length = geometry::resolve_noise_length(s.geometry.noise, expanded);
  const jellyfish::SliceFrame* slices[2] = {&expanded, &contracted};
  const int label_w = 230, header_h = 40, gap = 6;
  const auto names = stage_names();
  const int rows = static_cast<int>(names.size());
  RgbImage picture(label_w + 2 * (panel_w + gap), header_h + rows * (panel_h + gap), {2, 14, 24});
  draw_text(picture, label_w + panel_w / 2 - 48, 12, "Expanded", 2, kLabel);
  draw_text(picture, label_w + panel_w + gap + panel_w / 2 - 60, 12, "Contracted", 2, kLabel);
  for (int r = 0; r < rows; ++r) draw_text(picture, 10, header_h + r * (panel_h + gap) + panel_h / 2 - 8, names[static_cast<std::size_t>(r)], 2, kLabel);

  // One 2D view and one camera for every panel, so the panels compare.
  geometry::GeometrySettings plain = stage_geometry(s, 2);
  const geometry::FrameGeometry reference = geometry::GeometryBuilder(plain, length).build(expanded);
  const geometry::Bounds b = geometry::bounds(reference.mesh);
  const Vec3 size = b.max - b.min;
  const double extent = std::max({size.x, size.y, size.z});
  const Vec2 centre{0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y)};
  const SliceView view{centre, 0.85 * std::min(panel_w, panel_h) / std::max(size.x, size.y), panel_w, panel_h};
  PipelineSettings look = s;
  look.camera_elevation_deg = 18.0;
  const Camera camera = camera_looking_at(Vec3{centre.x, centre.y, 0.0}, view_direction(look), 2.3 * extent, s.fov_y_deg);
  RenderStyle style = s.style;
  style.umbrella[3] = std::max(style.umbrella[3], 0.55);  // more opaque so the noise reads
  OffscreenRenderer renderer(panel_w, panel_h);

  for (int c = 0; c < 2; ++c) {
    const jellyfish::SliceFrame& f = *slices[c];
    const int x = label_w + c * (panel_w + gap);
    paste(picture, physics_panel(f, view), x, header_h);
    paste(picture, rendering_model_panel(f, s, view), x, header_h + (panel_h + gap));
    for (int r = 2; r < rows; ++r) {
      const geometry::FrameGeometry g = geometry::GeometryBuilder(stage_geometry(s, r), length).build(f);
      paste(picture, renderer.render(g.mesh, camera, style), x, header_h + r * (panel_h + gap));
    }
  }
  return picture;
}

}  // namespace jellysim::render
