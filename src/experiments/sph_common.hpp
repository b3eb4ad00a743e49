#pragma once
// Shared pieces of the particle-fluid experiments (thesis §8.1.1-8.1.2): recording frames and
// writing frames.csv and frame strips (the scene layer reads their sections and builds the larva).
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/sph/bodies.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/scene.hpp"

#include <string>
#include <vector>

namespace jellysim::experiments::sph_common {

// The sections' rules and readers are the scene layer's (scene/particle_scenes.hpp).
using scene::build_larva_scene;
using scene::LarvaScene;
using scene::read_bar;
using scene::read_collision;
using scene::read_fluid_parameters;
using scene::read_larva;

/// One recorded frame.
struct Frame {
  double t = 0.0;
  std::vector<Vec2> particles, particle_velocities, body, body_velocities;
};
Frame snapshot(double t, const sph::Scene& scene);

/// frames.csv: frame, t, object (0 particle, 1 body point), index, x, y, vx, vy.
void write_frames_csv(const io::OutputDir& out, const std::vector<Frame>& frames);

struct DrawOptions {
  std::vector<std::array<Vec2, 2>> decor;  ///< walls etc., drawn in every panel
  double velocity_scale_s = 0.0;           ///< > 0: body-point velocity vectors of this length per m/s
};
/// A strip of `count` frames evenly spread over [t0, t1] (all frames when fewer), 4 per row.
void write_strip(const io::OutputDir& out, const std::string& name, const std::string& title,
                 const sph::Scene& scene, const std::vector<Frame>& frames, double t0, double t1, int count,
                 const DrawOptions& options);

/// Segments of the four sides of a box.
std::vector<std::array<Vec2, 2>> box_segments(Vec2 lo, Vec2 hi);

/// Processor time of this process so far (s, all threads; std::clock).
double cpu_seconds();

/// Common key figures of a run; cpu_seconds = processor time of the run (all threads).
nlohmann::ordered_json run_figures(const sph::RunResult& r, double wall_seconds, double cpu_seconds);

/// An Experiment from its name, description, definition file and prepare function; every SPH
/// experiment takes --threads (run.threads).
Experiment make_experiment(std::string name, std::string description, std::string definition_path,
                           std::function<std::function<Outcome(const io::OutputDir&)>(const Context&)> prepare);

/// The base scene of the bar scenes (swinging-bar, bar-hits-wall, bar-hits-particle, sph-stream):
/// the one place for the Figure 8.1 bar's [bar] defaults, which elastic::BarSpec's are (tested).
inline constexpr const char* kBarBasePath = "scenes/bar.toml";
/// make_experiment for a scene on the Figure 8.1 bar: its definition extends kBarBasePath.
Experiment make_bar_experiment(std::string name, std::string description, std::string definition_path,
                               std::function<std::function<Outcome(const io::OutputDir&)>(const Context&)> prepare);

}  // namespace jellysim::experiments::sph_common
