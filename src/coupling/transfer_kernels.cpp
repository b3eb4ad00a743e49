#include "jellysim/coupling/transfer_kernels.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jellysim::coupling {

std::string_view to_string(Kernel k) { return k == Kernel::bilinear ? "bilinear" : "peskin4"; }

std::optional<Kernel> kernel_from_string(std::string_view name) {
  if (name == "bilinear") return Kernel::bilinear;
  if (name == "peskin4") return Kernel::peskin4;
  return std::nullopt;
}

int kernel_radius(Kernel k) { return k == Kernel::bilinear ? 1 : 2; }

// Peskin (2002), eq. 6.27: the 4-point function built from the zeroth and first moment conditions
// and Σφ² = 3/8.
double kernel_weight(Kernel k, double r) {
  const double a = std::abs(r);
  if (k == Kernel::bilinear) return a < 1.0 ? 1.0 - a : 0.0;
  if (a < 1.0) return (3.0 - 2.0 * a + std::sqrt(1.0 + 4.0 * a - 4.0 * a * a)) / 8.0;
  if (a < 2.0) return (5.0 - 2.0 * a - std::sqrt(std::max(0.0, -7.0 + 12.0 * a - 4.0 * a * a))) / 8.0;
  return 0.0;
}

Stencil make_stencil(const fluid::Field& field, Vec2 p, Kernel k, Periodicity periodic) {
  const fluid::MacGrid& g = field.grid();
  const fluid::Staggering st = field.staggering();
  // Continuous sample coordinates: sample (i, j) sits at grid coordinates (i + st.x, j + st.y).
  const Vec2 gc = g.grid_from_world(p);
  const double fx = gc.x - st.x, fy = gc.y - st.y;
  const int r = kernel_radius(k);
  Stencil s;
  s.width = 2 * r;
  s.i0 = static_cast<int>(std::floor(fx)) - r + 1;
  s.j0 = static_cast<int>(std::floor(fy)) - r + 1;
  s.period_x = periodic.x ? g.nx : 0;
  s.period_y = periodic.y ? g.ny : 0;
  for (int a = 0; a < s.width; ++a) {
    const int i = s.i0 + a, j = s.j0 + a;
    s.wx[a] = (periodic.x || (i >= -1 && i <= field.count_x())) ? kernel_weight(k, fx - i) : 0.0;
    s.wy[a] = (periodic.y || (j >= -1 && j <= field.count_y())) ? kernel_weight(k, fy - j) : 0.0;
  }
  return s;
}

double interpolate(const fluid::Field& field, const Stencil& s) {
  double sum = 0.0;
  for (int b = 0; b < s.width; ++b) {
    if (s.wy[b] == 0.0) continue;
    for (int a = 0; a < s.width; ++a) {
      if (s.wx[a] == 0.0) continue;
      sum += s.wx[a] * s.wy[b] * field(s.index_x(a), s.index_y(b));
    }
  }
  return sum;
}

void spread(fluid::Field& field, const Stencil& s, double value) {
  for (int b = 0; b < s.width; ++b) {
    if (s.wy[b] == 0.0) continue;
    for (int a = 0; a < s.width; ++a) {
      if (s.wx[a] == 0.0) continue;
      field(s.index_x(a), s.index_y(b)) += s.wx[a] * s.wy[b] * value;
    }
  }
}

void interpolate_velocities(const fluid::Velocity& vel, std::span<const Vec2> points, Kernel k, std::span<Vec2> out,
                            Periodicity periodic) {
  for (std::size_t p = 0; p < points.size(); ++p) {
    out[p] = {interpolate(vel.u, make_stencil(vel.u, points[p], k, periodic)),
              interpolate(vel.v, make_stencil(vel.v, points[p], k, periodic))};
  }
}

void spread_forces(std::span<const Vec2> points, std::span<const Vec2> forces, Kernel k, double density_kg_per_m3,
                   fluid::FaceAccelerations& acc, Periodicity periodic) {
  const fluid::MacGrid& g = acc.u.grid();
  const double to_acceleration = 1.0 / (density_kg_per_m3 * g.dx() * g.dy());  // eq. 4.19
  for (std::size_t p = 0; p < points.size(); ++p) {
    spread(acc.u, make_stencil(acc.u, points[p], k, periodic), forces[p].x * to_acceleration);
    spread(acc.v, make_stencil(acc.v, points[p], k, periodic), forces[p].y * to_acceleration);
  }
}

namespace {

/// Sample index a along x of a stencil folded across the axis (x = 0): a face-centred (normal)
/// sample −i is face i with sign −1, a cell-centred sample −1 − i is cell i with sign +1.
struct Folded {
  int i;
  double sign;
};
Folded fold_across_axis(int i, bool normal) {
  if (i >= 0) return {i, 1.0};
  return normal ? Folded{-i, -1.0} : Folded{-1 - i, 1.0};
}

/// Calls visit(i, j, weight) for every sample of the field the ring at p touches, folded.
template <class Visit>
void for_each_folded_sample(const fluid::Field& field, Vec2 p, Kernel k, bool normal, bool periodic_z, Visit&& visit) {
  const Stencil s = make_stencil(field, p, k, Periodicity{false, periodic_z});
  for (int b = 0; b < s.width; ++b) {
    if (s.wy[b] == 0.0) continue;
    for (int a = 0; a < s.width; ++a) {
      // make_stencil zeroes samples beyond the ghost layer; across the axis they are images.
      const int i = s.i0 + a;
      const double wx = i < -1 ? kernel_weight(k, field.grid().grid_from_world(p).x - field.staggering().x - i) : s.wx[a];
      if (wx == 0.0) continue;
      const Folded f = fold_across_axis(i, normal);
      visit(f.i, s.index_y(b), f.sign * wx * s.wy[b]);
    }
  }
}

}  // namespace

void interpolate_velocities_axisymmetric(const fluid::Velocity& vel, std::span<const Vec2> points, Kernel k,
                                         std::span<Vec2> out, bool periodic_z) {
  for (std::size_t p = 0; p < points.size(); ++p) {
    double ur = 0.0, uz = 0.0;
    for_each_folded_sample(vel.u, points[p], k, true, periodic_z, [&](int i, int j, double w) { ur += w * vel.u(i, j); });
    for_each_folded_sample(vel.v, points[p], k, false, periodic_z, [&](int i, int j, double w) { uz += w * vel.v(i, j); });
    out[p] = {ur, uz};
  }
}

void spread_forces_axisymmetric(std::span<const Vec2> points, std::span<const Vec2> forces, Kernel k,
                                double density_kg_per_m3, fluid::FaceAccelerations& acc, bool periodic_z) {
  const fluid::MacGrid& g = acc.u.grid();
  const double volume = 2.0 * std::numbers::pi * g.dx() * g.dy();  // per unit radius
  const double to_acceleration = 1.0 / (density_kg_per_m3 * volume);
  for (std::size_t p = 0; p < points.size(); ++p) {
    for_each_folded_sample(acc.u, points[p], k, true, periodic_z, [&](int i, int j, double w) {
      if (i == 0) return;  // the axis face: u_r = 0 there
      acc.u(i, j) += forces[p].x * w * to_acceleration / (i * g.dx());
    });
    for_each_folded_sample(acc.v, points[p], k, false, periodic_z, [&](int i, int j, double w) {
      acc.v(i, j) += forces[p].y * w * to_acceleration / ((i + 0.5) * g.dx());
    });
  }
}

}  // namespace jellysim::coupling
