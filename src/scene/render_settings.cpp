#include "jellysim/scene/render_settings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "jellysim/core/errors.hpp"

namespace jellysim::scene {
namespace {

using config::Range;

using namespace param;

// [render]: picture size, the 3D model's sampling, the camera, the looks and the output files.
std::vector<Parameter> render_section_parameters() {
  return {
      integer("render.width", "640", 16, 8192, "pixels (frames and video)"),
      integer("render.height", "480", 16, 8192, "pixels"),
      integer("render.latitude_samples", "65", 5, 100001, "rendering-model samples per umbrella surface (odd)"),
      integer("render.disc_points", "64", 8, 100000, "points around each disc, j_max"),
      integer("render.tentacle_samples", "40", 2, 100000, "samples along each tentacle"),
      integer("render.tentacle_count", "16", 1, 10000, "3D tentacles around the rim per opposing pair of slice tentacles"),
      integer("render.tube_sides", "6", 3, 64, "tentacle tube cross-section"),
      number("render.tentacle_radius", "0.00025", "m", Range::positive(), "at the root (tapers to 30 % at the tip)"),
      choice("render.interpolant", "catmull-rom", {"thesis", "catmull-rom"}, "eq. 7.8 as printed, or Catmull–Rom"),
      number("render.camera_distance_m", "0.22", "m", Range::positive(),
             "camera distance from its target: a bigger bell looks bigger"),
      number("render.camera_distance", "0.0", "first-frame mesh extents", Range::non_negative(),
             "> 0: the camera distance in first-frame mesh extents instead (the former framing: every bell the same size); 0: use camera_distance_m"),
      number("render.camera_elevation_deg", "12.0", "°", Range::closed(-89.0, 89.0), "camera elevation"),
      number("render.camera_azimuth_deg", "25.0", "°", Range::closed(-360.0, 360.0), "camera azimuth"),
      choice("render.camera", "fixed", {"fixed", "follow"},
             "fixed: one camera framing the whole path (the bell swims across the picture); follow: tracks the bell"),
      number("render.camera_follow", "0.25", "", Range{0.0, 1.0, true, false},
             "follow camera: fraction of the way to the jellyfish per frame"),
      number("render.fov_deg", "40.0", "°", Range::closed(5.0, 120.0), "vertical field of view"),
      number("render.obstacle_depth", "0.12", "m", Range{0.0, 100.0, true, false},
             "obstacles are drawn as prisms this long across the slice"),
      number("render.umbrella_opacity", "0.35", "", Range::closed(0.0, 1.0),
             "base alpha of the translucent umbrella (rim adds more at grazing angles)"),
      number("render.tentacle_opacity", "0.75", "", Range::closed(0.0, 1.0), "alpha of the tentacles"),
      number("render.rim", "0.55", "", Range::closed(0.0, 1.0), "rim opacity/brightness at grazing angles"),
  };
}

// [render]'s look: colours, the bell's tissue, the key light, the background (issue 39).
std::vector<Parameter> look_parameters() {
  const Range unit = Range::closed(0.0, 1.0);
  return {
      vec3("render.rim_color", "[0.45, 0.65, 0.75]", "", unit, "linear RGB of the rim's added light"),
      vec3("render.bell_color", "[0.78, 0.9, 1.0]", "", unit,
           "linear RGB of the umbrella; also the tissue's attenuation colour"),
      vec3("render.tentacle_color", "[1.0, 0.72, 0.8]", "", unit, "linear RGB of the tentacles"),
      number("render.transmission", "1.0", "", unit,
             "fraction of the light from behind that the bell's tissue passes (where its opacity lets it through)"),
      number("render.attenuation_distance", "1.0", "m", Range::positive(),
             "Beer–Lambert: light through this much tissue keeps bell_color of itself"),
      vec3("render.key_light_direction", "[0.2, 1.0, 0.6]", "", Range{},
           "towards the key light, world axes (y up; normalised; not zero)"),
      vec3("render.key_light_color", "[0.95, 0.98, 1.0]", "", Range::closed(0.0, 100.0), "linear RGB of the key light"),
      choice("render.background", "water", {"water", "solid", "transparent"},
             "water: gradient and light shafts; solid: background_color; transparent: RGBA frames, alpha 0 (the video is over black)"),
      vec3("render.background_color", "[0.0, 0.05, 0.13]", "", unit, "linear RGB of the solid background"),
  };
}

// [render]'s output files and the marine snow.
std::vector<Parameter> output_parameters() {
  const Range unit = Range::closed(0.0, 1.0);
  return {
      boolean("render.png_frames", "true", "frames/frame_0000.png …"),
      boolean("render.video", "true", "jellyfish.mp4 (ffmpeg, H.264)"),
      boolean("render.glb", "true", "jellyfish.glb (glTF 2.0: a node per jellyfish with its root motion, quantized morph targets)"),
      integer("render.glb_every", "2", 1, 1000, "a morph target every n-th frame (and the last); playback interpolates"),
      boolean("render.obj", "false", "meshes/frame_0000.obj … (about 1.5 MB per frame)"),
      boolean("render.ply", "false", "meshes/frame_0000.ply …"),
      boolean("render.viewer", "true", "viewer.html (needs glb)"),
      boolean("render.page_embed", "false",
              "viewer.html embeds the .glb (jellyfish.glb.js, opens from file://); else loads it (serve the folder)"),
      boolean("render.marine_snow", "true",
              "the simulation's tracers as specks around the bell's axis: motion reads even with a follow camera"),
      number("render.snow_size", "0.0003", "m", Range{0.0, 0.01, true, false}, "size of a marine snow speck"),
      number("render.snow_density", "1.0", "", unit, "fraction of the tracers near the bell drawn as marine snow"),
      boolean("render.exr", "false",
              "frames/frame_0000.exr: OpenEXR with beauty (RGBA, linear half), depth (Z, m) and velocity (px per frame)"),
      boolean("render.vertex_velocities", "true",
              "per-vertex velocities (m/s, for motion blur) in jellyfish.glb (_VELOCITY) and jellyfish.usda "
              "(velocities); false: a smaller .glb"),
      boolean("render.pc2", "true", "caches/jellyfish_N.obj rest mesh + .pc2 point cache per jellyfish (and obstacles)"),
      boolean("render.mdd", "false", "caches/*.mdd point caches (big-endian; Maya, Houdini, 3ds Max)"),
      boolean("render.usda", "false", "jellyfish.usda: USD stage, root motion + time-sampled points (text, large)"),
  };
}

// [render.noise]: the surface noise of §7.1 (eqs. 7.10–7.18, Figure 8.19).
std::vector<Parameter> noise_section_parameters() {
  const Range frequency = Range::closed(0.0, 1000.0);
  return {
      integer("render.noise.seed", "1", 0, 2147483647,
              "the individual (0 = Perlin's reference permutation)"),
      number("render.noise.structural_weight", "0.01875", "", Range::non_negative(),
             "w_s of Figure 8.19 (fractions of the noise length)", {0.0, 0.2}),
      number("render.noise.compression_weight", "0.125", "", Range::non_negative(), "w_c of Figure 8.19", {0.0, 1.0}),
      number("render.noise.unstructured_weight", "0.45", "", Range::non_negative(), "w_u of Figure 8.19", {0.0, 2.0}),
      number("render.noise.structural_frequency", "9.0", "", frequency, "f of eqs. 7.10/7.11"),
      choice("render.noise.structural_form", "abs", {"abs", "sin"}, "abs: eq. 7.11 |sin fσ| (Fig. 8.19); sin: eq. 7.10"),
      number("render.noise.compression_frequency", "9.0", "", frequency, "ridge frequency in eq. 7.14 (as printed: 1)"),
      number("render.noise.max_contraction", "0.56", "", Range{0.0, 1.0, true, true}, "γ (§7.1)"),
      number("render.noise.latitude_frequency", "2.0", "", frequency, "eq. 7.18: Q_P(2 d_i, 8 d_j, 0.01 t)"),
      number("render.noise.longitude_frequency", "8.0", "", frequency, "eq. 7.18's 8"),
      number("render.noise.time_frequency", "0.3", "1/s", frequency, "eq. 7.18's 0.01 per frame at 30 frames/s"),
      number("render.noise.length_scale", "0.0", "m", Range::non_negative(),
             "the length the noise equations are in; 0: the first frame's bell height"),
      boolean("render.noise.tentacles", "true", "unstructured noise on the tentacles too"),
      boolean("render.noise.bend_shell", "true",
              "unstructured noise moves both surfaces together (false: each along its own normal)"),
  };
}

// [render]'s seamless loop (issue 39 item 3; jellyfish/stroke_loop.hpp, docs/rendering.md).
std::vector<Parameter> loop_parameters() {
  return {
      boolean("render.loop", "false",
              "a seamless loop: simulate until render.loop_cycles whole cycles close on themselves, then animate them "
              "(the frame rate rounded to whole frames per cycle; `jellysim run --loop CYCLES`)"),
      integer("render.loop_cycles", "1", 1, 100, "contraction cycles in the loop (below render.loop_max_cycles)"),
      number("render.loop_tolerance", "0.05", "", Range{0.0, 1.0, true, false},
             "the loop closes when the start of the cycle after it matches its first frame: umbrella shape about its "
             "centroid (RMS, of the diameter) and centroid speed (of diameter × frequency)"),
      integer("render.loop_max_cycles", "10", 2, 1000,
              "the last cycle whose start may close the loop; none by then: the loop cut at the best match, exit 1"),
      choice("render.loop_root_motion", "remove", {"remove", "constant"},
             "remove: the travel over the loop taken out linearly (the bell swims in place); constant: kept (frame N "
             "is frame 0 moved by summary.json's loop.travel)"),
  };
}

ParameterTable make_render_parameters() {
  std::vector<Parameter> p = render_section_parameters();
  for (std::vector<Parameter> more : {look_parameters(), output_parameters(), loop_parameters()})
    for (Parameter& q : more) p.push_back(std::move(q));
  for (Parameter& n : noise_section_parameters()) p.push_back(std::move(n));
  return ParameterTable("render", "", std::move(p));
}

geometry::NoiseSettings read_noise(const Reader& r) {
  geometry::NoiseSettings n;
  n.seed = static_cast<std::uint64_t>(r.integer("render.noise.seed"));
  n.structural_weight = r.number("render.noise.structural_weight");
  n.compression_weight = r.number("render.noise.compression_weight");
  n.unstructured_weight = r.number("render.noise.unstructured_weight");
  n.structural_frequency = r.number("render.noise.structural_frequency");
  n.structural_absolute = r.choice("render.noise.structural_form") == "abs";
  n.compression_frequency = r.number("render.noise.compression_frequency");
  n.max_contraction = r.number("render.noise.max_contraction");
  n.latitude_frequency = r.number("render.noise.latitude_frequency");
  n.longitude_frequency = r.number("render.noise.longitude_frequency");
  n.time_frequency_hz = r.number("render.noise.time_frequency");
  n.length_scale_m = r.number("render.noise.length_scale");
  n.tentacles = r.boolean("render.noise.tentacles");
  n.bend_shell = r.boolean("render.noise.bend_shell");
  return n;
}

std::array<double, 3> rgb(const Reader& r, std::string_view key) {
  const std::vector<double> v = r.numbers(key);
  return {v[0], v[1], v[2]};
}

render::Background parse_background(const std::string& name) {
  if (name == "solid") return render::Background::solid;
  if (name == "transparent") return render::Background::transparent;
  return render::Background::water;
}

/// The look: colours, the bell's tissue, the key light and the background.
void read_look(const Reader& r, render::PipelineSettings& s) {
  render::RenderStyle& style = s.style;
  const auto bell = rgb(r, "render.bell_color"), tentacles = rgb(r, "render.tentacle_color");
  std::copy(bell.begin(), bell.end(), style.umbrella.begin());
  std::copy(tentacles.begin(), tentacles.end(), style.tentacles.begin());
  style.rim_colour = rgb(r, "render.rim_color");
  style.transmission = r.number("render.transmission");
  style.attenuation_distance_m = r.number("render.attenuation_distance");
  const auto d = rgb(r, "render.key_light_direction");
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(length > 1e-9))
    throw InputError("field 'render.key_light_direction' = [" + config::format_number(d[0]) + ", " +
                     config::format_number(d[1]) + ", " + config::format_number(d[2]) +
                     "] must not be the zero vector (it points towards the light)");
  style.lights[0].direction = {d[0], d[1], d[2]};  // the shader normalises it
  style.lights[0].colour = rgb(r, "render.key_light_color");
  style.background = parse_background(r.choice("render.background"));
  style.background_colour = rgb(r, "render.background_color");
}

}  // namespace

