#include "jellysim/fluid3d/cavity_3d.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace jellysim::fluid3d {

namespace {

// max over the faces of |a − b| (every component, interior and boundary faces).
double largest_change(const Grid3d& g, const Velocity3d& a, const Velocity3d& b) {
  double m = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < g.n(2); ++k)
      for (int j = 0; j < g.n(1); ++j)
        for (int i = 0; i < g.n(0); ++i) {
          const std::size_t I = g.index(i, j, k);
          m = std::max(m, std::abs(a.c[static_cast<std::size_t>(c)][I] - b.c[static_cast<std::size_t>(c)][I]));
        }
  return m;
}

// Component c's value at face index `along` on the line through mid-span: the average of the two
// cell layers either side of z = span/2 (nz even). The line runs along axis `axis` (0 or 1).
std::vector<fluid::ProfilePoint> mid_span_line(const Grid3d& g, const Velocity3d& vel, int c, int axis, double wall_high) {
  const int other = 1 - axis, face = g.n(other) / 2, kz = g.n(2) / 2;
  std::vector<fluid::ProfilePoint> line{{0.0, 0.0}};
  for (int m = 0; m < g.n(axis); ++m) {
    Index3 a{}, b{};
    a[static_cast<std::size_t>(axis)] = b[static_cast<std::size_t>(axis)] = m;
    a[static_cast<std::size_t>(other)] = b[static_cast<std::size_t>(other)] = face;
    a[2] = kz - 1;
    b[2] = kz;
    const Field3d& q = vel.c[static_cast<std::size_t>(c)];
    line.push_back({(m + 0.5) * g.h(axis), 0.5 * (q[g.index(a[0], a[1], a[2])] + q[g.index(b[0], b[1], b[2])])});
  }
  line.push_back({g.size(axis), wall_high});
  return line;
}

double mirror_asymmetry(const Grid3d& g, const Velocity3d& vel) {
  double m = 0.0;
  for (int c = 0; c < 2; ++c)  // u and v are even about mid-span (w is odd)
    for (int k = 0; k < g.n(2); ++k)
      for (int j = 0; j < g.n(1); ++j)
        for (int i = 0; i < g.n(0); ++i) {
          const Field3d& q = vel.c[static_cast<std::size_t>(c)];
          m = std::max(m, std::abs(q[g.index(i, j, k)] - q[g.index(i, j, g.n(2) - 1 - k)]));
        }
  return m;
}

}  // namespace

CavityResult3d run_lid_driven_cavity_3d(const CavitySettings3d& s) {
  const int nz = 2 * static_cast<int>(std::lround(0.5 * s.cells * s.span));
  if (s.cells < 4 || s.cells % 2 != 0 || nz < 4) throw std::invalid_argument("3D cavity: an even number of cells (>= 4) is needed");
  const Grid3d g({s.cells, s.cells, nz}, {1.0, 1.0, s.span});
  FluidSettings3d f;
  f.boundaries = Boundaries3d::lid_driven_cavity(1.0);
  f.boundaries.axis[2].periodic = s.periodic_span;
  f.density_kg_per_m3 = 1.0;
  f.viscosity_m2_per_s = 1.0 / s.reynolds;
  f.safety_factor = s.safety_factor;
  f.convection = s.convection;
  f.threads = s.threads;
  auto solver = make_fluid_solver_3d(g, f);
  CavityResult3d r;
  Velocity3d previous(g);
  while (solver->state().time_s < s.max_time_s) {
    previous = solver->state().velocity;
    const double dt = solver->stable_time_step();
    solver->step(dt);
    ++r.steps;
    r.change_rate = largest_change(g, solver->state().velocity, previous) / dt;  // L = U = 1
    if (r.steps > 10 && r.change_rate < s.steady_tolerance) {
      r.steady = true;
      break;
    }
  }
  const Velocity3d& vel = solver->state().velocity;
  r.time_s = solver->state().time_s;
  r.centreline_u = mid_span_line(g, vel, 0, 1, 1.0);
  r.centreline_v = mid_span_line(g, vel, 1, 0, 0.0);
  r.symmetry_error = mirror_asymmetry(g, vel);
  r.max_divergence = max_divergence(g, vel);
  return r;
}

double interpolate_profile(const std::vector<fluid::ProfilePoint>& profile, double position) {
  const auto hi = std::lower_bound(profile.begin(), profile.end(), position,
                                   [](const fluid::ProfilePoint& p, double x) { return p.position < x; });
  if (hi == profile.begin()) return profile.front().velocity;
  if (hi == profile.end()) return profile.back().velocity;
  const auto lo = hi - 1;
  const double t = (position - lo->position) / (hi->position - lo->position);
  return lo->velocity + t * (hi->velocity - lo->velocity);
}

double largest_profile_difference(const std::vector<fluid::ProfilePoint>& profile,
                                  std::span<const fluid::ProfilePoint> reference) {
  double m = 0.0;
  for (const fluid::ProfilePoint& p : reference) m = std::max(m, std::abs(interpolate_profile(profile, p.position) - p.velocity));
  return m;
}

}  // namespace jellysim::fluid3d
