#pragma once
// The parameters the real-time viewer changes while the simulation runs (its sliders and the
// scripted `set NAME [INDEX] VALUE` events). Each is an entry of a parameter table: the scene's
// (frequency, gamma, viscosity), the render table's (noise weights) or the viewer's own controls
// (speed, stiffness), so the viewer allows exactly what a scene file allows, and its slider range
// is part of the entry.
#include <string>
#include <string_view>
#include <vector>

#include "jellysim/scene/parameters.hpp"

namespace jellysim::scene {

struct LiveParameter {
  std::string name;              ///< as scripts and sliders say it, e.g. "frequency", "noise.structural"
  const Parameter* parameter;    ///< its table entry: key, unit, allowed range, slider, description
  bool per_jellyfish = false;    ///< `set NAME INDEX VALUE` picks a jellyfish
};

/// The viewer's own controls: view.speed (simulated seconds per wall second) and view.stiffness
/// (a factor on every spring of one jellyfish).
const ParameterTable& viewer_controls();

const std::vector<LiveParameter>& live_parameters();
/// The live parameter `name`; throws InputError listing the known names.
const LiveParameter& live_parameter(std::string_view name);

/// "" when `value` is allowed for `name`, else "NAME must be in RANGE, got VALUE".
std::string check_live_value(const LiveParameter& p, double value);

/// The reference page's section on the live parameters (Markdown).
std::string live_parameters_markdown();

}  // namespace jellysim::scene
