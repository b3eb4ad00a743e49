#pragma once
// Shared by the jellyfish tests: the jellyfish scene on the thesis's coarse tank (80 cm, 60 × 60
// cells: fast, and where the scenes of these tests were laid out) with a TOML overlay, tracers off.
// The built-in (resolved) scene is tested in test_swim.cpp.
#include <string>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//experiments/experiment.hpp"
#include "jellysim/config/config.hpp"

namespace jellysim::experiments::testing {

inline config::Config scene_with(const std::string& overlay) {
  config::Config c = scene::builtin_jellyfish_scene();
  c.merge(config::Config::parse(embedded_text("scenes/jellyfish-thesis.toml"), "scenes/jellyfish-thesis.toml"));
  c.set("tank.tracers_per_side=0");
  c.merge(config::Config::parse(overlay, "test scene"));
  return c;
}

}  // namespace jellysim::experiments::testing
