#include "jellysim/scene/study_scenes.hpp"

#include "jellysim/core/errors.hpp"
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"

namespace jellysim::scene {
namespace {

using config::Range;
using namespace param;


ParameterTable make_cavity() {
  std::vector<Parameter> p{
      {"scene", Type::text, "\"driven-cavity\"", "", {}, {}, 0, "the scene kind"},
      choice("solver", "eulerian", fluid::fluid_solver_names(), "fluid solver (`--solver`)"),
      number("re", "100.0", "", Range{0.0, 1e5, true, false}, "Reynolds number U L / ν (`--re`)"),
      integer("grid", "64", 4, 1024, "cells per side (`--grid`)"),
      choice("cavity.pressure_solver", "multigrid", fluid::pressure_solver_names(), "pressure solver"),
      number("cavity.pressure_tolerance", "1e-8", "", Range{0.0, 1e-2, true, false},
             "relative max-norm residual of the pressure solve"),
      number("cavity.time_step", "0.0", "s", Range::non_negative(),
             "0: the Eulerian CFL/viscous limit (eqs. 4.8-4.9), or Δx/U semi-Lagrangian"),
      number("cavity.safety_factor", "0.9", "", Range{0.0, 1.0, true, false}, "on the Eulerian step limit"),
      choice("cavity.convection", "koren", fluid::convection_scheme_names(),
             "Eulerian: limited second order (koren, van-leer) or the thesis's γ blend"),
      choice("cavity.advection", "maccormack", fluid::advection_scheme_names(),
             "semi-Lagrangian: second order (maccormack, bfecc, cubic) or the thesis's linear"),
      number("cavity.max_time", "200.0", "s", Range::positive(), "stop here if not steady before"),
      number("cavity.steady_tolerance", "1e-6", "", Range::positive(),
             "steady when max|du/dt| < tolerance U²/L (`--steady-tolerance`); else the run ends at max_time"),
      number("output.frame_interval", "1.0", "s", Range::non_negative(),
             "between VTK frames (frames/*.vti, *.vtp, listed in cavity.pvd); 0: none"),
      integer("output.tracers_per_side", "24", 0, 1000,
              "marker particles on a lattice, drawn in the pictures and written per frame"),
      boolean("figure_8_7.enabled", "true", "also draw thesis Figure 8.7: both solvers, several viscosities"),
      {"figure_8_7.viscosities", Type::numbers, "[0.1, 0.01, 0.001]", "m²/s", Range::positive(), {}, 0,
       "ν of the panels (the thesis does not list its values)"},
      integer("figure_8_7.grid", "30", 4, 256, "cells per side (thesis: 30 × 30)"),
      number("figure_8_7.time_step", "0.03333333333333333", "s", Range::positive(), "thesis: 1/30"),
      number("figure_8_7.duration", "20.0", "s", Range::positive(), "simulated per panel"),
  };
  return ParameterTable(
      "driven-cavity",
      "# Lid-driven cavity (thesis §8.1.3, Figure 8.7): unit square, lid speed 1 on the top side, no-slip\n"
      "# elsewhere. Run to steady state and compared with Ghia, Ghia & Shin (1982) when re = 100, 400,\n"
      "# 1000 or 3200 (centreline profiles and the primary vortex).\n"
      "# `jellysim experiment driven-cavity --solver S --re R --grid N` sets the three top-level keys.\n"
      "# Generated from the parameter table (src/scene/study_scenes.cpp): jellysim scenes driven-cavity\n",
      std::move(p));
}

ParameterTable make_membrane() {
  std::vector<Parameter> p{
      number("duration", "2.0", "s", Range::positive(), "simulated time"),
      choice("solver", "eulerian", fluid::fluid_solver_names(), "fluid solver (`--solver`)"),
      integer("membrane.cells", "30", 4, 1024, "grid cells per side (Fig. 8.9: 30 x 30)"),
      number("membrane.box", "1.0", "m", Range::positive(), "side of the square fluid box"),
      number("membrane.viscosity", "0.0", "m²/s", Range::non_negative(), "ν (Fig. 8.9: inviscid)"),
      number("membrane.density", "1.0", "kg/m²", Range::positive(), "ρ"),
      number("membrane.stiffness", "10.0", "N/m", Range::positive(), "κ_l of every spring (Fig. 8.9)"),
      vec2("membrane.semi_axes", "[0.35, 0.25]", "m", Range::positive(),
           "initial oval (Fig. 8.9's \"0.35 x 0.25\", read as semi-axes), each below half the box"),
      number("membrane.dt", "0.002", "s", Range::positive(), "fixed step (Fig. 8.9)"),
      number("membrane.frame_interval", "0.02", "s", Range::positive(), "recorded frames"),
      choice("membrane.scheme", "explicit", {"explicit", "semi-implicit"}, "explicit (thesis) or semi-implicit"),
      choice("membrane.kernel", "bilinear", {"bilinear", "peskin4"}, "bilinear (thesis) or peskin4"),
      {"refinement.cells", Type::integers, "[30, 60, 120]", "", Range::closed(4, 1024), {}, 0,
       "the same test on finer grids (Δt scaled with the cell size)"},
  };
  return ParameterTable(
      "oval-membrane",
      "# Oval membrane test of Stockie & Wetton — thesis §8.1.3, Figures 8.8 and 8.9.\n"
      "# A ring of zero-rest-length springs around an ellipse pulls itself toward a circle; the enclosed\n"
      "# area should not change, so the area lost measures leakage through the immersed boundary.\n"
      "# Thesis: 2.575 % lost (Eulerian), 3.67 % (semi-Lagrangian); Stockie & Wetton 2.8 %.\n"
      "# Generated from the parameter table (src/scene/study_scenes.cpp): jellysim scenes oval-membrane\n",
      std::move(p));
}

/// [flow] length, speed, viscosity and the grids of a Taylor-Green study.
std::vector<Parameter> taylor_green_flow(const std::string& viscosity) {
  return {number("flow.length", "6.283185307179586", "m", Range::positive(), "L: the periodic box is L × L"),
          number("flow.speed", "1.0", "m/s", Range::positive(), "U: velocity amplitude"),
          number("flow.viscosity", viscosity, "m²/s", Range::positive(), "ν")};
}

ParameterTable make_taylor_green() {
  std::vector<Parameter> p{{"scene", Type::text, "\"taylor-green\"", "", {}, {}, 0, "the scene kind"}};
  for (Parameter& f : taylor_green_flow("0.1")) p.push_back(std::move(f));
  const std::vector<Parameter> rest{
      number("flow.end_time", "1.0", "s", Range::positive(), "errors are measured here"),
      {"study.solvers", Type::choices, "[\"eulerian\", \"semi-lagrangian\"]", "", {}, fluid::fluid_solver_names(), 0, "fluid solvers compared"},
      {"study.convection", Type::choices, "[\"donor-cell\", \"van-leer\", \"koren\"]", "", {},
       fluid::convection_scheme_names(), 0, "convection schemes the Eulerian solver is run with"},
      {"study.advection", Type::choices, "[\"linear\", \"maccormack\", \"bfecc\", \"cubic\"]", "", {},
       fluid::advection_scheme_names(), 0, "advection schemes the semi-Lagrangian solver is run with"},
      {"study.grids", Type::integers, "[16, 32, 64, 128]", "", Range::closed(4, 2048), {}, 0, "cells per side"},
      number("study.safety_factor", "0.5", "", Range{0.0, 1.0, true, false}, "Eulerian Δt = factor × limit of eqs. 4.8-4.9"),
      number("study.semi_lagrangian_courant", "0.5", "", Range::positive(), "semi-Lagrangian Δt = courant × Δx / U"),
      choice("study.pressure_solver", "multigrid", fluid::pressure_solver_names(), "pressure solver"),
      number("study.pressure_tolerance", "1e-10", "", Range{0.0, 1e-2, true, false}, "relative max-norm residual"),
  };
  p.insert(p.end(), rest.begin(), rest.end());
  return ParameterTable(
      "taylor-green",
      "# Periodic Taylor–Green vortex against its exact solution (thesis ch. 4): error norms and measured\n"
      "# order of convergence in space for both fluid solvers, with each of their schemes, over several grids.\n"
      "# Generated from the parameter table (src/scene/study_scenes.cpp): jellysim scenes taylor-green\n",
      std::move(p));
}

ParameterTable make_solver_cost() {
  std::vector<Parameter> p{{"scene", Type::text, "\"solver-cost\"", "", {}, {}, 0, "the scene kind"}};
  for (Parameter& f : taylor_green_flow("0.01")) p.push_back(std::move(f));
  const std::vector<Parameter> rest{
      {"study.grids", Type::integers, "[32, 64, 128, 256, 512]", "", Range::closed(4, 2048), {}, 0,
       "cells per side (SOR at 512² takes about 15 s per cold solve)"},
      {"study.solvers", Type::choices, "[\"eulerian\", \"semi-lagrangian\"]", "", {}, fluid::fluid_solver_names(), 0, "fluid solvers compared"},
      {"study.pressure_solvers", Type::choices, "[\"sor\", \"multigrid\", \"fft\"]", "", {}, fluid::pressure_solver_names(), 0,
       "pressure solvers compared"},
      integer("study.steps", "5", 1, 100000, "timed steps per configuration (after one warm-up step)"),
      number("study.pressure_tolerance", "1e-6", "", Range{0.0, 1e-2, true, false}, "relative max-norm residual"),
      number("study.safety_factor", "0.5", "", Range{0.0, 1.0, true, false}, "Eulerian Δt = factor × limit"),
      number("study.semi_lagrangian_courant", "1.0", "", Range::positive(), "semi-Lagrangian Δt = courant × Δx / U"),
      boolean("study.sor_optimal_omega", "true", "ω = 2/(1 + sin(π/n)) instead of Griebel's 1.7"),
  };
  p.insert(p.end(), rest.begin(), rest.end());
  return ParameterTable(
      "solver-cost",
      "# Cost and accuracy of both fluid solvers with both pressure solvers on the Taylor–Green problem,\n"
      "# across grid sizes: time per step, time per simulated second, pressure iterations, error.\n"
      "# Generated from the parameter table (src/scene/study_scenes.cpp): jellysim scenes solver-cost\n",
      std::move(p));
}

fluid::TaylorGreen read_flow(const Reader& r) {
  return {r.number("flow.length"), r.number("flow.speed"), r.number("flow.viscosity")};
}

std::vector<int> read_grids(const Reader& r) {
  std::vector<int> grids;
  for (std::int64_t n : r.integers("study.grids")) grids.push_back(static_cast<int>(n));
  return grids;
}

}  // namespace

const ParameterTable& taylor_green_scene() {
  static const ParameterTable table = make_taylor_green();
  return table;
}

const ParameterTable& solver_cost_scene() {
  static const ParameterTable table = make_solver_cost();
  return table;
}

studies::TaylorGreenSettings read_taylor_green(const config::Config& c) {
  const Reader r(c, taylor_green_scene());
  studies::TaylorGreenSettings s;
  s.flow = read_flow(r);
  s.end_time_s = r.number("flow.end_time");
  s.solvers = r.choices("study.solvers");
  s.convection_schemes = r.choices("study.convection");
  s.advection_schemes = r.choices("study.advection");
  s.grids = read_grids(r);
  if (s.grids.size() < 2)  // an order needs two errors
    throw InputError("field 'study.grids' must list at least two grids to measure an order of convergence");
  s.safety_factor = r.number("study.safety_factor");
  s.semi_lagrangian_courant = r.number("study.semi_lagrangian_courant");
  s.pressure_solver = r.choice("study.pressure_solver");
  s.pressure_tolerance = r.number("study.pressure_tolerance");
  return s;
}

studies::SolverCostSettings read_solver_cost(const config::Config& c) {
  const Reader r(c, solver_cost_scene());
  studies::SolverCostSettings s;
  s.flow = read_flow(r);
  s.grids = read_grids(r);
  s.solvers = r.choices("study.solvers");
  s.pressure_solvers = r.choices("study.pressure_solvers");
  s.steps = static_cast<int>(r.integer("study.steps"));
  s.pressure_tolerance = r.number("study.pressure_tolerance");
  s.safety_factor = r.number("study.safety_factor");
  s.semi_lagrangian_courant = r.number("study.semi_lagrangian_courant");
  s.sor_optimal_omega = r.boolean("study.sor_optimal_omega");
  return s;
}

const ParameterTable& driven_cavity_scene() {
  static const ParameterTable table = make_cavity();
  return table;
}

const ParameterTable& oval_membrane_scene() {
  static const ParameterTable table = make_membrane();
  return table;
}

CavityScene read_cavity_scene(const config::Config& c) {
  const Reader r(c, driven_cavity_scene());
  CavityScene s;
  s.cavity.solver = r.choice("solver");
  s.cavity.reynolds = r.number("re");
  s.cavity.cells = static_cast<int>(r.integer("grid"));
  s.cavity.pressure_solver = r.choice("cavity.pressure_solver");
  s.cavity.pressure_tolerance = r.number("cavity.pressure_tolerance");
  s.cavity.time_step_s = r.number("cavity.time_step");
  s.cavity.safety_factor = r.number("cavity.safety_factor");
  s.cavity.convection = *fluid::convection_scheme_from_string(r.choice("cavity.convection"));
  s.cavity.advection = *fluid::advection_scheme_from_string(r.choice("cavity.advection"));
  s.cavity.max_time_s = r.number("cavity.max_time");
  s.cavity.steady_tolerance = r.number("cavity.steady_tolerance");
  s.cavity.frame_interval_s = r.number("output.frame_interval");
  s.cavity.tracers_per_side = static_cast<int>(r.integer("output.tracers_per_side"));
  s.figure_enabled = r.boolean("figure_8_7.enabled");
  s.figure.viscosities_m2_per_s = r.numbers("figure_8_7.viscosities");
  s.figure.cells = static_cast<int>(r.integer("figure_8_7.grid"));
  s.figure.time_step_s = r.number("figure_8_7.time_step");
  s.figure.duration_s = r.number("figure_8_7.duration");
  s.figure.pressure_solver = s.cavity.pressure_solver;
  if (s.figure_enabled && s.figure.viscosities_m2_per_s.empty()) {
    throw InputError("field 'figure_8_7.viscosities' must list at least one viscosity when figure_8_7.enabled");
  }
  return s;
}

MembraneScene read_membrane_scene(const config::Config& c) {
  const Reader r(c, oval_membrane_scene());
  MembraneScene m;
  studies::OvalMembraneSettings& s = m.membrane;
  s.solver = r.choice("solver");
  s.cells = static_cast<int>(r.integer("membrane.cells"));
  s.box_m = r.number("membrane.box");
  s.viscosity_m2_per_s = r.number("membrane.viscosity");
  s.density_kg_per_m3 = r.number("membrane.density");
  s.stiffness = r.number("membrane.stiffness");
  const Vec2 axes = r.vec2("membrane.semi_axes");
  if (!(axes.x < 0.5 * s.box_m && axes.y < 0.5 * s.box_m))
    throw InputError("field 'membrane.semi_axes' must be positive and below half the box");
  s.semi_axis_x_m = axes.x;
  s.semi_axis_y_m = axes.y;
  s.dt_s = r.number("membrane.dt");
  s.duration_s = r.number("duration");
  s.frame_interval_s = r.number("membrane.frame_interval");
  s.coupling.scheme = *coupling::scheme_from_string(r.choice("membrane.scheme"));
  s.coupling.kernel = *coupling::kernel_from_string(r.choice("membrane.kernel"));
  m.refinement_cells = r.integers("refinement.cells");
  return m;
}

const ParameterTable* table_for_definition(std::string_view path) {
  if (path == "scenes/jellyfish.toml") return &jellyfish_scene();
  if (path == "experiments/driven-cavity.toml") return &driven_cavity_scene();
  if (path == "experiments/oval-membrane.toml") return &oval_membrane_scene();
  if (path == "experiments/taylor-green.toml") return &taylor_green_scene();
  if (path == "experiments/solver-cost.toml") return &solver_cost_scene();
  if (path == "experiments/integrator-order.toml") return &integrator_order_scene();
  if (path == "experiments/stages.toml") return &stages_scene();
  return nullptr;
}

}  // namespace jellysim::scene
