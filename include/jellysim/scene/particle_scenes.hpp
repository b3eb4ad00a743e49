#pragma once
// The elastic-bar and particle-fluid scenes (thesis §8.1.1–8.1.2: swinging-bar, bar-hits-wall,
// bar-hits-particle, sph-stream, mosquito-larva, integrator-cost): the rules of the sections they
// share and of each one's own fields, and the readers that build their settings. The rules (type, unit, allowed range, meaning)
// are one table; the default values are each scene's own, in its definition file (`jellysim scenes
// NAME`), because the scenes differ (the larva's step is not the bar's).
#include <string>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/elastic/bar.hpp"
#include "jellysim/scene/parameters.hpp"
#include "jellysim/sim/time_stepping.hpp"
#include "jellysim/sph/bodies.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/scene.hpp"

namespace jellysim::scene {

/// duration, [time], [output], [bar], [collision], [run], [box], [fluid], [larva], and the fields of
/// one experiment alone: [wall], [particle], [emitter], [study] (integrator-cost).
const ParameterTable& particle_scene_rules();

/// duration and [time] integrator, dt, adaptive, atol, rtol, frame_interval; dt <= duration.
sim::TimeSettings read_time_settings(const config::Config& c);
/// read_time_settings plus [time] error_control, thin_boundary_limit and [output] max_speed.
sph::RunSettings read_particle_run_settings(const config::Config& c);
/// [bar] length, width, segments, point_mass, stiffness, pivot, gravity (the Figure 8.1 bar).
elastic::BarSpec read_bar(const config::Config& c);
/// [collision] separation, trap_radius; run.threads (0: one per core).
void read_collision(const config::Config& c, sph::Scene& scene);
/// [fluid] smoothing_radius, rest_density, gas_constant, viscosity.
sph::SphParameters read_fluid_parameters(const config::Config& c);
/// [larva] (without gravity, which build_larva_scene applies).
sph::LarvaSpec read_larva(const config::Config& c);

/// [box] min and max; max above and right of min.
struct Box {
  Vec2 min, max;
};
Box read_box(const config::Config& c);

/// The frame strip of [output]: strip_frames, and strip_window, strip_start and velocity_scale
/// where the scene has them (0 otherwise).
struct StripOutput {
  int frames = 12;
  double window_s = 0.0;          ///< bar collisions: time around the first contact
  double start_s = 0.0;           ///< mosquito larva: first frame shown
  double velocity_scale_s = 0.0;  ///< mosquito larva: drawn velocity vectors' length per m/s
};
StripOutput read_strip_output(const config::Config& c);

/// bar-hits-wall: wall.gap.
double read_wall_gap(const config::Config& c);

/// bar-hits-particle: the point mass of [particle], its position made absolute (from bar.pivot).
struct PointParticle {
  Vec2 position, velocity, gravity;
  double mass_kg = 1.0;
};
PointParticle read_point_particle(const config::Config& c);

/// sph-stream: [emitter], placed from the box's top-left corner; it must lie inside the box.
sph::Emitter read_emitter(const config::Config& c, const Box& box);

/// integrator-cost: [study] gas_constants, integrators, error_controls.
struct CostStudy {
  std::vector<double> gas_constants;
  std::vector<std::string> integrators, error_controls;
};
CostStudy read_cost_study(const config::Config& c);

/// The mosquito-larva scene ([box], [fluid], [larva], [collision], run.threads) with the fluid's
/// gas constant `gas_constant` (the first form: fluid.gas_constant); also reports the
/// particle-mass search. Throws InputError.
struct LarvaScene {
  sph::Scene scene;
  sph::MassSearch mass;
};
LarvaScene build_larva_scene(const config::Config& c);
LarvaScene build_larva_scene(const config::Config& c, double gas_constant);

}  // namespace jellysim::scene
