#pragma once
// Two chapter 8 studies whose whole definition is a parameter table: the lid-driven cavity
// (§8.1.3, Figure 8.7; experiments/driven-cavity.toml) and Stockie & Wetton's oval membrane
// (Figures 8.8/8.9; experiments/oval-membrane.toml). Both files are generated from their tables
// (`jellysim scenes NAME`), like scenes/jellyfish.toml.
#include <string_view>
#include <vector>

#include "jellysim/config/config.hpp"
#include "jellysim/coupling/oval_membrane.hpp"
#include "jellysim/fluid/experiments_cavity.hpp"
#include "jellysim/scene/parameters.hpp"

namespace jellysim::scene {

const ParameterTable& driven_cavity_scene();
const ParameterTable& oval_membrane_scene();

struct CavityScene {
  fluid::DrivenCavitySettings cavity;
  bool figure_enabled = true;
  fluid::CavityFigureSettings figure;
};
CavityScene read_cavity_scene(const io::Config& c);

struct MembraneScene {
  coupling::OvalMembraneSettings membrane;
  std::vector<std::int64_t> refinement_cells;  ///< the same test on these grids
};
MembraneScene read_membrane_scene(const io::Config& c);

/// The table whose generated text is the built-in definition `path` (e.g. "scenes/jellyfish.toml"),
/// or nullptr when that definition is a plain file.
const ParameterTable* table_for_definition(std::string_view path);

}  // namespace jellysim::scene
