#include "live_params.hpp"

#include <cmath>
#include <sstream>

#include "jellysim/core/errors.hpp"
#include "jellysim/scene/live_parameters.hpp"

namespace jellysim::viewer {

LiveParams LiveParams::from(const jellyfish::SwimSettings& settings, const geometry::NoiseSettings& noise,
                            double speed) {
  LiveParams p;
  for (const jellyfish::JellyfishSpec& spec : settings.school) {
    JellyfishParams j;
    j.frequency_hz = spec.frequency_hz;
    j.gamma = spec.gamma;
    if (spec.steering) j.steer_target_m = spec.steer_target_m;
    p.jellyfish.push_back(j);
  }
  p.viscosity_m2_per_s = settings.tank.viscosity_m2_per_s;
  p.noise = noise;
  p.speed = speed;
  return p;
}

std::string check_param(const std::string& name, int index, double value, std::size_t jellyfish_count) {
  const scene::LiveParameter& p = scene::live_parameter(name);
  if (p.per_jellyfish && (index < 0 || static_cast<std::size_t>(index) >= jellyfish_count)) {
    return "jellyfish " + std::to_string(index) + " does not exist (the scene has " +
           std::to_string(jellyfish_count) + ")";
  }
  return scene::check_live_value(p, value);
}

void apply_param(const std::string& name, int index, double value, LiveParams& params,
                 jellyfish::SwimSimulation& sim) {
  const std::string why = check_param(name, index, value, sim.jellyfish_count());
  if (!why.empty()) throw InputError(why);
  const auto i = static_cast<std::size_t>(index);
  if (name == "frequency") {
    params.jellyfish[i].frequency_hz = value;
    sim.set_frequency(i, value);
  } else if (name == "gamma") {
    params.jellyfish[i].gamma = value;
    sim.set_gamma(i, value);
  } else if (name == "stiffness") {
    params.jellyfish[i].stiffness_scale = value;
    sim.set_stiffness_scale(i, value);
  } else if (name == "viscosity") {
    params.viscosity_m2_per_s = value;
    sim.set_viscosity(value);
  } else if (name == "speed") {
    params.speed = value;
  } else if (name == "noise.structural") {
    params.noise.structural_weight = value;
  } else if (name == "noise.compression") {
    params.noise.compression_weight = value;
  } else if (name == "noise.unstructured") {
    params.noise.unstructured_weight = value;
  }
}

void apply_all(const LiveParams& params, jellyfish::SwimSimulation& sim) {
  for (std::size_t i = 0; i < params.jellyfish.size() && i < sim.jellyfish_count(); ++i) {
    const JellyfishParams& j = params.jellyfish[i];
    sim.set_frequency(i, j.frequency_hz);
    sim.set_gamma(i, j.gamma);
    sim.set_stiffness_scale(i, j.stiffness_scale);
    sim.set_steer_target(i, j.steer_target_m);
  }
  sim.set_viscosity(params.viscosity_m2_per_s);
}

}  // namespace jellysim::viewer
