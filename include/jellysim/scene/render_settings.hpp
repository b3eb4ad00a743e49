#pragma once
// The [render] and [render.noise] sections of scenes that render the 3D jellyfish (`jellysim run`,
// `experiment stages`): their parameter table and the reader of the rendering pipeline's settings.
#include "jellysim/config/config.hpp"
#include "jellysim/jellyfish/stroke_loop.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/scene/parameters.hpp"

namespace jellysim::scene {

/// render.* (image, mesh, camera, style, files) and render.noise.* (§7.3, Figure 8.19).
const ParameterTable& render_parameters();

/// The rendering pipeline's settings from the [render] section; throws InputError naming the field.
render::PipelineSettings read_render_settings(const config::Config& c);

/// render.loop*: the seamless loop (jellyfish/stroke_loop.hpp); throws InputError naming the field.
jellyfish::LoopSettings read_loop_settings(const config::Config& c);

}  // namespace jellysim::scene