const ParameterTable& render_parameters() {
  static const ParameterTable table = make_render_parameters();
  return table;
}

render::PipelineSettings read_render_settings(const config::Config& c) {
  const Reader r(c, render_parameters());
  render::PipelineSettings s;
  geometry::GeometrySettings& g = s.geometry;
  s.width_px = static_cast<int>(r.integer("render.width"));
  s.height_px = static_cast<int>(r.integer("render.height"));
  g.latitude_samples = static_cast<int>(r.integer("render.latitude_samples"));
  if (g.latitude_samples % 2 == 0)
    throw InputError("field 'render.latitude_samples' = " + std::to_string(g.latitude_samples) + " must be odd");
  g.disc_points = static_cast<int>(r.integer("render.disc_points"));
  g.tentacle_samples = static_cast<int>(r.integer("render.tentacle_samples"));
  g.tentacle_count = static_cast<int>(r.integer("render.tentacle_count"));
  g.tube_sides = static_cast<int>(r.integer("render.tube_sides"));
  g.tentacle_radius_m = r.number("render.tentacle_radius");
  g.interpolant = geometry::parse_interpolant(r.choice("render.interpolant"), "render.interpolant");
  g.noise = read_noise(r);
  s.camera_distance = r.number("render.camera_distance");
  s.camera_distance_m = r.number("render.camera_distance_m");
  s.camera_elevation_deg = r.number("render.camera_elevation_deg");
  s.camera_azimuth_deg = r.number("render.camera_azimuth_deg");
  s.camera = r.choice("render.camera");
  s.camera_follow = r.number("render.camera_follow");
  s.fov_y_deg = r.number("render.fov_deg");
  s.obstacle_depth_m = r.number("render.obstacle_depth");
  s.style.umbrella[3] = r.number("render.umbrella_opacity");
  s.style.tentacles[3] = r.number("render.tentacle_opacity");
  s.style.rim = r.number("render.rim");
  read_look(r, s);
  s.png_frames = r.boolean("render.png_frames");
  s.video = r.boolean("render.video");
  s.glb = r.boolean("render.glb");
  s.obj = r.boolean("render.obj");
  s.ply = r.boolean("render.ply");
  s.viewer = r.boolean("render.viewer");
  s.page_embed = r.boolean("render.page_embed");
  s.glb_every = static_cast<int>(r.integer("render.glb_every"));
  s.marine_snow = r.boolean("render.marine_snow");
  s.snow_size_m = r.number("render.snow_size");
  s.snow_density = r.number("render.snow_density");
  s.exr = r.boolean("render.exr");
  s.vertex_velocities = r.boolean("render.vertex_velocities");
  s.pc2 = r.boolean("render.pc2");
  s.mdd = r.boolean("render.mdd");
  s.usda = r.boolean("render.usda");
  if (s.viewer && !s.glb) throw InputError("field 'render.viewer' = true needs 'render.glb' = true");
  s.viewer_script = render::default_viewer_script();
  geometry::validate_geometry_settings(g);
  return s;
}

jellyfish::LoopSettings read_loop_settings(const config::Config& c) {
  const Reader r(c, render_parameters());
  jellyfish::LoopSettings loop;
  loop.enabled = r.boolean("render.loop");
  loop.cycles = static_cast<int>(r.integer("render.loop_cycles"));
  loop.tolerance = r.number("render.loop_tolerance");
  loop.max_cycles = static_cast<int>(r.integer("render.loop_max_cycles"));
  loop.root_motion = r.choice("render.loop_root_motion") == "constant" ? jellyfish::RootMotion::constant
                                                                        : jellyfish::RootMotion::remove;
  return loop;
}

}  // namespace jellysim::scene
