#include "jellysim/fluid3d/boundary_3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace jellysim::fluid3d {

Boundaries3d Boundaries3d::closed_box() { return {}; }

Boundaries3d Boundaries3d::periodic_box() {
  Boundaries3d b;
  for (auto& a : b.axis) a.periodic = true;
  return b;
}

Boundaries3d Boundaries3d::duct(int flow_axis) {
  Boundaries3d b;
  b.axis.at(static_cast<std::size_t>(flow_axis)).periodic = true;
  return b;
}

Boundaries3d Boundaries3d::lid_driven_cavity(double lid_speed_m_per_s) {
  Boundaries3d b;
  b.axis[1].wall_velocity[1] = {lid_speed_m_per_s, 0.0, 0.0};
  return b;
}

Boundaries3d Boundaries3d::quarter() const {
  Boundaries3d b = *this;
  b.axis[0].symmetry[0] = b.axis[2].symmetry[0] = true;
  b.axis[0].wall_velocity[0] = b.axis[2].wall_velocity[0] = Vec3{};
  return b;
}

void Boundaries3d::validate() const {
  for (std::size_t d = 0; d < 3; ++d)
    for (std::size_t side = 0; side < 2; ++side) {
      const Vec3& u = axis[d].wall_velocity[side];
      if (u[d] != 0.0)
        throw std::invalid_argument("Boundaries3d: a wall normal to axis " + std::to_string(d) +
                                    " may only slide in its plane (normal velocity " + std::to_string(u[d]) + ")");
      if (axis[d].symmetry[side] && (axis[d].periodic || u != Vec3{}))
        throw std::invalid_argument("Boundaries3d: a mirror plane normal to axis " + std::to_string(d) +
                                    " can neither move nor sit on a periodic axis");
    }
}

double Boundaries3d::largest_wall_speed(int c) const {
  double m = 0.0;
  for (const AxisBoundary3d& a : axis)
    if (!a.periodic)
      for (const Vec3& u : a.wall_velocity) m = std::max(m, std::abs(u[static_cast<std::size_t>(c)]));
  return m;
}

namespace {

// Calls line(base) for the sample at index 0 along axis d of every line parallel to d, over the
// whole padded range of the other two axes.
template <class Line>
void for_each_line(const Grid3d& g, int d, Line&& line) {
  const int a = (d + 1) % 3, b = (d + 2) % 3;
  for (int ib = -Grid3d::ghosts; ib <= g.n(b) + Grid3d::ghosts; ++ib)
    for (int ia = -Grid3d::ghosts; ia <= g.n(a) + Grid3d::ghosts; ++ia) {
      Index3 idx{};
      idx[static_cast<std::size_t>(a)] = ia;
      idx[static_cast<std::size_t>(b)] = ib;
      line(g.index(idx[0], idx[1], idx[2]));
    }
}

// Ghosts along axis d of a field whose samples along d are faces (c == d): the boundary faces 0
// and n carry the normal wall velocity 0; ghosts are odd mirror images, q(−m) = −q(m).
void fill_normal_axis(const Grid3d& g, bool periodic, int d, Field3d& q) {
  const std::ptrdiff_t s = static_cast<std::ptrdiff_t>(g.stride(d));
  const int n = g.n(d);
  for_each_line(g, d, [&](std::size_t base) {
    double* l = q.data() + base;
    if (periodic) {
      for (int m = 0; m <= 2; ++m) l[(n + m) * s] = l[m * s];
      for (int m = 1; m <= 2; ++m) l[-m * s] = l[(n - m) * s];
    } else {
      l[0] = 0.0;
      l[n * s] = 0.0;
      for (int m = 1; m <= 2; ++m) {
        l[-m * s] = -l[m * s];
        l[(n + m) * s] = -l[(n - m) * s];
      }
    }
  });
}

// Ghosts along axis d of a field whose samples along d are cell centres (c ≠ d): wrapped, or
// mirrored about the wall with the wall's tangential velocity, q(−1 − m) = 2U − q(m).
void fill_tangential_axis(const Grid3d& g, const AxisBoundary3d& ab, int c, int d, Field3d& q) {
  const std::ptrdiff_t s = static_cast<std::ptrdiff_t>(g.stride(d));
  const int n = g.n(d);
  const double lo = 2.0 * ab.wall_velocity[0][static_cast<std::size_t>(c)];
  const double hi = 2.0 * ab.wall_velocity[1][static_cast<std::size_t>(c)];
  for_each_line(g, d, [&](std::size_t base) {
    double* l = q.data() + base;
    if (ab.periodic) {
      for (int m = 0; m <= 2; ++m) l[(n + m) * s] = l[m * s];
      for (int m = 1; m <= 2; ++m) l[-m * s] = l[(n - m) * s];
    } else {  // a mirror plane copies (even image), a wall mirrors about its velocity (odd image)
      for (int m = 0; m <= 1; ++m) l[(-1 - m) * s] = ab.symmetry[0] ? l[m * s] : lo - l[m * s];
      for (int m = 0; m <= 2; ++m) l[(n + m) * s] = ab.symmetry[1] ? l[(n - 1 - m) * s] : hi - l[(n - 1 - m) * s];
    }
  });
}

}  // namespace

void apply_velocity_boundaries(const Grid3d& g, const Boundaries3d& b, int c, Field3d& q) {
  for (int d = 0; d < 3; ++d) {
    const AxisBoundary3d& ab = b.axis[static_cast<std::size_t>(d)];
    if (d == c)
      fill_normal_axis(g, ab.periodic, d, q);
    else
      fill_tangential_axis(g, ab, c, d, q);
  }
}

void apply_velocity_boundaries(const Grid3d& g, const Boundaries3d& b, Velocity3d& vel) {
  for (int c = 0; c < 3; ++c) apply_velocity_boundaries(g, b, c, vel.c[static_cast<std::size_t>(c)]);
}

void apply_pressure_boundaries(const Grid3d& g, const Boundaries3d& b, Field3d& p) {
  for (int d = 0; d < 3; ++d) {
    const std::ptrdiff_t s = static_cast<std::ptrdiff_t>(g.stride(d));
    const int n = g.n(d);
    const bool periodic = b.axis[static_cast<std::size_t>(d)].periodic;
    for_each_line(g, d, [&](std::size_t base) {
      double* l = p.data() + base;
      for (int m = 1; m <= 2; ++m) {
        l[-m * s] = periodic ? l[(n - m) * s] : l[(m - 1) * s];
        l[(n - 1 + m) * s] = periodic ? l[(m - 1) * s] : l[(n - m) * s];
      }
    });
  }
}

std::array<int, 2> unknown_range(const Grid3d& g, const Boundaries3d& b, int c, int d) {
  const bool periodic = b.axis[static_cast<std::size_t>(d)].periodic;
  return {c == d && !periodic ? 1 : 0, g.n(d)};
}

}  // namespace jellysim::fluid3d
