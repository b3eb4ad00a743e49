#pragma once
// Shared pieces of the jellyfish commands (`jellysim simulate` and the chapter 8 jellyfish
// experiments): the output options, running a swim scene while writing per-frame
// pictures and VTK files, and writing metrics, plots and summary figures.
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>

#include "jellysim/config/config.hpp"
#include "jellysim/io/checkpoint.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/jellyfish/swim_record.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/render/field_picture.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace jellysim::experiments {

using scene::read_swim_settings;  // the scene layer reads the scene (scene/jellyfish_scene.hpp)

struct SwimOutputOptions {
  bool pictures = false;
  int picture_every = 1;
  render::FieldQuantity quantity = render::FieldQuantity::vorticity;
  double zoom_diameters = 6.0;  ///< picture width in bell diameters; 0: whole tank
  bool vtk = false;
  bool record_tracers = false;  ///< keep every frame's tracer positions (the animation's marine snow)
  /// When given, asked before every step: true ends the run early with what is recorded (a loop).
  std::function<bool(const jellyfish::SwimRecord&)> stop_when;
};
SwimOutputOptions read_output_options(const config::Config& c);

/// A run's record (jellyfish/swim_record.hpp: frames, forces, metrics) and its step statistics.
struct SwimRecording : jellyfish::SwimRecord {
  jellyfish::SwimRunStats stats;
};

/// Checkpoints of a swim (issue 23): io/checkpoint.hpp's file, written at the first frame at or
/// after every `how.every_s` simulated seconds, holding the simulation's state and the recording
/// so far; and the checkpoint a resumed run continues from.
struct Checkpointing {
  io::Checkpoint how;  ///< the run's configuration as given (each checkpoint carries it); .state unused
  /// Resuming: `how` is the checkpoint io::read_checkpoint read, whose state run_swim reads once it
  /// knows how large this configuration's state can be, after checking that the files the scene
  /// read then (how.inputs) are the ones it reads now.
  bool resume = false;
  /// A whole simulation leaves a checkpoint of its end (`jellysim run`: the render stage follows,
  /// and a run stopped there resumes from it); the caller removes it once its outputs are whole.
  bool keep_when_whole = false;
};

/// When the next checkpoint is due: the first multiple of `every` (s) after t (s).
double next_checkpoint_time(double t, double every);

/// Runs the swim, writing pictures/VTK per frame into `out` when given (files go to frames/). With
/// `checkpoints` (and `out`), writes checkpoints, or continues from one: the outputs are those of
/// the uninterrupted run, byte for byte. A completed run removes its checkpoint (or, with
/// keep_when_whole, replaces it with one of its end).
SwimRecording run_swim(const jellyfish::SwimSettings& settings, const SwimOutputOptions& options,
                       const io::OutputDir* out, const sim::ProgressCallback& progress,
                       const Checkpointing* checkpoints = nullptr);

/// metrics.csv: t, position, velocity, acceleration, volume, aperture_area, volume_ratio,
/// aperture_ratio, thrust, lateral, daniel_velocity, daniel_position.
void write_metrics_csv(const io::OutputDir& out, const std::vector<jellyfish::MetricsRow>& rows,
                       const std::string& name = "metrics.csv");
/// For busier tanks: metrics_jellyfish_N.csv for the second jellyfish on (same columns as
/// metrics.csv), obstacles.csv (t, obstacle, force_x, force_y: the fluid's force, N/m) and
/// structures.csv (t, structure, centroid_x, centroid_y: IB2d structures without their targets, m).
void write_scene_extras(const io::OutputDir& out, const SwimRecording& rec);
/// slices.csv: frame, t, part (umbrella or tentacle_k), index, x, y — the recorded 2D slices.
void write_slices_csv(const io::OutputDir& out, const std::vector<jellyfish::SliceFrame>& frames,
                      const std::string& name = "slices.csv");
/// kinematics.png (position, velocity, acceleration; Figs 8.15–8.17, with Daniel's model) and
/// morphology.png (volume and aperture ratios; Fig. 8.18).
void write_swim_plots(const io::OutputDir& out, const std::vector<jellyfish::MetricsRow>& rows,
                      const std::string& title);
/// Key figures for summary.json: units, bell_height, cycles, distance_travelled, lateral_drift,
/// volume_frequency, simulated_seconds, wall_seconds, steps and more.
nlohmann::ordered_json swim_figures(const jellyfish::SwimSettings& settings, const SwimRecording& rec);

/// The 2D picture of one state (springs, muscles, tracers over speed or vorticity).
render::FieldPicture swim_picture(const jellyfish::SwimSimulation& sim, double zoom_diameters);
/// Panels side by side on one vorticity scale (±10/s, no arrows) into `name` (nothing without panels).
void write_vorticity_panels(const io::OutputDir& out, const std::string& name,
                            const std::vector<render::FieldPicture>& panels);

}  // namespace jellysim::experiments
