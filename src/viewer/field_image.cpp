#include "jellysim/viewer/field_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace jellysim::viewer {

namespace {

using Colour = std::array<double, 3>;

Colour mix(const Colour& a, const Colour& b, double t) {
  return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

/// Piecewise-linear colour map through evenly spaced stops, s ∈ [0, 1].
template <std::size_t N>
Colour ramp(const std::array<Colour, N>& stops, double s) {
  const double x = std::clamp(s, 0.0, 1.0) * static_cast<double>(N - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(x), N - 2);
  return mix(stops[k], stops[k + 1], x - static_cast<double>(k));
}

/// Deep water blue → teal → yellow → white.
Colour speed_colour(double s) {
  static constexpr std::array<Colour, 4> stops{
      Colour{0.02, 0.06, 0.16}, Colour{0.05, 0.45, 0.55}, Colour{0.95, 0.85, 0.30}, Colour{1.0, 1.0, 0.95}};
  return ramp(stops, s);
}

/// Blue (clockwise) → dark water → red (counter-clockwise), s ∈ [−1, 1].
Colour vorticity_colour(double s) {
  static constexpr std::array<Colour, 5> stops{Colour{0.55, 0.80, 1.0}, Colour{0.10, 0.30, 0.75},
                                               Colour{0.03, 0.06, 0.14}, Colour{0.80, 0.20, 0.10},
                                               Colour{1.0, 0.80, 0.50}};
  return ramp(stops, 0.5 * (s + 1.0));
}

struct CellVelocities {
  int nx, ny;
  std::vector<double> u, v;
  double at_u(int i, int j) const { return u[index(i, j)]; }
  double at_v(int i, int j) const { return v[index(i, j)]; }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(std::clamp(j, 0, ny - 1)) * static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(std::clamp(i, 0, nx - 1));
  }
};

CellVelocities cell_velocities(const fluid::FlowState& flow) {
  const int nx = flow.grid.nx, ny = flow.grid.ny;
  CellVelocities c{nx, ny, std::vector<double>(static_cast<std::size_t>(nx) * ny),
                   std::vector<double>(static_cast<std::size_t>(nx) * ny)};
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      c.u[c.index(i, j)] = 0.5 * (flow.velocity.u(i, j) + flow.velocity.u(i + 1, j));
      c.v[c.index(i, j)] = 0.5 * (flow.velocity.v(i, j) + flow.velocity.v(i, j + 1));
    }
  }
  return c;
}

/// The in-plane cell-centred velocity of plane k, the whole width when mirrored (u odd in x).
CellVelocities plane_velocities(const fluid3d::FlowState3d& flow, int k, bool mirror_x) {
  const fluid3d::Grid3d& g = flow.grid;
  const int n = g.n(0), nx = mirror_x ? 2 * n : n, ny = g.n(1);
  CellVelocities c{nx, ny, std::vector<double>(static_cast<std::size_t>(nx) * ny),
                   std::vector<double>(static_cast<std::size_t>(nx) * ny)};
  const fluid3d::Field3d& u = flow.velocity.c[0];
  const fluid3d::Field3d& v = flow.velocity.c[1];
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < n; ++i) {
      const double uc = 0.5 * (u[g.index(i, j, k)] + u[g.index(i + 1, j, k)]);
      const double vc = 0.5 * (v[g.index(i, j, k)] + v[g.index(i, j + 1, k)]);
      const int at = mirror_x ? n + i : i;
      c.u[c.index(at, j)] = uc, c.v[c.index(at, j)] = vc;
      if (mirror_x) c.u[c.index(n - 1 - i, j)] = -uc, c.v[c.index(n - 1 - i, j)] = vc;
    }
  return c;
}

/// Speed or ω_z per cell of a plane's velocities (central differences; at the edges the index is
/// clamped, a half-width one-sided difference).
std::vector<double> plane_values(const CellVelocities& c, double dx, double dy, FieldShown shown) {
  std::vector<double> values(c.u.size());
  for (int j = 0; j < c.ny; ++j)
    for (int i = 0; i < c.nx; ++i) {
      double value = std::hypot(c.at_u(i, j), c.at_v(i, j));
      if (shown == FieldShown::vorticity)
        value = (c.at_v(i + 1, j) - c.at_v(i - 1, j)) / (2.0 * dx) - (c.at_u(i, j + 1) - c.at_u(i, j - 1)) / (2.0 * dy);
      values[c.index(i, j)] = value;
    }
  return values;
}

std::uint8_t byte(double x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); }

/// The values coloured with the range `range` (≤ 0: their own largest magnitude).
FieldImage coloured(const std::vector<double>& values, int width, int height, FieldShown shown, double range) {
  FieldImage image;
  image.width = width;
  image.height = height;
  for (double v : values) {
    if (std::isfinite(v)) image.max_value = std::max(image.max_value, std::abs(v));
  }
  const double scale = range > 0.0 ? range : std::max(image.max_value, 1e-12);
  image.range = scale;
  image.rgba.resize(values.size() * 4);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::array<std::uint8_t, 3> c = field_colour(shown, std::isfinite(values[k]) ? values[k] / scale : 0.0);
    std::copy(c.begin(), c.end(), image.rgba.begin() + static_cast<std::ptrdiff_t>(4 * k));
    image.rgba[4 * k + 3] = 255;
  }
  return image;
}

}  // namespace

FieldImage field_image(const fluid::FlowState& flow, FieldShown shown, double range) {
  return coloured(plane_values(cell_velocities(flow), flow.grid.dx(), flow.grid.dy(), shown), flow.grid.nx, flow.grid.ny,
                  shown, range);
}

FieldImage field_image(const fluid3d::FlowState3d& flow, int k, FieldShown shown, double range, bool mirror_x) {
  const CellVelocities c = plane_velocities(flow, k, mirror_x);
  return coloured(plane_values(c, flow.grid.h(0), flow.grid.h(1), shown), c.nx, c.ny, shown, range);
}

std::array<std::uint8_t, 3> field_colour(FieldShown shown, double s) {
  const Colour c = shown == FieldShown::speed ? speed_colour(s) : vorticity_colour(s);
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

}  // namespace jellysim::viewer
