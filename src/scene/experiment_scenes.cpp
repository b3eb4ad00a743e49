#include "jellysim/scene/experiment_scenes.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/ode/integrator.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/render_settings.hpp"

namespace jellysim::scene {
namespace {

using config::Range;
using namespace param;

Parameter scene_kind(const std::string& name) {
  return {"scene", Type::text, "\"" + name + "\"", "", {}, {}, 0, "the scene kind"};
}

const char* const kCoarsestSteps = "study.coarsest_steps.";

/// Each integrator's coarsest run, in the registry's order; chosen so that every run is in the
/// asymptotic range and well above round-off.
std::vector<Parameter> coarsest_steps() {
  const std::vector<std::pair<std::string, std::string>> steps{
      {"forward-euler", "4000"}, {"predictor-corrector", "4000"}, {"leapfrog", "200"}, {"rk2", "200"},
      {"rk4", "100"},            {"dopri5", "80"},                {"backward-euler", "4000"}};
  std::vector<Parameter> p;
  for (const auto& [name, value] : steps)
    p.push_back(integer(kCoarsestSteps + name, value, 1, 10000000, "steps over end_time of the coarsest " + name + " run"));
  return p;
}

ParameterTable make_integrator_order() {
  std::vector<Parameter> p{
      scene_kind("integrator-order"),
      number("problem.point_mass", "1.0", "kg", Range::positive(), "m of each point"),
      number("problem.stiffness", "50.0", "N/m", Range::positive(), "κ_l; ω = sqrt(2 κ_l / m) = 10 rad/s"),
      number("problem.rest_length", "1.0", "m", Range::positive(), "l_r"),
      number("problem.amplitude", "0.1", "m", Range::non_negative(), "A, initial stretch"),
      number("problem.end_time", "2.0", "s", Range::positive(), "time at which the error is measured"),
      integer("study.refinements", "4", 1, 12, "step halvings after the coarsest run"),
  };
  for (Parameter& s : coarsest_steps()) p.push_back(std::move(s));
  return ParameterTable(
      "integrator-order",
      "# Measured global order of convergence of every integrator (thesis §2.4).\n"
      "# Problem: two point masses joined by one linear spring, free in space, started stretched along x.\n"
      "# The spring length then follows l(t) = l_r + A cos(ω t) with ω = sqrt(2 κ_l / m) exactly.\n"
      "# [study.coarsest_steps]: steps over end_time of each integrator's coarsest run, chosen so that every\n"
      "# run is in the asymptotic range (error ∝ dt^p) and well above round-off. An integrator left out of\n"
      "# the table (src/scene/experiment_scenes.cpp) is left out of the study.\n"
      "# Generated from the parameter table (src/scene/experiment_scenes.cpp): jellysim scenes integrator-order\n",
      std::move(p));
}

/// A parameter of another table with this definition's default and why it differs.
Parameter with_default(Parameter p, std::string value, std::string description) {
  p.value = std::move(value);
  p.description = std::move(description);
  return p;
}

ParameterTable make_stages() {
  const ParameterTable& render = render_parameters();
  std::vector<Parameter> p{
      scene_kind("stages"),
      choice("bell.source", "simulation", {"simulation", "synthetic"},
             "simulation: one cycle of the built-in jellyfish (rest and most contracted frames); synthetic: the "
             "analytic bell below"),
      number("bell.diameter", "0.04", "m", Range::positive(), "aperture diameter when expanded (Fig. 8.21: 4 cm)"),
      number("bell.height", "0.028", "m", Range::positive(), "bell height when expanded (Fig. 8.21: 2.8 cm)"),
      number("bell.thickness", "0.0015", "m", Range::positive(), "ϑ (§7.2: 5.4 % of the height)"),
      number("bell.contracted", "0.9", "", Range::closed(0.0, 1.0), "contraction of the contracted column"),
      integer("bell.umbrella_points", "21", 5, 10001, "umbrella points of the synthetic bell (odd)"),
      integer("bell.tentacle_points", "8", 2, 10000, "per tentacle"),
      number("bell.tentacle_length", "0.014", "m", Range::positive(), "Fig. 8.21: 1.4 cm"),
      integer("output.panel_width", "360", 64, 2048, "pixels per panel"),
      integer("output.panel_height", "300", 64, 2048, "pixels per panel"),
      with_default(render.at("render.obj"), "true", "meshes/frame_0000.obj …"),
      with_default(render.at("render.ply"), "true", "meshes/frame_0000.ply …"),
      with_default(render.at("render.disc_points"), "160",
                   "points around each disc: the structural ridges (18 a ring) need ≥ 144 to be drawn"),
  };
  return ParameterTable(
      "stages",
      "# Thesis Figure 8.19: each stage from the 2D slice to the noisy 3D umbrella (2D physics model,\n"
      "# 2D rendering model, extrapolated to 3D, structural, Perlin and compression noise, all noises),\n"
      "# for the expanded and the contracted bell, as one picture (stages.png) plus summary.json.\n"
      "# The [render] section is the rendering pipeline's configuration: its fields and defaults come from\n"
      "# the render parameter table (`jellysim scenes stages` prints them all; docs/parameters.md); this\n"
      "# file lists what the figure changes.\n"
      "# Generated from the parameter table (src/scene/experiment_scenes.cpp); when this file is stale,\n"
      "# the test ExperimentScenes.StagesDefinitionIsItsTable writes the current text.\n",
      std::move(p));
}

/// A rule: the default is each study's (value left empty).
Parameter rule(std::string key, Type type, std::string unit, Range range, std::string description,
               std::vector<std::string> choices = {}) {
  return {std::move(key), type, "", std::move(unit), range, std::move(choices), 0, std::move(description)};
}

ParameterTable make_jellyfish_study_rules() {
  const Range positive = Range::positive(), non_negative = Range::non_negative();
  std::vector<Parameter> p{
      rule("figure.panels", Type::integer, "", Range::closed(1, 24),
           "instability studies: pictures in the figure (the failing state is always included)"),
      rule("figure.expected", Type::choice, "", {}, "instability studies: the instability the figure shows",
           {"structural", "numerical"}),
      rule("sweep.frequencies", Type::numbers, "Hz", jellyfish_scene().at("jellyfish.frequency").range,
           "sweeps: the contraction frequencies run"),
      rule("sweep.placements", Type::integer, "", Range::closed(1, 64),
           "sweeps: runs per frequency, the bell shifted along its axis by k/placements of a cell (the coarse "
           "tank's distance is chaotic: one run is one sample, docs/jellyfish.md)"),
      rule("sweep.threads", Type::integer, "", Range::closed(0, 64), "sweeps: worker threads; 0: one per core"),
      rule("fluidless.drag", Type::number, "kg/s", non_negative,
           "κ_d per marker (per metre of depth), eq. 2.17 (jellyfish.elastic_model = thesis)"),
      rule("fluidless.drag_per_length", Type::number, "kg/(s·m²)", non_negative,
           "κ_d per metre of bell and tentacle (jellyfish.elastic_model = continuum)"),
      rule("fluidless.pressure_factor", Type::number, "Pa·s/m²", non_negative, "α of the cavity pressure p = −α dA/dt"),
      rule("fluidless.point_mass", Type::number, "kg", positive,
           "mass per marker (per metre of depth; thesis model: the continuum's is jellyfish.line_density)"),
      rule("fluidless.integrator", Type::choice, "", {}, "time integrator (docs/integrators.md)", ode::integrator_names()),
      rule("fluidless.dt", Type::number, "s", positive, "step; the first step when adaptive"),
      rule("fluidless.adaptive", Type::boolean, "", {}, "step-size control by the error estimate"),
      rule("fluidless.atol", Type::number, "", positive, "absolute error tolerance of adaptive steps"),
      rule("fluidless.rtol", Type::number, "", non_negative, "relative error tolerance of adaptive steps"),
      rule("fluidless.compare_with_fluid", Type::boolean, "", {}, "also run the fluid simulation and report the speed-up"),
      rule("steering.target_offset", Type::vec2, "m", {},
           "from the start, x > 0: the left target is at (−x, y), the right one at (x, y)"),
      rule("steering.settle_cycles", Type::number, "", non_negative, "headings are averaged after this many cycles"),
      rule("study.time_steps", Type::numbers, "s", positive, "coupling-stability: the Δt caps tried"),
      rule("resonance.hold", Type::number, "s", Range::closed(0.0, 60.0),
           "resonance: the contraction is held this long at its peak before the release"),
      rule("resonance.ring_down", Type::number, "s", Range{0.0, 60.0, true, false},
           "resonance: the bell's volume is recorded this long after the release"),
      rule("resonance.multiples", Type::numbers, "", Range{0.0, 20.0, true, false},
           "resonance: the sweep's driving frequencies as multiples of the natural frequency"),
      rule("resonance.cycles", Type::number, "", Range::closed(2.0, 1000.0),
           "resonance: cycles each sweep run swims (speed and cost over the cycles after the first)"),
      rule("resonance.threads", Type::integer, "", Range::closed(0, 64), "resonance: sweep runs at a time; 0: one per core"),
  };
  return ParameterTable("jellyfish-studies", "", std::move(p));
}

/// hoover-miller's own fields (the tank, coupling and [[objects]] are the jellyfish scene's).
ParameterTable make_hoover_miller_rules() {
  std::vector<Parameter> p{
      rule("re", Type::number, "", Range{0.0, 1e5, true, false},
           "Reynolds number ρ D U / μ with D = 1 m, U = 1 m/s (`--re`); sets tank.viscosity = 1/re m²/s"),
      rule("grid", Type::integer, "", Range::closed(32, 1024),
           "IB2d's N, a multiple of 8 (`--grid`); sets tank.cells = [0.375 N, 1.25 N] and the bell's resolution"),
      rule("cycles", Type::integer, "", Range::closed(1, 100), "strokes of 1 s simulated (`--cycles`); sets duration"),
      rule("muscles", Type::choice, "", {},
           "ib2d: IB2d's muscle springs, 1e5 each at any N; per-length: each stands for its ds of bell, 1e5 · 256/N "
           "(docs/ib2d.md)",
           {"ib2d", "per-length"}),
  };
  return ParameterTable("hoover-miller", "", std::move(p));
}

/// axisymmetric-vs-planar's own field.
ParameterTable make_axisymmetric_vs_planar_rules() {
  std::vector<Parameter> p{
      rule("cycles", Type::integer, "", Range::closed(2, 100),
           "contraction cycles of each run; sets duration = cycles / jellyfish.frequency"),
  };
  return ParameterTable("axisymmetric-vs-planar", "", std::move(p));
}

}  // namespace

const ParameterTable& integrator_order_scene() {
  static const ParameterTable table = make_integrator_order();
  return table;
}

IntegratorOrderScene read_integrator_order(const config::Config& c) {
  const Reader r(c, integrator_order_scene());
  IntegratorOrderScene s;
  s.point_mass = r.number("problem.point_mass");
  s.stiffness = r.number("problem.stiffness");
  s.rest_length = r.number("problem.rest_length");
  s.amplitude = r.number("problem.amplitude");
  s.end_time = r.number("problem.end_time");
  s.refinements = static_cast<int>(r.integer("study.refinements"));
  for (const std::string& name : ode::integrator_names()) {
    const std::string key = kCoarsestSteps + name;
    if (c.has(key)) s.coarsest_steps.emplace_back(name, static_cast<int>(r.integer(key)));
  }
  return s;
}

const ParameterTable& stages_scene() {
  static const ParameterTable table = make_stages();
  return table;
}

StagesScene read_stages_scene(const config::Config& c) {
  const Reader r(c, stages_scene());
  StagesScene s;
  s.bell.diameter_m = r.number("bell.diameter");
  s.bell.height_m = r.number("bell.height");
  s.bell.thickness_m = r.number("bell.thickness");
  s.contracted = r.number("bell.contracted");
  s.simulated = r.choice("bell.source") == "simulation";
  s.bell.umbrella_points = static_cast<int>(r.integer("bell.umbrella_points"));
  if (s.bell.umbrella_points % 2 == 0)
    throw InputError("field 'bell.umbrella_points' = " + std::to_string(s.bell.umbrella_points) + " must be odd");
  s.bell.tentacle_points = static_cast<int>(r.integer("bell.tentacle_points"));
  s.bell.tentacle_length_m = r.number("bell.tentacle_length");
  s.panel_width = static_cast<int>(r.integer("output.panel_width"));
  s.panel_height = static_cast<int>(r.integer("output.panel_height"));
  s.pipeline = read_render_settings(c);
  s.bell.max_contraction = s.pipeline.geometry.noise.max_contraction;
  return s;
}

const ParameterTable& jellyfish_study_rules() {
  static const ParameterTable table = make_jellyfish_study_rules();
  return table;
}

InstabilityFigure read_instability_figure(const config::Config& c) {
  const Reader r(c, jellyfish_study_rules());
  InstabilityFigure f;
  f.panels = static_cast<int>(r.integer("figure.panels"));
  f.zoom_diameters = read_picture_zoom(c);
  f.expected = r.choice("figure.expected");
  return f;
}

SweepScene read_sweep(const config::Config& c) {
  const Reader r(c, jellyfish_study_rules());
  SweepScene s;
  s.frequencies = r.numbers("sweep.frequencies");
  s.placements = static_cast<int>(r.integer("sweep.placements"));
  s.threads = static_cast<int>(r.integer("sweep.threads"));
  return s;
}

FluidlessScene read_fluidless(const config::Config& c) {
  const Reader r(c, jellyfish_study_rules());
  FluidlessScene s;
  s.model.drag_kg_per_s = r.number("fluidless.drag");
  s.model.drag_kg_per_s_m2 = r.number("fluidless.drag_per_length");
  s.model.pressure_factor = r.number("fluidless.pressure_factor");
  s.point_mass = r.number("fluidless.point_mass");
  s.time.integrator = r.choice("fluidless.integrator");
  s.time.dt = r.number("fluidless.dt");
  s.time.adaptive = r.boolean("fluidless.adaptive");
  s.time.tolerances.atol = r.number("fluidless.atol");
  s.time.tolerances.rtol = r.number("fluidless.rtol");
  s.compare_with_fluid = r.boolean("fluidless.compare_with_fluid");
  return s;
}

SteeringScene read_steering(const config::Config& c) {
  const Reader r(c, jellyfish_study_rules());
  SteeringScene s;
  s.target_offset = r.vec2("steering.target_offset");
  if (!(s.target_offset.x > 0))
    throw InputError("field 'steering.target_offset' needs x > 0 (the target to the left is at −x)");
  s.settle_cycles = r.number("steering.settle_cycles");
  return s;
}

ResonanceScene read_resonance(const config::Config& c) {
  const Reader r(c, jellyfish_study_rules());
  ResonanceScene s;
  s.hold_s = r.number("resonance.hold");
  s.ring_down_s = r.number("resonance.ring_down");
  s.multiples = r.numbers("resonance.multiples");
  if (s.multiples.empty()) throw InputError("field 'resonance.multiples' is empty: give at least one multiple in (0, 20]");
  s.cycles = r.number("resonance.cycles");
  s.threads = static_cast<int>(r.integer("resonance.threads"));
  return s;
}

std::vector<double> read_coupling_stability_steps(const config::Config& c) {
  return Reader(c, jellyfish_study_rules()).numbers("study.time_steps");
}

const ParameterTable& hoover_miller_rules() {
  static const ParameterTable table = make_hoover_miller_rules();
  return table;
}

HooverMillerFields read_hoover_miller_fields(const config::Config& c) {
  const Reader r(c, hoover_miller_rules());
  HooverMillerFields f;
  f.re = r.number("re");
  f.grid = static_cast<int>(r.integer("grid"));
  if (f.grid % 8 != 0)
    throw InputError("field 'grid' = " + std::to_string(f.grid) + " must be a multiple of 8 in [32, 1024]");
  f.cycles = static_cast<int>(r.integer("cycles"));
  f.muscles = r.choice("muscles");
  return f;
}

const ParameterTable& axisymmetric_vs_planar_rules() {
  static const ParameterTable table = make_axisymmetric_vs_planar_rules();
  return table;
}

int read_axisymmetric_vs_planar_cycles(const config::Config& c) {
  return static_cast<int>(Reader(c, axisymmetric_vs_planar_rules()).integer("cycles"));
}

}  // namespace jellysim::scene
