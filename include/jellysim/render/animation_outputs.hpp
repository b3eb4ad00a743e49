#pragma once
// From recorded slices to the files a user holds (thesis §7.2–7.4, §8.2.4): PNG frames, an MP4,
// an animated .glb, per-frame OBJ/PLY meshes and a small HTML viewer; and the Figure 8.19 stages
// picture. The only place where geometry, meshes and pixels meet; physics never calls into it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/surface_geometry.hpp"
#include "jellysim/io/interchange.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"
#include "jellysim/render/gl_renderer.hpp"
#include "jellysim/render/image.hpp"

namespace jellysim::render {

struct PipelineSettings {
  geometry::GeometrySettings geometry;
  int width_px = 640;
  int height_px = 480;
  double fps = 30.0;                  ///< video frame rate: 1 / the recorded frame interval (real time)
  /// The camera's distance from its target (m): a bigger bell looks bigger. The fixed camera looks at
  /// the middle of the path the jellyfish took from this distance (not fitted to the path).
  double camera_distance_m = 0.22;
  /// > 0: the distance in first-frame mesh extents instead (and the fixed camera backs off until the
  /// path fits the picture), the framing before 2026-11-28 with 2.6: every bell looked the same size.
  double camera_distance = 0.0;
  double camera_elevation_deg = 12.0; ///< above the horizontal
  double camera_azimuth_deg = 25.0;   ///< around the axis, from the slice normal (+z)
  /// "fixed": one camera for the whole animation, framing the path the jellyfish took (computed
  /// after simulating), so the swimmer travels across the picture; "follow": the camera follows the
  /// bell (it then stays near the middle of every frame).
  std::string camera = "fixed";
  double camera_follow = 0.25;        ///< "follow": per frame, the fraction of the way the target moves to the jellyfish (1: rigid)
  double fov_y_deg = 40.0;
  /// The scene's obstacles are drawn as prisms this long across the slice plane (m); the 2D
  /// simulation treats them as infinitely long (geometry/obstacle_mesh.hpp).
  double obstacle_depth_m = 0.12;
  /// Multisampling of the rendered frames (OffscreenRenderer; 1: none). Not a config field: the
  /// video keeps 4×; the interactive setting is 1 with style.per_vertex_lighting (docs/rendering.md).
  int samples = 4;
  RenderStyle style;
  bool png_frames = true, video = true, glb = true, obj = true, ply = true, viewer = true;
  /// Point caches for VFX pipelines (caches/NAME.obj rest mesh + NAME.pc2 / NAME.mdd per jellyfish
  /// and for the obstacles) and a USD stage (jellyfish.usda: root motion + time-sampled points).
  bool pc2 = true, mdd = false, usda = false;
  /// .glb: a morph target every n-th frame (and the last), played back by linear interpolation.
  int glb_every = 2;
  /// The materials of the .glb and .usda (the renderer's colours by default; export_look(style)).
  /// A zero tissue thickness is taken from the first slice (its mesoglea thickness).
  io::ExportLook look;
  /// Marine snow: the simulation's tracers as specks of this size (m) in the 3D picture.
  bool marine_snow = true;
  double snow_size_m = 0.0003;
  double snow_density = 1.0;  ///< fraction of the tracers near the jellyfish drawn as specks
  /// frames/frame_NNNN.exr: beauty (RGBA, linear half), depth (Z, m) and screen-space velocity
  /// (velocity.X, velocity.Y: pixels per frame) passes (render/exr_frames.hpp).
  bool exr = false;
  /// A seamless loop (render.loop, experiments/animation.cpp): the frames are the loop's, and the
  /// .glb gets its closing key, frame 0 again one frame after the last, the jellyfish's roots (and a
  /// follow camera) moved on by this travel (m; zero when the root motion is removed), so that a
  /// player looping the clip wraps without a jump (io::glb_bytes's closes_loop). Unset: no loop.
  std::optional<geometry::Vec3> loop_travel_m;
  /// The jellyfish's per-vertex velocities (m/s) in the .glb (_VELOCITY) and .usda (`velocities`),
  /// for motion blur; off, the .glb is about a quarter smaller (docs/rendering.md).
  bool vertex_velocities = true;
  /// viewer.html: embed the .glb as base64 (jellyfish.glb.js, opens from file://) instead of
  /// loading jellyfish.glb beside it (needs a web server: browsers refuse file:// fetches).
  bool page_embed = false;
  /// The bundled viewer script (three.js + GLTFLoader + controls) copied next to viewer.html.
  std::filesystem::path viewer_script;
};

/// The default viewer bundle: <source dir>/web/dist/jellyfish-viewer.js (built by `npm run build`
/// in web/, see docs/rendering.md), or, in an installed tree without the sources,
/// PREFIX/share/jellysim/web/jellyfish-viewer.js beside the running program's PREFIX/bin.
std::filesystem::path default_viewer_script();

/// The materials of the exported files from the renderer's style: the umbrella's and tentacles'
/// colours and opacities, the obstacles' and the snow's.
io::ExportLook export_look(const RenderStyle& style);

/// Called after each frame: (frames done, frames in all).
using FrameProgress = std::function<void(std::size_t done, std::size_t total)>;

/// What write_animation_outputs wrote and measured.
struct AnimationOutputs {
  std::size_t frames = 0;
  std::size_t vertices = 0, triangles = 0;     ///< per frame
  double geometry_seconds_per_frame = 0.0;     ///< resample + extrapolate + noise + normals
  double render_seconds_per_frame = 0.0;       ///< OpenGL draw + read back (0 when no PNG/video)
  std::size_t glb_bytes = 0;
  std::string renderer;                        ///< GL_RENDERER string
  bool viewer_has_script = false;              ///< the viewer bundle was found and copied
  std::vector<std::string> files;              ///< relative paths written
  /// How far the middle of the umbrellas moved on screen from the first frame to the last, in
  /// picture heights.
  double bell_screen_travel = 0.0;
  std::size_t marine_snow_specks = 0;  ///< tracers drawn as marine snow
  /// The camera each frame was rendered with (also when no pixels were written): the one the
  /// .glb and .usda carry.
  std::vector<Camera> cameras;
  /// Key figures for summary.json.
  nlohmann::ordered_json figures() const;
};

/// Writes, as the settings ask: frames/frame_0000.png …, jellyfish.mp4, jellyfish.glb,
/// meshes/frame_0000.obj and .ply …, viewer.html with jellyfish-viewer.js and jellyfish.glb.js.
/// Frames must have increasing times and one topology (same umbrella and tentacle point counts).
/// Throws InputError for bad slices or settings, RunError when a file, OpenGL or ffmpeg fails.
AnimationOutputs write_animation_outputs(const std::vector<jellyfish::SliceFrame>& frames,
                                         const PipelineSettings& settings, const io::OutputDir& out,
                                         const FrameProgress& progress = {});

/// Per recorded frame, each obstacle's outline in the slice plane (m), e.g. its markers.
using ObstacleFrames = std::vector<std::vector<std::vector<Vec2>>>;

/// The same for several jellyfish in one scene: school[j] are the frames of jellyfish j (all the
/// same count), seeds[j] its noise individual. Every frame's meshes are merged into one (all
/// umbrellas, then all tentacles), so the .glb and meshes hold the whole school and the camera
/// follows the middle of the umbrellas. `obstacles`, when not empty, holds one entry per frame: the
/// obstacles become the mesh part "obstacles", prisms `settings.obstacle_depth_m` long. `tracers`,
/// when not empty, holds each frame's tracer positions: with settings.marine_snow they become the
/// specks of geometry::MarineSnow (part "snow") around the first jellyfish's axis, those near the
/// path the jellyfish took.
AnimationOutputs write_animation_outputs(const std::vector<std::vector<jellyfish::SliceFrame>>& school,
                                         const std::vector<std::uint64_t>& seeds, const PipelineSettings& settings,
                                         const io::OutputDir& out, const FrameProgress& progress = {},
                                         const ObstacleFrames& obstacles = {},
                                         const std::vector<std::vector<Vec2>>& tracers = {});

/// The same files for a simulated 3D bell (the 3D swimmer; geometry/surface_geometry.hpp): its
/// surface drawn as simulated, closed into a wall of thickness frames.thickness_m, its tentacles as
/// tubes; no extrapolation and no noise (settings.geometry's noise is not used), no obstacles or
/// marine snow (slice-tank only). The camera, pixels, video, meshes, caches, .glb and viewer follow
/// the slice pipeline's rules: one path after the geometry. Throws InputError for bad frames
/// (validate_surface_frames) or settings, RunError when a file, OpenGL or ffmpeg fails.
AnimationOutputs write_surface_animation_outputs(const geometry::SurfaceFrames& frames,
                                                 const PipelineSettings& settings, const io::OutputDir& out,
                                                 const FrameProgress& progress = {});

/// The camera distance (m) for a first frame whose mesh is `extent_m` across at its widest:
/// camera_distance × extent when camera_distance > 0, else camera_distance_m.
double camera_distance_for(const PipelineSettings& settings, double extent_m);

/// The fixed camera of an animation: looking at the middle of the box that holds every jellyfish in
/// every frame from the configured direction, at camera_distance_for(…, the first frame's extent)
/// (with camera_distance > 0, further back if the box's bounding sphere would not fit the picture).
Camera fixed_camera(const std::vector<std::vector<jellyfish::SliceFrame>>& school, const PipelineSettings& settings,
                    const geometry::Mesh& first);
/// The same for a path given as its box (min, max corners, m): the one framing rule of both pipelines.
Camera fixed_camera(const std::array<geometry::Vec3, 2>& path_box, const PipelineSettings& settings,
                    const geometry::Mesh& first);

/// Figure 8.19 as one picture: rows 2D physics model, 2D rendering model, extrapolated to 3D,
/// structural noise, Perlin noise, compression noise, all noises; columns expanded, contracted.
/// The noise length and individual come from `settings` (length from the expanded slice when 0).
RgbImage render_stages_picture(const jellyfish::SliceFrame& expanded, const jellyfish::SliceFrame& contracted,
                               const PipelineSettings& settings, int panel_width_px = 360, int panel_height_px = 300);

/// The stage names of render_stages_picture, top to bottom.
std::vector<std::string> stage_names();

}  // namespace jellysim::render
