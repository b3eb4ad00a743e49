#pragma once
// Offscreen OpenGL rendering of jellyfish meshes (thesis §7.4): an OpenGL 3.3 core context through
// EGL on Mesa's surfaceless platform (software llvmpipe: no display and no GPU needed), depth
// buffering, the three-term (ambient + diffuse + specular) lighting model with directional
// lights, translucency (back faces then front faces, blended, with a view-dependent rim), and a
// water-like background. Output code only: it receives meshes and returns pixels.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "jellysim/geometry/mesh.hpp"
#include "jellysim/render/image.hpp"

namespace jellysim::render {

struct Camera {
  geometry::Vec3 eye{0.0, 0.0, 0.1};
  geometry::Vec3 target{0.0, 0.0, 0.0};
  geometry::Vec3 up{0.0, 1.0, 0.0};
  double fov_y_deg = 40.0;
};

/// A camera at `distance_m` from `target`, looking along −`from` (a direction, need not be unit).
Camera camera_looking_at(geometry::Vec3 target, geometry::Vec3 from, double distance_m, double fov_y_deg);

/// Where `p` lands in the picture of `camera`: x and y in units
/// of the picture's height, from its centre (y up); the picture spans y in [−0.5, 0.5].
std::array<double, 2> screen_position(const Camera& camera, geometry::Vec3 p);

struct DirectionalLight {
  geometry::Vec3 direction{0.3, 1.0, 0.5};  ///< toward the light
  std::array<double, 3> colour{1.0, 1.0, 1.0};
};

/// What is behind the jellyfish: the water gradient, one colour, or nothing (alpha 0).
enum class Background { water, solid, transparent };

struct RenderStyle {
  Background background = Background::water;
  std::array<double, 3> background_colour{0.00, 0.05, 0.13};  ///< Background::solid (linear RGB)
  std::array<double, 3> water_top{0.10, 0.42, 0.56};     ///< background near the surface (linear RGB)
  std::array<double, 3> water_bottom{0.00, 0.05, 0.13};  ///< background in the depth
  bool light_shafts = true;                              ///< soft rays from above in the background
  std::array<double, 4> umbrella{0.78, 0.90, 1.00, 0.35};   ///< RGBA; alpha < 1: translucent
  std::array<double, 4> tentacles{1.00, 0.72, 0.80, 0.75};
  std::array<double, 4> obstacles{0.15, 0.14, 0.13, 1.00};  ///< opaque dark rock (lights and rim brighten it)
  std::array<double, 4> snow{0.85, 0.92, 0.95, 0.80};       ///< marine snow specks (mesh part "snow")
  double ambient = 0.30;
  double specular = 0.45;
  double shininess = 40.0;
  double rim = 0.55;  ///< extra opacity and brightness at grazing angles (translucent look)
  std::array<double, 3> rim_colour{0.45, 0.65, 0.75};  ///< the rim's added light (linear RGB)
  /// The umbrella's tissue: the light from behind it that its coverage lets through is multiplied by
  /// transmission × umbrella_rgb^(d / attenuation_distance_m) (Beer–Lambert with the glTF volume
  /// extension's attenuation colour), d = ½ tissue_thickness_m / |n·v| per surface crossed (a wall
  /// of the shell is crossed through two surfaces). 1 and an infinite distance: clear tissue.
  double transmission = 1.0;
  double attenuation_distance_m = 1.0;
  double tissue_thickness_m = 0.0;
  /// lights[0]: the key light (render.key_light_*), lights[1]: a dim blue fill from below.
  std::array<DirectionalLight, 2> lights{DirectionalLight{{0.2, 1.0, 0.6}, {0.95, 0.98, 1.0}},
                                         DirectionalLight{{-0.6, -0.3, 0.4}, {0.25, 0.35, 0.45}}};
  /// Light at the vertices and interpolate (Gouraud) instead of per pixel, for interactive use:
  /// with llvmpipe at 640×480 without multisampling a frame costs ≈ 12 ms instead of ≈ 27;
  /// highlights and the rim are a little softer (docs/rendering.md, "Interactive rendering").
  bool per_vertex_lighting = false;
};

/// Depth and screen-space velocity per pixel, top row first (for OpenEXR passes).
struct FramePasses {
  int width = 0, height = 0;
  std::vector<float> depth_m;     ///< width × height
  std::vector<float> velocity_px; ///< width × height × 2: (x right, y up) per pixel
};
/// The depth pass's value where no surface is (Blender's convention for its Z pass).
constexpr float kBackgroundDepth = 1.0e10f;

/// Whether an offscreen OpenGL 3.3 context can be created here; `why` gets the reason if not.
bool offscreen_gl_available(std::string* why);

/// The renderer keeps its context, programs, framebuffers, buffers and the background (drawn once
/// per style and size, then copied) between frames: a frame uploads the vertices and one index
/// list, draws and reads back, with no allocation once the sizes are known.
class OffscreenRenderer {
 public:
  /// Creates the context and framebuffers with `samples` × multisampling (rounded up by the driver
  /// to a count it offers, e.g. 4 on llvmpipe; 1: a single-sample framebuffer, no multisampling
  /// and no resolve). Throws RunError when no EGL/OpenGL context can be made (the message says
  /// what is missing) and InputError for a size outside [16, 8192] or samples outside [1, 16].
  OffscreenRenderer(int width_px, int height_px, int samples = 4);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Renders the mesh's parts "umbrella" and "tentacles" (others drawn like the umbrella):
  /// draw() then read_back().
  RgbImage render(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style);
  /// The same into `image`, reusing its buffer when it already has this size (no allocation).
  void render(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style, RgbImage& image);

  /// Draws a frame into the offscreen framebuffer without reading it back (for timing, or before
  /// read_back()).
  void draw(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style);
  /// Resolves the multisampled framebuffer and reads the last drawn frame into `image` (top row
  /// first), reusing its buffer when it has the renderer's size.
  void read_back(RgbImage& image);
  /// The same with alpha (straight, not premultiplied: PNG's convention); a transparent background
  /// reads as alpha 0, the water and a solid colour as 255.
  void read_back(RgbaImage& image);
  /// Draws the data passes of `mesh` seen by `camera` (opaque, depth-tested, single sample) and
  /// reads them into `passes`: per pixel the depth (m from the eye along the view axis; background
  /// kBackgroundDepth) and the screen-space velocity (pixels per frame, x right, y up) from where
  /// each vertex was at the previous frame, `previous_positions` (one per vertex of `mesh`) seen by
  /// `previous_camera`. Leaves the beauty framebuffer as it was.
  void draw_passes(const geometry::Mesh& mesh, const std::vector<geometry::Vec3>& previous_positions,
                   const Camera& camera, const Camera& previous_camera, FramePasses& passes);
  /// Waits until the frame drawn so far is complete (software rendering runs behind the calls).
  void finish();

  int width() const;
  int height() const;
  int samples() const;                ///< samples per pixel in use (1: no multisampling)
  std::string renderer_name() const;  ///< GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace jellysim::render
