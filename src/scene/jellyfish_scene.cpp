#include "jellysim/scene/jellyfish_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "jellysim/core/errors.hpp"
#include "jellysim/core/memory.hpp"
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/scene/objects.hpp"

namespace jellysim::scene {

namespace {

using config::Range;
constexpr double kDegree = std::numbers::pi / 180.0;
const Range kPositive = Range::positive();
const Range kNonNegative = Range::non_negative();
// Upper bounds where a larger value is no longer the model (issue 23: 1e200 Pa ran into NaN).
const Range kModulus{0.0, 1e9, true, false};          ///< Pa: up to stiff plastics; mesoglea ~1e2–1e4
const Range kModulusOrZero{0.0, 1e9, false, false};
const Range kTankSize{0.0, 100.0, true, false};       ///< m
const Range kMaterial{0.0, 1e9, true, false};         ///< continuum material quantities (N/m, N·m, kg/m²)
const Range kMaterialOrZero{0.0, 1e9, false, false};
/// k_m of the continuum model (N/m² per metre of bell height): docs/jellyfish.md, "Elastic models".
constexpr const char* kDefaultMuscleStiffness = "427.0";
const Range kAny{};
/// m: a body's size, from 0.1 mm (below any medusa; a bell 1e-308 m across had springs of infinite
/// stiffness) to the largest tank.
constexpr double kMinBodyLength = 1e-4;
const Range kBodyLength{kMinBodyLength, 100.0, false, false};
/// The thesis model's factors of its angular springs (a factor 1e308 made them infinitely stiff).
const Range kFactor{0.0, 1e6, false, false};

fluid::BoundaryType read_boundary(const std::string& name) { return *fluid::boundary_type_from_string(name); }

using namespace param;

const char* const kPreamble =
    "# The built-in jellyfish: thesis Figure 8.21's 4 cm bell (§7.1, §8.2.4), resolved by 64 fluid cells\n"
    "# across its diameter (the coarsest grid whose distance per cycle is within 10 % of the converged one,\n"
    "# docs/convergence.md), in a 24 cm × 48 cm tank with free-slip walls (a tank 1.5 times as wide or\n"
    "# 4/3 as tall changes the distance per cycle by less than 0.5 %). The bell is a continuum\n"
    "# (jellyfish.elastic_model): the same body on any grid.\n"
    "# The thesis's own coarse tank (80 cm, 60 × 60 cells: 3 cells across the bell) is\n"
    "# scenes/jellyfish-thesis.toml. SI units throughout.\n"
    "# The thesis gives lengths in cm and ν = 0.1304 without units; we read it as cm²/s\n"
    "# (1.304e-5 m²/s), which gives the Reynolds numbers of small jellyfish (docs/jellyfish.md).\n"
    "# This file is generated from the parameter table (src/scene/jellyfish_scene.cpp):\n"
    "#   jellysim scenes jellyfish > scenes/jellyfish.toml\n"
    "# Each comment gives the unit, the allowed values and the meaning; docs/parameters.md has them all.\n"
    "# More things in the tank, as [[objects]] tables (docs/scenes.md):\n"
    "#   type = \"jellyfish\": another jellyfish; any [jellyfish] field overrides the one below, e.g.\n"
    "#                       position, tilt_deg, diameter, frequency, phase, noise_seed, steering.\n"
    "#   type = \"circle\" (centre, radius), \"box\" (centre, size, angle_deg) or \"polygon\" (points =\n"
    "#   [x0, y0, x1, y1, ...] or file = \"outline.txt\"): a rigid obstacle held by stiff tethers\n"
    "#   (tether_stiffness, N/m² per metre of outline, default 40000; or stiffness, N/m per marker),\n"
    "#   optionally moving: velocity = [vx, vy], amplitude = [ax, ay],\n"
    "#   frequency (p(t) = p0 + v t + a sin 2πft).\n"
    "#   type = \"ib2d\" (files = \"path/stem\" or model = \"hoover-miller\", [[objects.schedules]]): a structure\n"
    "#   in IB2d's terms, its springs' rest lengths or stiffnesses on a schedule (docs/ib2d.md).\n";

/// The scene kind, its duration, [[objects]] and the tank (§7.1).
std::vector<Parameter> scene_and_tank_parameters() {
  return {
      {"scene", Type::text, "\"jellyfish\"", "", {}, {}, 0, "the scene kind"},
      number("duration", "7.142857142857143", "s", kPositive,
             "simulated time: 5 contraction cycles at 0.7 Hz (the convergence study's; 10 reach the lid)"),
      {"objects", Type::tables, "[]", "", {}, {}, 0, "more jellyfish, rigid obstacles and IB2d structures, as [[objects]] tables (docs/scenes.md)"},

      number("tank.width", "0.24", "m", kTankSize, "six bell diameters"),
      number("tank.height", "0.48", "m", kTankSize, "tank height: five cycles and the wake below (docs/convergence.md)"),
      {"tank.cells", Type::integers, "[384, 768]", "", Range::closed(4, 4096), {}, 0,
       "fluid cells along x and y [nx, ny]: 0.625 mm, 64 across the bell, the coarsest grid within 10 % of the "
       "converged distance per cycle (docs/convergence.md); with tank.geometry = \"3d\" three, [nx, ny, nz]: the "
       "whole tank's cells, even across a mirror plane (tank.symmetry)"},
      vec3("tank.size", "[0.0, 0.0, 0.0]", "m", Range::closed(0.0, 100.0),
           "tank.geometry = \"3d\" only: the tank's [width (x), height (y), depth (z)], each in (0, 100]; "
           "[0, 0, 0]: [tank.width, tank.height, tank.width]"),
      choice("tank.solver", "semi-lagrangian", fluid::fluid_solver_names(),
             "semi-lagrangian (Stam, §4.2, with tank.advection) or eulerian (§4.1, with tank.convection; docs/jellyfish.md)"),
      choice("tank.convection", "donor-cell", fluid::convection_scheme_names(),
             "Eulerian convection: the thesis's γ blend, or limited second order (koren, van-leer; docs/fluids.md)"),
      choice("tank.advection", "maccormack", fluid::advection_scheme_names(),
             "semi-Lagrangian advection: second order (maccormack, bfecc, cubic) or the thesis's linear"),
      choice("tank.pressure_solver", "fft", fluid::pressure_solver_names(),
             "fft is exact and fastest on uniform grids; direct: sparse Cholesky"),
      number("tank.pressure_tolerance", "1e-8", "", Range{0.0, 1e-2, true, false},
             "relative max-norm residual of each pressure solve"),
      number("tank.viscosity", "1.304e-5", "m²/s", kNonNegative, "kinematic viscosity ν", {1e-6, 1e-3, true}),
      number("tank.density", "1000.0", "kg/m³", Range::closed(1e-3, 1e5), "density ρ (thin gas to past mercury)"),
      {"tank.boundaries", Type::choices, "[\"free-slip\", \"free-slip\", \"free-slip\", \"free-slip\"]", "", {},
       {"no-slip", "free-slip", "outflow", "inflow", "periodic"}, 4, "sides [west, east, south, north] (§7.1)"},
      vec2("tank.inflow_velocity", "[0.0, 0.0]", "m/s", kAny, "velocity of the sides of type \"inflow\""),
      integer("tank.tracers_per_side", "40", 0, 1000, "marker particles on a lattice (Figs 8.11/8.12); 0: none"),
      vec2("tank.current", "[0.0, 0.0]", "m/s", kAny,
           "uniform background flow at the start (pair with inflow/outflow or periodic sides)"),
      choice("tank.symmetry", "auto", {"auto", "mirror", "none"},
             "auto: keep the mirror symmetry of a scene that is its own mirror image about the centre line "
             "(docs/jellyfish.md); mirror: insist; none. 3D: auto solves the quarter tank (mirror planes x = 0 "
             "and z = 0) for the symmetric stroke, the half z >= 0 with a pacemaker at azimuth 0 or 180 degrees, "
             "the whole tank otherwise; mirror: the same, refused where no plane is the stroke's own; none: the "
             "whole tank (docs/three-d.md)"),
      choice("tank.geometry", "planar", {"planar", "axisymmetric", "3d"},
             "planar: the slice is a plane section (the thesis); axisymmetric: the slice is the meridian of a body "
             "of revolution about the centre line, the water 3D around it (docs/jellyfish.md); 3d: the bell as an "
             "elastic shell in 3D water, `jellysim simulate` only (docs/three-d.md, \"The 3D scene\")"),
      boolean("tank.half_tank", "true",
              "while the symmetry is kept, solve only the east half (a symmetry plane on the centre line)"),
  };
}

/// The jellyfish: where it is, its body (Fig. 8.21) and its continuum material.
std::vector<Parameter> jellyfish_body_parameters() {
  return {
      boolean("jellyfish.enabled", "true",
              "false: no jellyfish here (e.g. flow past obstacles); [[objects]] may still add some"),
      vec2("jellyfish.position", "[0.12, 0.08]", "m", kAny,
           "aperture centre, inside the tank; 3D: [0, aperture height], the bell's axis on the tank's centre line "
           "x = z = 0 (the 3D tank spans x in [-W/2, W/2], y in [0, H], z in [-D/2, D/2])"),
      number("jellyfish.tilt_deg", "0.0", "°", Range::closed(-360, 360), "swimming direction from +y, counter-clockwise"),
      number("jellyfish.diameter", "0.04", "m", kBodyLength, "bell diameter (Fig. 8.21)"),
      number("jellyfish.height", "0.028", "m", kBodyLength, "bell height"),
      number("jellyfish.tentacle_length", "0.014", "m", Range::closed(0.0, 100.0),
             "tentacle length; 0: none, else at least 0.0001 m"),
      number("jellyfish.thickness", "0.0015", "m", Range::closed(1e-6, 10.0),
             "ϑ: 5.4 % of the height (§7.2); Fig. 8.21's 0.0002 is a rendering value"),
      choice("jellyfish.model", "angular", {"angular", "mesh"},
             "angular: string of points with angular springs (Fig. 7.2 right); mesh: Fig. 7.2 left"),
      number("jellyfish.spacing", "0.0", "m", kNonNegative, "marker spacing; 0: Peskin's rule, half a fluid cell"),
      integer("jellyfish.min_segments_per_side", "6", 2, 1000, "at least this many umbrella springs from aperture to apex"),
      choice("jellyfish.elastic_model", "continuum", {"continuum", "thesis"},
             "continuum: springs from the material quantities below, the same body at any marker spacing; thesis: "
             "per spring as §7.1 builds it (bell_modulus ... tentacle_bending_factor), which changes with the "
             "spacing (docs/jellyfish.md, \"Elastic models\")"),
      number("jellyfish.stretching_stiffness", "2.6685", "N/m", kMaterial,
             "continuum: the bell's tension per unit strain per metre of depth (a plate: E·h)"),
      number("jellyfish.bending_rigidity", "4.0e-5", "N·m", kMaterialOrZero,
             "continuum: the bell's bending moment per unit curvature per metre of depth (a plate: E·h³/12)"),
      number("jellyfish.muscle_stiffness", kDefaultMuscleStiffness, "N/m²", kMaterialOrZero,
             "continuum: the muscle layer's tension per unit strain, per metre of bell height and of depth"),
      number("jellyfish.tentacle_stretching_stiffness", "8.0055", "N/m", kMaterial,
             "continuum: a tentacle's tension per unit strain per metre of depth"),
      number("jellyfish.tentacle_bending_rigidity", "1.09e-5", "N·m", kMaterialOrZero,
             "continuum: a tentacle's bending moment per unit curvature per metre of depth"),
      choice("jellyfish.tentacle_root", "auto", {"auto", "axis", "margin"},
             "what a tentacle's root joint holds it against: axis: the aperture chord, so the tentacle hangs along "
             "the swimming axis however the margin tilts; margin: the bell's last segment, so it continues the "
             "margin's tangent and swings under the bell in the recovery stroke (§7.1); auto: axis for the "
             "continuum model, margin for the thesis's (docs/jellyfish.md, \"Tentacles that trail\")"),
      number("jellyfish.line_density", "0.8166", "kg/m²", kMaterial,
             "continuum: the bell's mass per metre of arc and of depth (the fluid-free model; coupled markers are massless)"),
      number("jellyfish.tentacle_line_density", "2.571", "kg/m²", kMaterial,
             "continuum: a tentacle's mass per metre of length and of depth (the fluid-free model)"),
  };
}

/// The thesis model's moduli, the stroke (§6.2, §7.1) and steering.
std::vector<Parameter> jellyfish_stroke_parameters() {
  return {
      number("jellyfish.bell_modulus", "1.186e6", "Pa", kModulus,
             "thesis: λ of the bell mesoglea (Fig. 8.12: stable with the semi-implicit coupling)"),
      number("jellyfish.muscle_modulus", "4.0e5", "Pa", kModulusOrZero, "thesis: λ of the circumferential muscle (§7.1)"),
      number("jellyfish.bending_factor", "10.0", "", kFactor, "thesis: umbrella angular springs: κ_θ = factor · κ_l · l_r²"),
      number("jellyfish.tentacle_volume_fraction", "3.0", "", Range{0.0, 1e6, true, false},
             "thesis: tentacle springs' volume relative to the umbrella's (thesis: 0.01, stretches > 100 %)"),
      number("jellyfish.tentacle_bending_factor", "1.0", "", kFactor,
             "thesis: tentacle angular springs: κ_θ = factor · κ_l · l_r²"),
      number("jellyfish.frequency", "0.7", "Hz", Range{0.0, 5.0, true, false}, "contractions per second", {0.1, 3.0}),
      number("jellyfish.gamma", "0.56", "", Range{0.0, 1.0, true, false}, "contracted rest length fraction γ (eq. 7.5)", {0.3, 1.0}),
      choice("jellyfish.contraction", "hermite", jellyfish::contraction_shape_names(), "contraction function (§7.1, Fig. 6.10)"),
      number("jellyfish.contract_fraction", "0.3", "", Range{0.0, 1.0, true, true},
             "part of the cycle spent contracting (Fig. 6.10)"),
      number("jellyfish.pause_fraction", "0.0", "", Range{0.0, 1.0, false, true},
             "part of the cycle resting relaxed after re-expanding (Gemmell et al. 2013); contract_fraction + "
             "pause_fraction < 1; open-loop contraction only"),
      number("jellyfish.aperture_expansion_exponent", "2.0", "", Range::closed(1.0, 10.0),
             "aperture springs re-expand more slowly (Fig. 7.5); 1: all alike"),
      number("jellyfish.neural_delay", "0.03", "s", Range::closed(0.0, 10.0),
             "activation delay from the margin to the apex (§6.2)"),
      boolean("jellyfish.controller", "false", "eq. 7.2 closed-loop controller instead of the open-loop function"),
      number("jellyfish.controller_alpha", "2.0", "", kPositive, "α of eq. 7.2"),
      number("jellyfish.trochoid_skew", "0.6", "", Range{0.0, 1.0, false, true}, "λ of the trochoid contraction function"),
      number("jellyfish.phase", "0.0", "cycles", Range::closed(-1000, 1000), "phase offset"),
      integer("jellyfish.noise_seed", "1", 1, 2147483647,
              "the individual (§7.3): `jellysim run` uses render.noise.seed + noise_seed − 1"),
      boolean("jellyfish.steering", "false", "turn toward steer_target by bending one side harder (beyond the thesis)"),
      vec2("jellyfish.steer_target", "[0.12, 0.28]", "m", kAny, "the point to steer toward"),
      number("jellyfish.steer_gain", "0.3", "1/rad", kNonNegative,
             "extra bend of the steering side per radian of heading error"),
      number("jellyfish.steer_max_bend_deg", "20.0", "°", Range::closed(0.0, 90.0),
             "largest extra bend of the steering side, shared by its joints"),
      number("jellyfish.steer_damping", "1.5", "cycles", kNonNegative,
             "the last cycle's turn, times this, is subtracted from the heading error"),
  };
}

/// The coupling (§4.3), the stability limits and the outputs.
std::vector<Parameter> coupling_and_output_parameters() {
  return {
      choice("coupling.scheme", "semi-implicit", coupling::scheme_names(),
             "semi-implicit (backward Euler exchange, GMRES) or explicit (thesis)"),
      choice("coupling.kernel", "bilinear", {"bilinear", "peskin4"},
             "bilinear (thesis: nearest four samples) or Peskin's 4-point kernel"),
      number("coupling.safety_factor", "0.5", "", Range{0.0, 1.0, true, false}, "τ on the CFL/viscous limits of eqs. 4.8–4.9"),
      number("coupling.max_dt", "0.016666666666666666", "s", kPositive,
             "largest step: two per 1/30 s frame (docs/jellyfish.md: the step study)"),
      number("coupling.min_dt", "1e-6", "s", kPositive,
             "a smaller stable step stops the run; below coupling.max_dt and output.frame_interval"),
      number("coupling.krylov_tolerance", "1e-6", "", Range{0.0, 1.0, true, true},
             "relative residual of the semi-implicit solve"),
      integer("coupling.krylov_max_iterations", "200", 1, 100000, "GMRES iterations per step at most"),
      choice("coupling.preconditioner", "mobility", {"mobility", "none"},
             "mobility: dense marker-space solve (one GMRES iteration per step); none: plain GMRES"),
      number("coupling.mobility_rebuild", "0.0", "cells", Range::closed(0.0, 10.0),
             "a marker may move this far before the mobility matrix is rebuilt (0: every step)"),
      integer("coupling.threads", "0", 0, 64,
              "threads that build the marker-space table (0: one per core; one per run inside a batch or sweep); "
              "the results do not depend on it"),

      number("stability.max_speed", "2.0", "m/s", kPositive, "faster fluid or markers = numerical instability"),
      number("stability.max_strain", "1.25", "", kPositive,
             "|l / l_r − 1| of any spring (muscles: uncontracted length) = structural; the margin segment peaks "
             "at 1.0–1.1 in sound runs at small steps (docs/jellyfish.md)"),
      number("stability.max_bend_deg", "143.0", "°", Range{0.0, 180.0, true, false},
             "|θ − θ_r| of any joint = structural (a fold)"),

      number("output.frame_interval", "0.03333333333333333", "s", kPositive,
             "time between recorded frames, at most the duration and at least coupling.min_dt; "
             "at most 10⁶ frames per run"),
      number("output.fps", "0.0", "1/s", Range::closed(0.0, 1000.0),
             "frames per second instead of output.frame_interval (not both): frame k at k / fps exactly, e.g. 24; "
             "0: output.frame_interval. The run ends on the frame nearest the duration, at its grid time"),
      boolean("output.pictures", "true", "a 2D picture per frame (frames/slice_NNNN.png)"),
      integer("output.picture_every", "1", 1, 1000000, "draw every n-th frame"),
      choice("output.picture_quantity", "vorticity", {"vorticity", "speed"}, "what the pictures colour"),
      number("output.picture_zoom", "6.0", "bell diameters", Range::closed(0.0, 1000.0),
             "width of the picture; 0: the whole tank, else at least 0.01"),
      boolean("output.vtk", "true", "fluid fields, tracers and the body per frame (frames/*.vti, *.vtp, jellyfish.pvd)"),
      integer("output.frames_per_cycle", "0", 0, 10000,
              "tank.geometry = \"3d\" only: frames recorded per contraction cycle (frame k at k / (frequency · n)); "
              "0: the nearest whole number to 1 / (frequency · output.frame_interval)"),
  };
}

/// The 3D bell's own fields (tank.geometry = "3d"; docs/three-d.md): its shell mesh, pacemaker and
/// tentacle rods. Its shape, material and stroke are the [jellyfish] fields above.
std::vector<Parameter> shell_parameters() {
  return {
      number("jellyfish.shell_edge", "0.0", "m", Range::closed(0.0, 1.0),
             "3D only: the shell mesh's edge length, in [diameter / 1000, diameter / 2]; 0: half a fluid cell "
             "(Peskin's rule, as the slice's markers)"),
      boolean("jellyfish.pacemaker", "false",
              "3D only: the impulse starts at one point of the margin (the bell turns); false: the margin fires at once"),
      number("jellyfish.pacemaker_azimuth_deg", "0.0", "°", Range::closed(-360.0, 360.0),
             "3D only: where on the margin the pacemaker sits, from +x toward +z (0 or 180: the half tank is solved)"),
      number("jellyfish.conduction_speed", "0.0", "m/s", Range::closed(0.0, 1000.0),
             "3D only: the pacemaker's impulse's speed around the margin; 0: the slice's, the meridian's arc over "
             "jellyfish.neural_delay (1.2 m/s for the built-in bell: the far side 0.05 s late; 0.25 turns it by "
             "about 24 degrees a cycle, docs/three-d.md)"),
      integer("jellyfish.tentacle_count", "12", 0, 1000,
              "3D only: tentacles (rods of jellyfish.tentacle_length) hanging evenly around the margin; 0: none"),
  };
}

ParameterTable make_jellyfish_scene() {
  std::vector<Parameter> p;
  for (auto section : {scene_and_tank_parameters, jellyfish_body_parameters, jellyfish_stroke_parameters,
                       shell_parameters, coupling_and_output_parameters})
    for (Parameter& q : section()) p.push_back(std::move(q));
  return ParameterTable("jellyfish", kPreamble, std::move(p));
}

/// The material fields of each elastic model (docs/jellyfish.md, "Elastic models").
constexpr const char* kContinuumFields[] = {"stretching_stiffness", "bending_rigidity", "muscle_stiffness",
                                            "tentacle_stretching_stiffness", "tentacle_bending_rigidity",
                                            "line_density", "tentacle_line_density"};
constexpr const char* kThesisFields[] = {"bell_modulus", "muscle_modulus", "bending_factor", "tentacle_volume_fraction",
                                         "tentacle_bending_factor"};

/// A material field of the other elastic model set to anything but its default would be ignored
/// silently: refused, naming both (a contradiction, issue 23).
void refuse_other_models_fields(const Reader& r, jellyfish::ElasticModel model) {
  const bool continuum = model == jellyfish::ElasticModel::continuum;
  const std::span<const char* const> ignored = continuum ? std::span<const char* const>(kThesisFields)
                                                         : std::span<const char* const>(kContinuumFields);
  for (const char* field : ignored) {
    const std::string key = std::string("jellyfish.") + field;
    const double value = r.number(key);
    if (value == std::stod(r.table().at(key).value)) continue;
    throw InputError("field '" + key + "' = " + config::format_number(value) + " belongs to jellyfish.elastic_model = \"" +
                     (continuum ? "thesis" : "continuum") + "\", but the model is \"" + (continuum ? "continuum" : "thesis") +
                     "\": set jellyfish.elastic_model = \"" + (continuum ? "thesis" : "continuum") + "\" or use " +
                     (continuum ? "stretching_stiffness, bending_rigidity, muscle_stiffness and the tentacle_ fields"
                                : "bell_modulus, muscle_modulus, bending_factor and the tentacle_ fields") +
                     " (docs/jellyfish.md, \"Elastic models\")");
  }
}

/// The bell's and tentacles' elastic constants of both models (continuum material; the thesis's moduli).
void read_elastic_constants(const Reader& r, jellyfish::JellyfishSpec& j) {
  jellyfish::ContinuumMaterial& m = j.material;
  m.stretching_n_per_m = r.number("jellyfish.stretching_stiffness");
  m.bending_n_m = r.number("jellyfish.bending_rigidity");
  m.muscle_n_per_m2 = r.number("jellyfish.muscle_stiffness");
  m.tentacle_stretching_n_per_m = r.number("jellyfish.tentacle_stretching_stiffness");
  m.tentacle_bending_n_m = r.number("jellyfish.tentacle_bending_rigidity");
  m.line_density_kg_per_m2 = r.number("jellyfish.line_density");
  m.tentacle_line_density_kg_per_m2 = r.number("jellyfish.tentacle_line_density");
  j.bell_modulus_pa = r.number("jellyfish.bell_modulus");
  j.muscle_modulus_pa = r.number("jellyfish.muscle_modulus");
  j.bending_factor = r.number("jellyfish.bending_factor");
  j.tentacle_volume_fraction = r.number("jellyfish.tentacle_volume_fraction");
  j.tentacle_bending_factor = r.number("jellyfish.tentacle_bending_factor");
}

/// The bell's shape, tentacles' length, material and stroke (§7.1, §6.2, Fig. 8.21): the
/// [jellyfish] fields the 2D slice and the 3D shell (ShellBellSpec::slice) share.
void read_body_and_stroke(const Reader& r, jellyfish::JellyfishSpec& j) {
  j.diameter_m = r.number("jellyfish.diameter");
  j.height_m = r.number("jellyfish.height");
  j.tentacle_length_m = r.number("jellyfish.tentacle_length");
  if (j.tentacle_length_m > 0 && j.tentacle_length_m < kMinBodyLength)
    throw InputError("field 'jellyfish.tentacle_length' = " + config::format_number(j.tentacle_length_m) +
                     " is out of range: 0 (no tentacles) or [" + config::format_number(kMinBodyLength) + ", 100] m");
  j.thickness_m = r.number("jellyfish.thickness");
  j.elastic_model = r.choice("jellyfish.elastic_model") == "thesis" ? jellyfish::ElasticModel::thesis
                                                                    : jellyfish::ElasticModel::continuum;
  refuse_other_models_fields(r, j.elastic_model);
  read_elastic_constants(r, j);
  j.frequency_hz = r.number("jellyfish.frequency");
  j.gamma = r.number("jellyfish.gamma");
  j.profile.shape = *jellyfish::contraction_shape_from_string(
      r.choice("jellyfish.contraction"));
  j.profile.contract_fraction = r.number("jellyfish.contract_fraction");
  j.profile.pause_fraction = r.number("jellyfish.pause_fraction");
  j.aperture_expansion_exponent = r.number("jellyfish.aperture_expansion_exponent");
  j.neural_delay_s = r.number("jellyfish.neural_delay");
  j.closed_loop = r.boolean("jellyfish.controller");
  j.controller_alpha = r.number("jellyfish.controller_alpha");
  j.profile.trochoid_skew = r.number("jellyfish.trochoid_skew");
  j.phase_cycles = r.number("jellyfish.phase");
}

/// One jellyfish from the [jellyfish] table of `c` (§7.1, Fig. 8.21), in the tank `t`.
jellyfish::JellyfishSpec read_jellyfish(const config::Config& c, const coupling::TankSpec& t) {
  const Reader r(c, jellyfish_scene());
  jellyfish::JellyfishSpec j;
  j.aperture_centre_m = r.vec2("jellyfish.position");
  if (!(j.aperture_centre_m.x > 0 && j.aperture_centre_m.x < t.width_m && j.aperture_centre_m.y > 0 &&
        j.aperture_centre_m.y < t.height_m))
    throw InputError("field 'jellyfish.position' = [" + config::format_number(j.aperture_centre_m.x) + ", " +
                     config::format_number(j.aperture_centre_m.y) + "] is outside the tank [0, " +
                     config::format_number(t.width_m) + "] x [0, " + config::format_number(t.height_m) + "]");
  j.tilt_rad = r.number("jellyfish.tilt_deg") * kDegree;
  read_body_and_stroke(r, j);
  j.model = r.choice("jellyfish.model") == "mesh" ? jellyfish::UmbrellaModel::mesh
                                                                       : jellyfish::UmbrellaModel::angular;
  const double spacing = r.number("jellyfish.spacing");
  j.max_spacing_m = spacing > 0 ? spacing : coupling::peskin_spacing(t);
  j.min_segments_per_side = static_cast<int>(r.integer("jellyfish.min_segments_per_side"));
  const std::string root = r.choice("jellyfish.tentacle_root");
  j.tentacle_root = root == "axis"     ? jellyfish::TentacleRoot::axis
                    : root == "margin" ? jellyfish::TentacleRoot::margin
                                       : jellyfish::TentacleRoot::automatic;
  j.steering = r.boolean("jellyfish.steering");
  j.steer_target_m = r.vec2("jellyfish.steer_target");
  j.steer_gain = r.number("jellyfish.steer_gain");
  j.steer_max_bend_rad = r.number("jellyfish.steer_max_bend_deg") * kDegree;
  j.steer_damping_cycles = r.number("jellyfish.steer_damping");
  j.noise_seed = static_cast<int>(r.integer("jellyfish.noise_seed"));
  try {
    jellyfish::validate(j);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  return j;
}

/// The scene's [[objects]]: more jellyfish (any [jellyfish] field overrides the template), rigid
/// obstacles (circle, box, polygon), each with an optional prescribed path, and IB2d structures;
/// each type's fields are a table (scene/objects.hpp).
void read_objects(const config::Config& c, jellyfish::SwimSettings& s) {
  const std::size_t count = c.array_size("objects");
  for (std::size_t k = 0; k < count; ++k) {
    config::Config o = c.element("objects", k);
    const std::string where = "objects[" + std::to_string(k) + "]";
    if (!o.has("type")) throw InputError(where + ": missing field 'type' (jellyfish, circle, box, polygon or ib2d)");
    std::string type;
    try {
      type = o.choice("type", object_types());
    } catch (const InputError& e) {
      throw InputError(where + ": unknown object " + e.what());
    }
    const std::string name = where + " (" + type + ")";
    try {
      if (type == "jellyfish") {
        o.erase("type");
        config::Config jc = c;
        jc.merge(o.nested_under("jellyfish"));
        s.school.push_back(read_jellyfish(jc, s.tank));
      } else if (type == "ib2d") {
        s.structures.push_back(read_ib2d_object(o, name, s.tank));
      } else {
        s.obstacles.push_back(read_obstacle(o, type, name));
      }
    } catch (const InputError& e) {
      const std::string message = e.what();
      throw InputError(message.rfind(name, 0) == 0 ? message : name + ": " + message);
    }
  }
}

}  // namespace

jellyfish::JellyfishSpec read_jellyfish_body(const config::Config& c) {
  jellyfish::JellyfishSpec j;
  read_body_and_stroke(Reader(c, jellyfish_scene()), j);
  return j;
}

namespace {

/// The fields only the 3D scene reads (tank.geometry = "3d"), refused in a 2D scene unless left at
/// their defaults: the 2D run would ignore them.
constexpr const char* kFieldsOf3d[] = {"tank.size", "output.frames_per_cycle", "jellyfish.shell_edge",
                                       "jellyfish.pacemaker", "jellyfish.pacemaker_azimuth_deg",
                                       "jellyfish.conduction_speed", "jellyfish.tentacle_count"};

/// A 3D scene here (the 2D reader: sweep, view, batch, the experiments) or a 3D-only field in a 2D
/// scene: refused, naming the field (docs/three-d.md, "The 3D scene").
void refuse_3d(const Reader& r) {
  if (r.choice("tank.geometry") == "3d")
    throw InputError("field 'tank.geometry' = \"3d\": this command runs the 2D slice; the 3D scene runs with "
                     "`jellysim simulate` (docs/three-d.md, \"The 3D scene\")");
  for (const char* key : kFieldsOf3d)
    if (!r.holds_default(key))
      throw InputError("field '" + std::string(key) + "' = " + r.config().literal(key) +
                       " belongs to the 3D scene (tank.geometry = \"3d\"); this scene's geometry is \"" +
                       r.choice("tank.geometry") + "\": leave it at " + r.table().at(key).value);
}

/// What can be told before any body is built (issue 23): each jellyfish fits the tank at all (its
/// diameter, height and tentacles are each at most the tank's diagonal, or no placement fits), and
/// the run's estimated memory fits the budget (core/memory.hpp).
void check_size_and_memory(const jellyfish::SwimSettings& s) {
  const double diagonal = std::hypot(s.tank.width_m, s.tank.height_m);
  for (std::size_t k = 0; k < s.school.size(); ++k) {
    const jellyfish::JellyfishSpec& j = s.school[k];
    const std::pair<const char*, double> sizes[] = {
        {"diameter", j.diameter_m}, {"height", j.height_m}, {"tentacle_length", j.tentacle_length_m}};
    for (const auto& [field, value] : sizes)
      if (value > diagonal)
        throw InputError("jellyfish " + std::to_string(k + 1) + " cannot fit in the tank: its " + field + " " +
                         config::format_number(value) + " m exceeds the tank's diagonal " + config::format_number(diagonal) +
                         " m (field 'jellyfish." + field + "')");
  }
  const jellyfish::MemoryEstimate e = jellyfish::estimate_memory(s);
  const core::MemoryBudget budget = core::memory_budget();
  if (!(e.bytes <= static_cast<double>(budget.bytes)))
    throw InputError("the run would need about " + core::format_bytes(e.bytes) + " of memory (" + e.breakdown +
                     "), more than the budget of " + core::format_bytes(static_cast<double>(budget.bytes)) + " (" +
                     budget.source + (budget.source == "--memory-limit" ? "" : "; --memory-limit sets it") +
                     "): coarsen tank.cells, raise "
                     "jellyfish.spacing, record fewer frames (output.frame_interval) or raise --memory-limit");
}

/// The tank: size, grid, fluid solver, water, sides, tracers, current, symmetry and geometry (§7.1).
coupling::TankSpec read_tank(const Reader& r) {
  coupling::TankSpec t;
  t.width_m = r.number("tank.width");
  t.height_m = r.number("tank.height");
  const auto cells = r.integers("tank.cells");
  if (cells.size() != 2)
    throw InputError("field 'tank.cells' has " + std::to_string(cells.size()) + " entries: it must have 2, [nx, ny], "
                     "each in [4, 4096] (three, [nx, ny, nz], only with tank.geometry = \"3d\")");
  t.cells_x = static_cast<int>(cells[0]);
  t.cells_y = static_cast<int>(cells[1]);
  t.solver = r.choice("tank.solver");
  t.convection = *fluid::convection_scheme_from_string(r.choice("tank.convection"));
  t.advection = *fluid::advection_scheme_from_string(r.choice("tank.advection"));
  t.pressure_solver = r.choice("tank.pressure_solver");
  t.pressure_tolerance = r.number("tank.pressure_tolerance");
  t.viscosity_m2_per_s = r.number("tank.viscosity");
  t.density_kg_per_m3 = r.number("tank.density");
  const auto sides = r.choices("tank.boundaries");
  const Vec2 inflow = r.vec2("tank.inflow_velocity");
  fluid::BoundaryCondition* b[4] = {&t.boundaries.west, &t.boundaries.east, &t.boundaries.south, &t.boundaries.north};
  for (int k = 0; k < 4; ++k) {
    b[k]->type = read_boundary(sides[static_cast<std::size_t>(k)]);
    b[k]->velocity_m_per_s = b[k]->type == fluid::BoundaryType::inflow ? inflow : Vec2{};
  }
  try {
    t.boundaries.validate();
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("field 'tank.boundaries': ") + e.what());
  }
  t.tracers_per_side = static_cast<int>(r.integer("tank.tracers_per_side"));
  t.current_m_per_s = r.vec2("tank.current");
  const std::string symmetry = r.choice("tank.symmetry");
  t.half_tank = r.boolean("tank.half_tank");
  t.geometry = r.choice("tank.geometry") == "axisymmetric" ? fluid::Geometry::axisymmetric : fluid::Geometry::planar;
  t.symmetry = symmetry == "auto"     ? coupling::MirrorSymmetry::automatic
               : symmetry == "mirror" ? coupling::MirrorSymmetry::mirror
                                      : coupling::MirrorSymmetry::none;
  return t;
}

/// The coupling (§4.3) and its step limits; a smallest step above the largest, or above the frame
/// interval, is an input error (not a numerical instability at t = 0).
coupling::CouplingSettings read_coupling(const Reader& r, double frame_interval_s) {
  coupling::CouplingSettings k;
  k.scheme = *coupling::scheme_from_string(r.choice("coupling.scheme"));
  k.kernel = *coupling::kernel_from_string(r.choice("coupling.kernel"));
  k.safety_factor = r.number("coupling.safety_factor");
  k.max_time_step_s = r.number("coupling.max_dt");
  k.min_time_step_s = r.number("coupling.min_dt");
  // Contradictions are input errors, not a numerical instability at t = 0.
  if (!(k.min_time_step_s < k.max_time_step_s))
    throw InputError("field 'coupling.min_dt' = " + config::format_number(k.min_time_step_s) +
                     " must be below coupling.max_dt = " + config::format_number(k.max_time_step_s));
  if (!(frame_interval_s >= k.min_time_step_s))
    throw InputError("field 'output.frame_interval' = " + config::format_number(frame_interval_s) +
                     " is below coupling.min_dt = " + config::format_number(k.min_time_step_s) +
                     ": steps land on every frame, so each would be shorter than the smallest allowed");
  k.krylov_tolerance = r.number("coupling.krylov_tolerance");
  k.krylov_max_iterations = static_cast<int>(r.integer("coupling.krylov_max_iterations"));
  k.preconditioner = *coupling::preconditioner_from_string(r.choice("coupling.preconditioner"));
  k.mobility_rebuild_cells = r.number("coupling.mobility_rebuild");
  k.threads = static_cast<int>(r.integer("coupling.threads"));
  return k;
}

}  // namespace

/// output.frame_interval, or output.fps (frame k at k / fps): one of the two. The interval given
/// differs from the table's default when it was named (a scene naming the default itself is not
/// told apart from one leaving it out).
void read_frame_rate(const Reader& r, jellyfish::SwimSettings& s) {
  s.frame_interval_s = r.number("output.frame_interval");
  const double fps = r.number("output.fps");
  if (fps == 0.0) return;
  const double default_interval =
      config::Config::parse("x = " + r.table().at("output.frame_interval").value, "default").number("x");
  if (s.frame_interval_s != default_interval)
    throw InputError("fields 'output.fps' = " + config::format_number(fps) + " and 'output.frame_interval' = " +
                     config::format_number(s.frame_interval_s) + " both give the frame rate: give one of them " +
                     "(output.fps in (0, 1000] frames per second, or output.frame_interval in seconds)");
  if (fps * s.duration_s < 1.0)
    throw InputError("field 'output.fps' = " + config::format_number(fps) + " is out of range: at least one frame " +
                     "after the start, fps in [1 / duration = " + config::format_number(1.0 / s.duration_s) +
                     ", 1000] (or 0: output.frame_interval)");
  s.frames_per_second = fps;
  s.frame_interval_s = 1.0 / fps;
}

jellyfish::SwimSettings read_swim_settings(const config::Config& c) {
  const Reader r(c, jellyfish_scene());
  r.validate_all();
  refuse_3d(r);
  jellyfish::SwimSettings s;
  s.duration_s = r.number("duration");
  read_frame_rate(r, s);
  if (s.frame_interval_s > s.duration_s)
    throw InputError("field 'output.frame_interval' = " + config::format_number(s.frame_interval_s) +
                     " is out of range (0, duration = " + config::format_number(s.duration_s) + "]");
  if (!(s.duration_s / s.frame_interval_s <= kMaxFrames))
    throw InputError("fields 'duration' = " + config::format_number(s.duration_s) + " s and 'output.frame_interval' = " +
                     config::format_number(s.frame_interval_s) + " s ask for " + config::format_number(s.duration_s / s.frame_interval_s) +
                     " frames; at most " + config::format_number(kMaxFrames) + " (raise the interval or shorten the run)");

  const coupling::TankSpec& t = s.tank = read_tank(r);
  if (r.boolean("jellyfish.enabled")) s.school.push_back(read_jellyfish(c, t));
  read_objects(c, s);

  s.coupling = read_coupling(r, s.frame_interval_s);

  s.limits.max_speed_m_per_s = r.number("stability.max_speed");
  s.limits.max_strain = r.number("stability.max_strain");
  s.limits.max_bend_rad = r.number("stability.max_bend_deg") * kDegree;
  check_size_and_memory(s);  // before validate_layout builds the bodies
  try {
    jellyfish::validate_layout(s);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("scene layout: ") + e.what());
  }
  if (t.symmetry == coupling::MirrorSymmetry::mirror || t.geometry == fluid::Geometry::axisymmetric)
    if (const std::string problem = jellyfish::mirror_symmetry_problem(s); !problem.empty()) {
      if (t.geometry == fluid::Geometry::axisymmetric)
        throw InputError("field 'tank.geometry' is \"axisymmetric\", but the scene is not the slice of a body of "
                         "revolution (its own mirror image about the centre line): " + problem);
      throw InputError("field 'tank.symmetry' is \"mirror\", but the scene is not its own mirror image about the "
                       "tank's centre line: " + problem + " (use \"auto\" or \"none\")");
    }
  return s;
}


double read_picture_zoom(const config::Config& c) {
  const double zoom = Reader(c, jellyfish_scene()).number("output.picture_zoom");
  if (zoom != 0.0 && zoom < kMinPictureZoom)
    throw InputError("field 'output.picture_zoom' = " + config::format_number(zoom) + " is out of range: 0 (the whole " +
                     "tank) or [" + config::format_number(kMinPictureZoom) + ", 1000] bell diameters");
  return zoom;
}

const ParameterTable& jellyfish_scene() {
  static const ParameterTable table = make_jellyfish_scene();
  return table;
}

std::span<const char* const> fields_of_3d() { return kFieldsOf3d; }

}  // namespace jellysim::scene
