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
/// and line).
jellyfish::SwimSettings read_swim_settings(const config::Config& c);
/// output.picture_zoom: 0 (the whole tank) or [kMinPictureZoom, 1000] bell diameters (a narrower
/// view has no width left to draw; throws InputError naming the field).
double read_picture_zoom(const config::Config& c);
inline constexpr double kMinPictureZoom = 0.01;

}  // namespace jellysim::scene
