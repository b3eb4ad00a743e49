#pragma once
// Shared pieces of the particle-fluid experiments (thesis §8.1.1-8.1.2): reading their TOML
// sections with range checks, building the Figure 8.1 bar, the fluid and the larva, recording
// frames, and writing frames.csv and frame strips.
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/sph/bodies.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/scene.hpp"

#include <string>
#include <vector>

namespace jellysim::experiments::sph_common {

/// [time] plus `duration`: integrator, dt, adaptive, atol, rtol, error_control, frame_interval,
/// thin_boundary_limit; [output] max_speed.
sph::RunSettings read_run_settings(const io::Config& c);
/// [bar] as in swinging-bar (length, width, segments, point_mass, stiffness, pivot, gravity).
elastic::BarSpec read_bar(const io::Config& c);
/// [collision] separation, trap_radius; run.threads (0: one per core).
void read_collision(const io::Config& c, sph::Scene& scene);
/// [fluid] smoothing_radius, rest_density, gas_constant, viscosity.
sph::SphParameters read_fluid_parameters(const io::Config& c);
/// [larva] section.
sph::LarvaSpec read_larva(const io::Config& c);

/// Builds the mosquito-larva scene ([box], [fluid], [larva], [collision], run.threads); also
/// reports the mass search. Throws InputError for invalid input.
struct LarvaScene {
  sph::Scene scene;
  sph::MassSearch mass;
};
LarvaScene build_larva_scene(const io::Config& c, double gas_constant);

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

/// Throws InputError when the run settings cannot work (e.g. dt > duration).
void check_time(const sph::RunSettings& s);

/// An Experiment from its name, description, definition file and prepare function.
Experiment make_experiment(std::string name, std::string description, std::string definition_path,
                           std::function<std::function<Outcome(const io::OutputDir&)>(const Context&)> prepare);

}  // namespace jellysim::experiments::sph_common
