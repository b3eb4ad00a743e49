#pragma once
// Shared by the jellyfish tests: the default scene with a TOML overlay, tracers off.
#include <string>

#include "experiments/experiment.hpp"
#include "io/config.hpp"

namespace jellysim::experiments::testing {

inline io::Config scene_with(const std::string& overlay) {
  io::Config c = default_config(find_experiment("jellyfish"));
  c.set("tank.tracers_per_side=0");
  c.merge(io::Config::parse(overlay, "test scene"));
  return c;
}

}  // namespace jellysim::experiments::testing
