#pragma once
// The parameters a user changes while the simulation runs, and the one place that passes them on
// to the simulation (the sliders and scripted `set` events both come here).
#include <optional>
#include <string>
#include <vector>

#include "jellysim/geometry/surface_noise.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"

namespace jellysim::viewer {

struct JellyfishParams {
  double frequency_hz = 0.7;
  double gamma = 0.56;
  double stiffness_scale = 1.0;
  std::optional<Vec2> steer_target_m;
};

struct LiveParams {
  std::vector<JellyfishParams> jellyfish;
  double viscosity_m2_per_s = 1.304e-5;
  geometry::NoiseSettings noise;
  double speed = 1.0;  ///< target simulated seconds per wall second

  /// The scene's values.
  static LiveParams from(const jellyfish::SwimSettings& settings, const geometry::NoiseSettings& noise, double speed);
};

/// "" when `set name [index] value` is allowed (the ranges are scene/live_parameters.hpp's) for `jellyfish_count` jellyfish, else why not.
std::string check_param(const std::string& name, int index, double value, std::size_t jellyfish_count);

/// Applies one parameter to `params` and, for simulation parameters, to `sim`; throws
/// InputError when check_param does not allow it.
void apply_param(const std::string& name, int index, double value, LiveParams& params,
                 jellyfish::SwimSimulation& sim);

/// Passes every simulation parameter of `params` to `sim` (after a reset keeps the user's values).
void apply_all(const LiveParams& params, jellyfish::SwimSimulation& sim);

}  // namespace jellysim::viewer
