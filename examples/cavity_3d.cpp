// The 3D lid-driven cavity to steady state (issue 40; docs/three-d.md), through the public headers
// of jellysim::fluid3d only. Writes the centrelines as CSV and prints the run's figures:
//   cavity_3d [CELLS [RE [SPAN [periodic]]]] > centrelines.csv
// CELLS cells along x and y (even, default 32), RE the Reynolds number (default 100), SPAN the depth
// along z in cavity sides (default 1: the cube), "periodic" makes z periodic (the 2D cavity,
// extruded). With Re 100, 400 or 1000 the largest differences to Ghia et al.'s 2D centrelines are
// printed too: a check for the periodic span, only a sanity check for a walled one (the side walls
// slow the flow). The cube (SPAN 1, walled) at Re 1000 is compared with Albensoeder & Kuhlmann's
// (2005) published 3D centrelines.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "jellysim/fluid3d/cavity_3d.hpp"

namespace {

using namespace jellysim;

void print_ghia_differences(const fluid3d::CavityResult3d& r, double re) {
  std::span<const fluid::ProfilePoint> u, v;
  if (re == 100.0) u = fluid::kGhiaRe100CentrelineU, v = fluid::kGhiaRe100CentrelineV;
  if (re == 400.0) u = fluid::kGhiaRe400CentrelineU, v = fluid::kGhiaRe400CentrelineV;
  if (re == 1000.0) u = fluid::kGhiaRe1000CentrelineU, v = fluid::kGhiaRe1000CentrelineV;
  if (u.empty()) return;
  std::fprintf(stderr, "largest difference to Ghia et al. (2D, Re %g): u %.4f, v %.4f\n", re,
               fluid3d::largest_profile_difference(r.centreline_u, u), fluid3d::largest_profile_difference(r.centreline_v, v));
}

/// The walled cube at Re 1000 against Albensoeder & Kuhlmann (2005), Tables 5 and 6 (3D, published).
void print_albensoeder_kuhlmann_differences(const fluid3d::CavitySettings3d& s, const fluid3d::CavityResult3d& r) {
  if (s.reynolds != 1000.0 || s.span != 1.0 || s.periodic_span) return;
  std::fprintf(stderr, "largest difference to Albensoeder & Kuhlmann (2005, the cube at Re 1000): u %.4f, v %.4f\n",
               fluid3d::largest_profile_difference(r.centreline_u, fluid3d::kAlbensoederKuhlmannRe1000CentrelineU),
               fluid3d::largest_profile_difference(r.centreline_v, fluid3d::kAlbensoederKuhlmannRe1000CentrelineV));
}

}  // namespace

int main(int argc, char** argv) {
  fluid3d::CavitySettings3d s;
  s.threads = 0;
  if (argc > 1) s.cells = std::atoi(argv[1]);
  if (argc > 2) s.reynolds = std::atof(argv[2]);
  if (argc > 3) s.span = std::atof(argv[3]);
  if (argc > 4) s.periodic_span = std::string(argv[4]) == "periodic";
  const fluid3d::CavityResult3d r = fluid3d::run_lid_driven_cavity_3d(s);
  double umin = 1.0, vmin = 1.0, vmax = -1.0, y_umin = 0.0, x_vmin = 0.0, x_vmax = 0.0;
  for (const auto& p : r.centreline_u)
    if (p.velocity < umin) umin = p.velocity, y_umin = p.position;
  for (const auto& p : r.centreline_v) {
    if (p.velocity < vmin) vmin = p.velocity, x_vmin = p.position;
    if (p.velocity > vmax) vmax = p.velocity, x_vmax = p.position;
  }
  std::fprintf(stderr, "%d cells, Re %g, span %g%s: %s at t = %.2f s after %ld steps (change rate %.2e)\n", s.cells,
               s.reynolds, s.span, s.periodic_span ? " (periodic)" : "", r.steady ? "steady" : "NOT steady", r.time_s,
               r.steps, r.change_rate);
  std::fprintf(stderr, "u_min %.4f at y = %.4f; v_min %.4f at x = %.4f; v_max %.4f at x = %.4f\n", umin, y_umin, vmin,
               x_vmin, vmax, x_vmax);
  std::fprintf(stderr, "mid-span asymmetry %.1e m/s, max |div u| %.1e 1/s\n", r.symmetry_error, r.max_divergence);
  print_ghia_differences(r, s.reynolds);
  print_albensoeder_kuhlmann_differences(s, r);
  std::printf("line,position,velocity\n");
  for (const auto& p : r.centreline_u) std::printf("u_vertical,%.6f,%.6f\n", p.position, p.velocity);
  for (const auto& p : r.centreline_v) std::printf("v_horizontal,%.6f,%.6f\n", p.position, p.velocity);
  return r.steady ? 0 : 1;
}
