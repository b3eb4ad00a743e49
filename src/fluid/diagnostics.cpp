#include "jellysim/fluid/diagnostics.hpp"

#include <cmath>

namespace jellysim::fluid {

Field vorticity_at_nodes(const Velocity& vel) {
  const MacGrid& g = vel.u.grid();
  Field w(g, kNodes);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i)
      w(i, j) = (vel.v(i, j) - vel.v(i - 1, j)) / g.dx() - (vel.u(i, j) - vel.u(i, j - 1)) / g.dy();
  return w;
}

Field vorticity_at_centres(const Velocity& vel) {
  const MacGrid& g = vel.u.grid();
  const Field w = vorticity_at_nodes(vel);
  Field c(g, kCellCentres);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) c(i, j) = 0.25 * (w(i, j) + w(i + 1, j) + w(i, j + 1) + w(i + 1, j + 1));
  return c;
}

Field stream_function_at_nodes(const Velocity& vel) {
  const MacGrid& g = vel.u.grid();
  Field psi(g, kNodes);
  for (int i = 0; i < g.nx; ++i) psi(i + 1, 0) = psi(i, 0) - vel.v(i, 0) * g.dx();
  for (int j = 0; j < g.ny; ++j)  // row by row: each column's sum, in the same order
    for (int i = 0; i <= g.nx; ++i) psi(i, j + 1) = psi(i, j) + vel.u(i, j) * g.dy();
  return psi;
}

Vec2 velocity_at_centre(const Velocity& vel, int i, int j) {
  return {0.5 * (vel.u(i, j) + vel.u(i + 1, j)), 0.5 * (vel.v(i, j) + vel.v(i, j + 1))};
}

Field speed_at_centres(const Velocity& vel) {
  const MacGrid& g = vel.u.grid();
  Field s(g, kCellCentres);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) s(i, j) = norm(velocity_at_centre(vel, i, j));
  return s;
}

namespace {
template <class Fn>
void for_distinct_faces(const Velocity& vel, bool periodic_x, bool periodic_y, Fn&& fn) {
  const MacGrid& g = vel.u.grid();
  const int u_end = periodic_x ? g.nx : g.nx + 1;  // u(nx) repeats u(0) when periodic
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < u_end; ++i) fn(0, vel.u(i, j));
  const int v_end = periodic_y ? g.ny : g.ny + 1;
  for (int j = 0; j < v_end; ++j)
    for (int i = 0; i < g.nx; ++i) fn(1, vel.v(i, j));
}
}  // namespace

Vec2 total_momentum(const Velocity& vel, bool periodic_x, bool periodic_y) {
  const MacGrid& g = vel.u.grid();
  Vec2 m{};
  for_distinct_faces(vel, periodic_x, periodic_y, [&](int c, double value) { (c == 0 ? m.x : m.y) += value; });
  return m * (g.dx() * g.dy());
}

double kinetic_energy(const Velocity& vel, bool periodic_x, bool periodic_y) {
  const MacGrid& g = vel.u.grid();
  double e = 0.0;
  for_distinct_faces(vel, periodic_x, periodic_y, [&](int, double value) { e += value * value; });
  return 0.5 * e * g.dx() * g.dy();
}

}  // namespace jellysim::fluid
