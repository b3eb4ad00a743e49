#pragma once
// `jellysim view` on a 3D scene (tank.geometry = "3d"; issue 40 part 4, docs/viewer.md "The 3D
// scene"): the shell bell in 3D water stepped live (swim3d::Swimmer3d, one coupled step at a time),
// its simulated surface drawn as `jellysim run` draws it (geometry::SurfaceGeometryBuilder), beside
// the flow on the bell's vertical mid-plane. The 3D water is far below real time on a workstation:
// the viewer says so on screen, with the rate it reaches. No physics here.
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/viewer/viewer.hpp"

namespace jellysim::viewer {

/// Opens the window and runs until it is closed, `q`/Escape is pressed or `frames` have been shown.
/// Returns 0, or 1 when the simulation failed (shown and written to the stats). Of the options, the
/// script, the live parameters and mouse editing are the 2D viewer's only (InputError when a script
/// is given). Throws RunError when no window or OpenGL 3.3 context can be made.
int run_viewer_3d(const scene::Swim3dSettings& settings, const ViewerOptions& options);

}  // namespace jellysim::viewer
