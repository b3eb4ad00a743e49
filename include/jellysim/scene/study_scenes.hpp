#pragma once
// The fluid and membrane studies whose whole definition is a parameter table: the lid-driven cavity
// (§8.1.3, Figure 8.7), Stockie & Wetton's oval membrane (Figures 8.8/8.9), the Taylor-Green
// accuracy study and the solver-cost study (ch. 4). Their experiments/*.toml files are generated
// from the tables (`jellysim scenes NAME`), like scenes/jellyfish.toml.
#include <cstdint>
#include <string_view>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/studies/oval_membrane.hpp"
#include "jellysim/studies/driven_cavity.hpp"
#include "jellysim/studies/taylor_green.hpp"
#include "jellysim/scene/parameters.hpp"

namespace jellysim::scene {

const ParameterTable& driven_cavity_scene();
const ParameterTable& oval_membrane_scene();
const ParameterTable& taylor_green_scene();
const ParameterTable& solver_cost_scene();

struct CavityScene {
  studies::DrivenCavitySettings cavity;
  bool figure_enabled = true;
  studies::CavityFigureSettings figure;
};
CavityScene read_cavity_scene(const config::Config& c);

struct MembraneScene {
  studies::OvalMembraneSettings membrane;
  std::vector<std::int64_t> refinement_cells;  ///< the same test on these grids
};
MembraneScene read_membrane_scene(const config::Config& c);
studies::TaylorGreenSettings read_taylor_green(const config::Config& c);
studies::SolverCostSettings read_solver_cost(const config::Config& c);

/// The table whose generated text is the built-in definition `path` (e.g. "scenes/jellyfish.toml"),
/// or nullptr when that definition is a plain file.
const ParameterTable* table_for_definition(std::string_view path);

}  // namespace jellysim::scene
