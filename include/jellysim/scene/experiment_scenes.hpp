#pragma once
// The experiments' own fields as parameter tables: integrator-order and stages, whose whole
// definitions are generated from their tables (`jellysim scenes NAME`), and the rules (type, unit,
// allowed range, meaning) of the fields the jellyfish studies add to scenes/jellyfish.toml, whose
// defaults stay in each study's definition file (the two instability figures, the two sweeps and
// the fluid-free model differ).
#include <string>
#include <utility>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/jellyfish/fluidless.hpp"
#include "jellysim/math/vec2.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/scene/parameters.hpp"
#include "jellysim/sim/time_stepping.hpp"

namespace jellysim::scene {

// ---- integrator-order (§2.4) ------------------------------------------------------------------

const ParameterTable& integrator_order_scene();

/// Two point masses joined by one spring, and the step counts of each integrator's coarsest run.
struct IntegratorOrderScene {
  double point_mass = 1.0, stiffness = 50.0, rest_length = 1.0, amplitude = 0.1, end_time = 2.0;
  int refinements = 4;                                        ///< step halvings after the coarsest run
  std::vector<std::pair<std::string, int>> coarsest_steps;    ///< (integrator, steps), registry order
};
IntegratorOrderScene read_integrator_order(const config::Config& c);

// ---- stages (Figure 8.19) ---------------------------------------------------------------------

const ParameterTable& stages_scene();

struct StagesScene {
  geometry::SyntheticBell bell;   ///< the synthetic bell (max_contraction from [render.noise])
  double contracted = 0.9;        ///< contraction of the synthetic bell's contracted column
  bool simulated = true;          ///< bell.source = "simulation"
  int panel_width = 360, panel_height = 300;
  render::PipelineSettings pipeline;  ///< the [render] section
};
/// [bell], [output] and [render]; throws InputError naming the field.
StagesScene read_stages_scene(const config::Config& c);

// ---- the jellyfish studies' own fields (rules; defaults are each study's) ----------------------

/// [figure], [sweep], [fluidless], [steering] and [study] of the studies extending the jellyfish scene.
const ParameterTable& jellyfish_study_rules();

/// structural- and numerical-instability: the figure's panels and the instability it shows.
struct InstabilityFigure {
  int panels = 6;
  double zoom_diameters = 6.0;  ///< output.picture_zoom of the jellyfish scene
  std::string expected;         ///< "structural" or "numerical"
};
InstabilityFigure read_instability_figure(const config::Config& c);

/// frequency-sweep and sweep.
struct SweepScene {
  std::vector<double> frequencies;
  int placements = 1;  ///< runs per frequency
  int threads = 0;     ///< 0: one per core
};
SweepScene read_sweep(const config::Config& c);

/// fluidless: the model's settings, its point mass and its time stepping (duration and frame
/// interval are the jellyfish scene's, set by the caller).
struct FluidlessScene {
  jellyfish::FluidlessSettings model;
  double point_mass = 1e-3;
  sim::TimeSettings time;
  bool compare_with_fluid = true;
};
FluidlessScene read_fluidless(const config::Config& c);

/// steering: where the targets lie and when the headings are averaged.
struct SteeringScene {
  Vec2 target_offset;  ///< from the start; x > 0 (the left target is at (−x, y))
  double settle_cycles = 4.0;
};
SteeringScene read_steering(const config::Config& c);

/// resonance (docs/control.md): the release test and the frequency sweep around its result.
struct ResonanceScene {
  double hold_s = 1.0;        ///< the contraction held at its peak before the release
  double ring_down_s = 2.0;   ///< volume recorded after the release
  std::vector<double> multiples;  ///< sweep frequencies / natural frequency
  double cycles = 4.0;        ///< cycles per sweep run
  int threads = 0;
};
ResonanceScene read_resonance(const config::Config& c);

/// coupling-stability: the Δt caps tried.
std::vector<double> read_coupling_stability_steps(const config::Config& c);

// ---- experiments extending the jellyfish scene with top-level fields of their own -------------

/// hoover-miller (docs/ib2d.md): re, grid, cycles, muscles (rules; defaults in its definition).
const ParameterTable& hoover_miller_rules();
struct HooverMillerFields {
  double re = 150.0;
  int grid = 256;                ///< IB2d's N, a multiple of 8
  int cycles = 3;
  std::string muscles = "ib2d";  ///< "ib2d" or "per-length"
};
HooverMillerFields read_hoover_miller_fields(const config::Config& c);

/// axisymmetric-vs-planar: cycles (rules; the default in its definition).
const ParameterTable& axisymmetric_vs_planar_rules();
int read_axisymmetric_vs_planar_cycles(const config::Config& c);

}  // namespace jellysim::scene
