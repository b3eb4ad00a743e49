#pragma once
// The jellyfish scene in 3D water under `jellysim simulate` (tank.geometry = "3d"; issue 40 part 4,
// docs/three-d.md "The 3D scene"): the "jellyfish" experiment dispatches here.
#include <functional>

#include "jellysim/experiments/experiment.hpp"

namespace jellysim::experiments {

/// Reads and validates the 3D scene (InputError before anything is written); the run writes
/// metrics.csv, summary.json and, with output.vtk, the flow of every frame.
std::function<Outcome(const io::OutputDir&)> prepare_jellyfish_3d(const Context& ctx);
/// `jellysim run` on a 3D scene: the same run, then the simulated surface rendered and exported
/// (render::write_surface_animation_outputs: PNG frames, MP4, .glb, meshes, point caches, viewer).
std::function<Outcome(const io::OutputDir&)> prepare_animation_3d(const Context& ctx);

}  // namespace jellysim::experiments
