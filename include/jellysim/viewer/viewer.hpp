#pragma once
// `jellysim view`: the real-time viewer. A GLFW window with the 2D slice in its fluid (speed or
// vorticity, tracers, springs, obstacle outlines) beside the 3D jellyfish (one mesh per jellyfish
// from the geometry pipeline), Dear ImGui controls, mouse interaction (drag a jellyfish or an
// obstacle, stir the water, set a steering target) and PNG/MP4 recording. It only calls the
// simulation's public API (jellyfish::SwimSimulation): no physics here.
#include <filesystem>
#include <optional>
#include <string>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/viewer/field_image.hpp"

namespace jellysim::viewer {

struct ViewerOptions {
  int width_px = 960;   // software GL keeps real time at this size (docs/viewer.md)
  int height_px = 540;
  double target_fps = 30.0;        ///< frames are paced to this rate; 0: as fast as possible
  double speed = 1.0;              ///< simulated seconds per wall second wanted
  double min_fps = 10.0;           ///< the simulation may slow the frame rate down to this to keep up
  double render_scale = 0.6;       ///< resolution of the 3D panel relative to the window, (0, 1]
  long frames = 0;                 ///< quit after this many frames; 0: run until the window closes
  bool start_paused = false;
  FieldShown field = FieldShown::vorticity;
  std::string script_text;         ///< timed input events (viewer/input_script.hpp)
  std::string script_source;       ///< names the script in error messages
  std::filesystem::path screenshot;  ///< PNG of the last frame, written at exit
  std::filesystem::path record_dir;  ///< record every frame: frame_00000.png … and view.mp4
  bool record_png = true;
  bool record_mp4 = true;
  std::filesystem::path stats;       ///< JSON with fps, sim_rate, frames, steps and the state
  geometry::GeometrySettings geometry;  ///< the 3D pipeline (noise weights are live parameters)
  double obstacle_depth_m = 0.12;  ///< obstacles in the 3D panel: prisms this long (as render.obstacle_depth)
  std::string scene_name;          ///< shown in the title bar
  bool vsync = false;
  bool profile = false;            ///< glFinish after each stage so the stats' ms_per_frame attribute GPU time
};

/// Checks the options; throws InputError naming the option and its allowed range.
void validate(const ViewerOptions& options);

/// Geometry settings for interactive rates: fewer rings, discs points and tentacle strands than
/// the offline pipeline's defaults, with the same noise.
geometry::GeometrySettings interactive_geometry(const geometry::NoiseSettings& noise);

/// Opens the window and runs until it is closed, `q`/Escape is pressed or `frames` have been shown.
/// Returns 0, or 1 when the simulation failed (the failure is shown and written to the stats).
/// Throws InputError for bad options or script, RunError when no window or OpenGL 3.3 context can
/// be made (e.g. no display: run under `xvfb-run -a`).
int run_viewer(const jellyfish::SwimSettings& settings, const ViewerOptions& options);

}  // namespace jellysim::viewer
