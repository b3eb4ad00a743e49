// jellysim as a library: a tank of water and the built-in 4 cm bell, built in code through the
// public headers and linked against the physics libraries only (jellysim::jellyfish and what it
// needs: no scene files, no pictures, no OpenGL). One contraction cycle; prints how far it swam.
//   build/release/examples/swim_in_a_tank
#include <cstdio>

#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"

int main() {
  using namespace jellysim;
  jellyfish::SwimSettings settings;  // the built-in scene's tank (24 x 48 cm), fluid, coupling, limits
  settings.tank.tracers_per_side = 0;
  settings.tank.cells_x = 96;   // a preview grid, 16 cells across the bell, 60 times cheaper than the
  settings.tank.cells_y = 192;  // built-in 384 x 768 (on which the first cycle swims 1.65 cm)
  jellyfish::JellyfishSpec bell;  // Figure 8.21's bell at the built-in position
  bell.max_spacing_m = 0.5 * settings.tank.width_m / settings.tank.cells_x;  // markers half a cell apart
  bell.frequency_hz = 0.7;
  settings.school.push_back(bell);
  settings.duration_s = 1.0 / bell.frequency_hz;  // one contraction cycle

  jellyfish::SwimSimulation sim(settings);
  const double start_m = jellyfish::measure_bell(sim.jellyfish().umbrella_points()).centroid.y;
  const jellyfish::SwimRunStats stats = sim.run([](const jellyfish::SwimSimulation&) { return std::string(); });
  if (!stats.failure.empty()) {
    std::fprintf(stderr, "the run failed: %s\n", stats.failure.c_str());
    return 1;
  }
  const double end_m = jellyfish::measure_bell(sim.jellyfish().umbrella_points()).centroid.y;
  std::printf("one cycle: %ld steps, %ld Krylov iterations, swam %.2f cm (%.2f bell heights)\n", stats.steps,
              stats.krylov_iterations, 100.0 * (end_m - start_m), (end_m - start_m) / bell.height_m);
  return end_m > start_m ? 0 : 1;
}
