#include "advection_3d.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::fluid3d {

double sample_face_field(const Grid3d& g, const Boundaries3d& b, int c, const Field3d& q, Vec3 x, double* lo, double* hi) {
  Index3 i0{};
  Vec3 t{};
  for (int d = 0; d < 3; ++d) {
    const std::size_t dd = static_cast<std::size_t>(d);
    const double length = g.size(d);
    double r = x[dd] - g.origin()[dd];
    if (b.axis[dd].periodic)
      r -= length * std::floor(r / length);  // into [0, L)
    else
      r = std::clamp(r, 0.0, length);
    // Sample m of the field sits at (m + offset)·h along d: offset 0 on its own axis, ½ across.
    const double s = std::min(r / g.h(d) - (d == c ? 0.0 : 0.5), static_cast<double>(g.n(d)));
    i0[dd] = static_cast<int>(std::floor(s));
    t[dd] = s - i0[dd];
  }
  double value = 0.0, smallest = q[g.index(i0[0], i0[1], i0[2])], largest = smallest;
  for (int corner = 0; corner < 8; ++corner) {
    const int ox = corner & 1, oy = (corner >> 1) & 1, oz = corner >> 2;
    const double sample = q[g.index(i0[0] + ox, i0[1] + oy, i0[2] + oz)];
    value += (ox ? t[0] : 1.0 - t[0]) * (oy ? t[1] : 1.0 - t[1]) * (oz ? t[2] : 1.0 - t[2]) * sample;
    smallest = std::min(smallest, sample);
    largest = std::max(largest, sample);
  }
  if (lo != nullptr) *lo = smallest;
  if (hi != nullptr) *hi = largest;
  return value;
}

Vec3 sample_velocity(const Grid3d& g, const Boundaries3d& b, const Velocity3d& vel, const Vec3& x) {
  return {sample_face_field(g, b, 0, vel.c[0], x), sample_face_field(g, b, 1, vel.c[1], x),
          sample_face_field(g, b, 2, vel.c[2], x)};
}

Vec3 trace_midpoint(const Grid3d& g, const Boundaries3d& b, const Velocity3d& vel, const Vec3& x, double dt) {
  const Vec3 u1 = sample_velocity(g, b, vel, x);
  const Vec3 mid{x[0] + 0.5 * dt * u1[0], x[1] + 0.5 * dt * u1[1], x[2] + 0.5 * dt * u1[2]};
  const Vec3 u2 = sample_velocity(g, b, vel, mid);
  return {x[0] + dt * u2[0], x[1] + dt * u2[1], x[2] + dt * u2[2]};
}

}  // namespace jellysim::fluid3d
