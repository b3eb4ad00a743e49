#pragma once
// What the interchange files (.glb, .usda) carry beside the meshes: the look (materials) and the
// film camera, and the vertices' velocities. Plain data, filled by the pipeline (render) from its
// settings; the writers (mesh_files.hpp, point_caches.hpp) turn it into glTF and USD.
#include <array>
#include <vector>

#include "jellysim/geometry/vec3.hpp"

namespace jellysim::io {

/// The materials of the exported files. The defaults are the offscreen renderer's
/// (render::RenderStyle: umbrella, tentacles, obstacles, snow); the `render.bell_color`,
/// `render.tentacle_color`, `render.transmission`, `render.attenuation_distance`,
/// `render.umbrella_opacity` and `render.tentacle_opacity` keys fill it (src/experiments/animation.cpp).
struct ExportLook {
  std::array<double, 3> bell_color{0.78, 0.90, 1.00};      ///< linear RGB (glTF baseColor, USD diffuseColor)
  std::array<double, 3> tentacle_color{1.00, 0.72, 0.80};  ///< linear RGB
  double transmission = 1.0;            ///< [0, 1]: KHR_materials_transmission of the bell
  double attenuation_distance_m = 1.0;  ///< KHR_materials_volume: light through this much tissue keeps bell_color
  double umbrella_opacity = 0.35;       ///< glTF baseColor alpha (BLEND), USD opacity
  double tentacle_opacity = 0.75;
  double ior = 1.34;                    ///< mesoglea is mostly sea water (KHR_materials_ior, USD ior)
  double bell_roughness = 0.3, tentacle_roughness = 0.5;
  std::array<double, 4> obstacle_rgba{0.15, 0.14, 0.13, 1.00};
  std::array<double, 4> snow_rgba{0.85, 0.92, 0.95, 0.80};
  /// The bell wall's thickness (m) for KHR_materials_volume: the slices' mesoglea thickness ϑ.
  double tissue_thickness_m = 0.0;
};

/// The film camera in one frame: where it is, what it looks at, which way is up (the renderer's
/// look-at camera; the picture's up is `up` made orthogonal to the view direction).
struct CameraFrame {
  geometry::Vec3 eye, target, up{0.0, 1.0, 0.0};
};

/// The renderer's camera through an animation, one frame per recorded frame (empty: no camera).
struct ExportCamera {
  std::vector<CameraFrame> frames;
  double fov_y_deg = 40.0;
  double aspect = 4.0 / 3.0;  ///< picture width / height
  int width_px = 0, height_px = 0;  ///< the rendered frames' size (0: not said)
  /// Clipping planes in eye–target distances of the first frame (the renderer's 0.02 and 50).
  double near_fraction = 0.02, far_fraction = 50.0;
  double near_m() const;
  double far_m() const;
  /// Whether every frame's camera is the first's (a "fixed" camera: no animation is written).
  bool still() const;
};

/// The rotation (unit quaternion x, y, z, w) that turns a glTF or USD camera (looking down −z, y up)
/// into `frame`'s view: −z → the view direction, +y → the picture's up.
std::array<double, 4> camera_rotation(const CameraFrame& frame);

/// The camera's axes in world space: right (+x), up (+y), back (+z; the view direction is −back).
std::array<geometry::Vec3, 3> camera_axes(const CameraFrame& frame);

/// Per frame and vertex, the velocity (m/s) from the frame-to-frame positions: central differences
/// (x_{k+1} − x_{k−1}) / (t_{k+1} − t_{k−1}) inside, one-sided at the first and last frames; zero
/// for a single frame. Throws InputError when counts disagree or times do not increase.
std::vector<std::vector<geometry::Vec3>> vertex_velocities(const std::vector<std::vector<geometry::Vec3>>& frames,
                                                           const std::vector<double>& times_s);

}  // namespace jellysim::io
