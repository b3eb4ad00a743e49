#pragma once
// The jellyfish scene in 3D water under `jellysim simulate` (tank.geometry = "3d"; issue 40 part 4,
// docs/three-d.md "The 3D scene"): the "jellyfish" experiment dispatches here.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"

namespace jellysim::experiments {

/// What a run recorded: its frames (the first at t = 0), why it stopped early (empty: it did not)
/// and what it cost.
struct Recording3d {
  std::vector<swim3d::Frame3d> frames;
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< the bell's surface (its vertices first in each frame's points)
  std::vector<std::vector<int>> tentacles;              ///< each rod's points from its root
  std::size_t surface_vertices = 0;                     ///< the first points of each frame
  std::string failure;
  swim3d::Swim3dTimings timings;
  std::size_t markers = 0;
  double wall_seconds = 0.0;
};

/// Runs the scene's frames (the first at t = 0), writing the flow and the bell's surface of each into
/// `out` when the settings ask (output.vtk); progress after every frame. A failure or SIGINT ends it
/// early, named. With `checkpoints`, writes checkpoints or continues from one (issue 23's rules, as
/// run_swim's): the outputs are those of the uninterrupted run, byte for byte.
Recording3d run_3d(const scene::Swim3dSettings& settings, const io::OutputDir& out, const sim::ProgressCallback& progress,
                   const Checkpointing* checkpoints = nullptr);

/// Reads and validates the 3D scene (InputError before anything is written); the run writes
/// metrics.csv, summary.json and, with output.vtk, the flow of every frame.
std::function<Outcome(const io::OutputDir&)> prepare_jellyfish_3d(const Context& ctx);
/// `jellysim run` on a 3D scene: the same run, then the simulated surface rendered and exported
/// (render::write_surface_animation_outputs: PNG frames, MP4, .glb, meshes, point caches, viewer).
std::function<Outcome(const io::OutputDir&)> prepare_animation_3d(const Context& ctx);

}  // namespace jellysim::experiments
