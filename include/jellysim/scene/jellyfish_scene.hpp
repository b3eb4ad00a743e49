#pragma once
// The jellyfish scene (`jellysim simulate`, `run`, `view`, `sweep` and the jellyfish experiments):
// its parameter table, whose defaults are the built-in scene (scenes/jellyfish.toml is generated
// from it), and the reader that turns a configuration into the simulation's settings.
#include "jellysim/config/config.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/scene/parameters.hpp"

namespace jellysim::scene {

/// Every field of a jellyfish scene: top level, [tank], [jellyfish], [coupling], [stability], [output].
const ParameterTable& jellyfish_scene();

/// Reads duration, output.frame_interval, [tank], [jellyfish], [[objects]], [coupling] and
/// [stability]; throws InputError naming the field and what is allowed (a polygon file: its path
/// and line), also for a 3D scene (tank.geometry = "3d": scene/jellyfish_3d_scene.hpp reads it) and
/// for a 3D-only field set in a 2D scene.
jellyfish::SwimSettings read_swim_settings(const config::Config& c);
/// The [jellyfish] fields the 2D slice and the 3D shell share: the bell's shape, the tentacles'
/// length, the material (either elastic model) and the stroke; not its position, tilt, markers or
/// steering, which keep JellyfishSpec's defaults. Throws InputError naming the field.
jellyfish::JellyfishSpec read_jellyfish_body(const config::Config& c);

/// output.frame_interval, or output.fps (frame k at k / fps): one of the two (InputError when both
/// are given); sets s.frame_interval_s and s.frames_per_second from s.duration_s.
void read_frame_rate(const Reader& r, jellyfish::SwimSettings& s);

/// More recorded frames than a run can write or anyone view (a million at 30 fps is 9 hours).
inline constexpr double kMaxFrames = 1e6;
/// output.picture_zoom: 0 (the whole tank) or [kMinPictureZoom, 1000] bell diameters (a narrower
/// view has no width left to draw; throws InputError naming the field).
double read_picture_zoom(const config::Config& c);
inline constexpr double kMinPictureZoom = 0.01;

}  // namespace jellysim::scene
