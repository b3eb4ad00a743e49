#pragma once
// The jellyfish scene in 3D water (tank.geometry = "3d"; issue 40 part 4, docs/three-d.md "The 3D
// scene"): the jellyfish scene's one parameter table (scene/jellyfish_scene.hpp) read into the 3D
// swimmer's spec (swim3d::Swim3dSpec) and the run's frames. The [jellyfish] shape, material and
// stroke are read by the 2D scene's reader (read_jellyfish_body); fields the 3D model does not
// have are refused unless left at their defaults, the 2D solver's own knobs are ignored (listed in
// docs/three-d.md).
#include <cstdint>
#include <span>

#include "jellysim/config/config.hpp"
#include "jellysim/swim3d/swimmer_3d.hpp"

namespace jellysim::scene {

struct Swim3dSettings {
  swim3d::Swim3dSpec spec;
  double duration_s = 0.0;  ///< as asked (`duration`, --duration)
  /// Frames after the one at t = 0: duration · frequency · frames_per_cycle rounded to the nearest
  /// whole number, at least 1 (the run ends on the frame nearest the duration, as the 2D tank's).
  std::int64_t frames = 0;
  bool vtk = false;                     ///< output.vtk: the flow of every frame
  double estimated_memory_bytes = 0.0;  ///< the water's (fluid3d::estimated_memory_bytes_3d) on the solved grid
  /// The last frame's time, frames / (frequency · frames_per_cycle).
  double end_time_s() const;
};

/// Whether the configuration is a 3D scene (tank.geometry = "3d").
bool is_3d_scene(const config::Config& c);
/// Reads and validates a 3D jellyfish scene: InputError naming the field and the allowed values
/// (also when the water's estimated memory exceeds the budget, core/memory.hpp).
Swim3dSettings read_swim3d_settings(const config::Config& c);

/// The fields only the 3D scene reads (refused in a 2D scene unless left at their defaults).
std::span<const char* const> fields_of_3d();

/// The 3D scene `c` as the axisymmetric solver's scene (issue 40 part 4's check, `jellysim experiment
/// 3d-vs-axisymmetric`): the same bell, stroke, water and frames; the tank's x–y section as the
/// axisymmetric tank (its width the 3D tank's, so its radius the 3D tank's half width; the same
/// cells along x and y), the aperture on the axis at the same height; the 3D-only fields dropped;
/// the axisymmetric solver's own numerics (tank.solver, convection, advection, symmetry and the
/// coupling's kernel, time step and threads) those of the built-in scene, `builtin`.
config::Config axisymmetric_counterpart(const config::Config& c, const config::Config& builtin);

}  // namespace jellysim::scene
