#pragma once
// Staggered (MAC) grid of thesis Figure 4.1: pressure at cell centres, the x-velocity on the
// vertical faces, the y-velocity on the horizontal faces. Every field carries one ghost layer
// around its interior samples; the boundary conditions (boundary.hpp) fill the ghosts.
#include <algorithm>
#include <cmath>
#include <span>
#include <string_view>
#include <vector>

#include "jellysim/math/vec2.hpp"

namespace jellysim::core {
class StateArchive;
}

namespace jellysim::fluid {

/// Geometry of a rectangular domain [origin, origin + size] divided into nx × ny equal cells.
/// The only place where world coordinates (metres) and grid coordinates (cells) meet.
struct MacGrid {
  int nx = 0;
  int ny = 0;
  double width_m = 1.0;
  double height_m = 1.0;
  Vec2 origin_m{};

  MacGrid() = default;
  MacGrid(int cells_x, int cells_y, double width, double height, Vec2 origin = {});

  double dx() const { return width_m / nx; }
  double dy() const { return height_m / ny; }
  int cell_count() const { return nx * ny; }
  /// World position of grid coordinates (gx, gy), measured in cells from the origin corner.
  Vec2 world_from_grid(double gx, double gy) const {
    return {origin_m.x + gx * dx(), origin_m.y + gy * dy()};
  }
  /// Grid coordinates (in cells from the origin corner) of a world position.
  Vec2 grid_from_world(Vec2 p) const {
    return {(p.x - origin_m.x) / dx(), (p.y - origin_m.y) / dy()};
  }
  /// Clamp a world position into the closed domain rectangle.
  Vec2 clamp_to_domain(Vec2 p) const {
    return {std::clamp(p.x, origin_m.x, origin_m.x + width_m), std::clamp(p.y, origin_m.y, origin_m.y + height_m)};
  }
};

/// Where a field's samples sit inside a cell, as a fraction of the cell size.
struct Staggering {
  double x = 0.5;
  double y = 0.5;
};
inline constexpr Staggering kCellCentres{0.5, 0.5};
inline constexpr Staggering kXFaces{0.0, 0.5};  ///< x-velocity: west/east faces
inline constexpr Staggering kYFaces{0.5, 0.0};  ///< y-velocity: south/north faces
inline constexpr Staggering kNodes{0.0, 0.0};   ///< cell corners (vorticity)

/// A scalar field on a MAC grid with a known staggering and one ghost layer on every side.
/// Interior indices run over [0, count_x) × [0, count_y); ghosts are at -1 and count.
class Field {
 public:
  Field() = default;
  Field(const MacGrid& grid, Staggering staggering, double value = 0.0);

  const MacGrid& grid() const { return grid_; }
  Staggering staggering() const { return stagger_; }
  int count_x() const { return count_x_; }
  int count_y() const { return count_y_; }

  double& operator()(int i, int j) { return data_[index(i, j)]; }
  double operator()(int i, int j) const { return data_[index(i, j)]; }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j + 1) * stride_ + static_cast<std::size_t>(i + 1);
  }
  std::size_t stride() const { return stride_; }
  /// Pointer to sample (i, j); consecutive i are contiguous.
  double* ptr(int i, int j) { return data_.data() + index(i, j); }
  const double* ptr(int i, int j) const { return data_.data() + index(i, j); }
  std::span<double> raw() { return data_; }
  std::span<const double> raw() const { return data_; }

  /// World position of sample (i, j), ghosts included.
  Vec2 position(int i, int j) const {
    return grid_.world_from_grid(i + stagger_.x, j + stagger_.y);
  }
  /// Bilinear interpolation at a world position; outside the stored samples (ghosts included)
  /// the position is clamped onto them.
  double sample(Vec2 p) const {
    // Continuous sample index, clamped to the stored range [-1, count] (ghosts included); a NaN
    // position (a diverged run) samples at -1 instead of indexing out of the field.
    const double fx = clamp_index((p.x - origin_x_) * inv_dx_, count_x_);
    const double fy = clamp_index((p.y - origin_y_) * inv_dy_, count_y_);
    const int i0 = std::min(static_cast<int>(fx + 1.0) - 1, count_x_ - 1);  // floor, as fx ≥ −1
    const int j0 = std::min(static_cast<int>(fy + 1.0) - 1, count_y_ - 1);
    const double tx = fx - i0;
    const double ty = fy - j0;
    const double* q = data_.data() + index(i0, j0);
    const double bottom = (1.0 - tx) * q[0] + tx * q[1];
    const double top = (1.0 - tx) * q[stride_] + tx * q[stride_ + 1];
    return (1.0 - ty) * bottom + ty * top;
  }
  void fill(double value);
  /// f clamped to [−1, count]; NaN → −1.
  static double clamp_index(double f, int count) {
    if (!(f > -1.0)) return -1.0;
    return f < count ? f : static_cast<double>(count);
  }
  /// Largest |value| over the interior samples (NaN if any sample is NaN).
  double max_abs_interior() const;

 private:
  MacGrid grid_{};
  Staggering stagger_{};
  int count_x_ = 0;
  int count_y_ = 0;
  std::size_t stride_ = 0;
  std::vector<double> data_;
  // World position of sample (0, 0) and inverse spacings, cached for sample().
  double origin_x_ = 0.0, origin_y_ = 0.0, inv_dx_ = 1.0, inv_dy_ = 1.0;
};

/// Number of interior samples along x for a staggering: faces and nodes have one more than cells.
int sample_count_x(const MacGrid& grid, Staggering s);
int sample_count_y(const MacGrid& grid, Staggering s);

/// The staggered velocity: u on x-faces, v on y-faces (m/s).
struct Velocity {
  Field u;
  Field v;

  Velocity() = default;
  explicit Velocity(const MacGrid& grid) : u(grid, kXFaces), v(grid, kYFaces) {}
  /// Bilinear sample of both components at a world position (needs filled ghosts).
  Vec2 sample(Vec2 p) const { return {u.sample(p), v.sample(p)}; }
};

/// Face-centred body accelerations (m/s²), e.g. the immersed-boundary force divided by the cell
/// mass ρΔxΔy (eq. 4.19). Same layout as Velocity.
using FaceAccelerations = Velocity;

/// Everything the fluid solvers advance: velocity (m/s) and pressure (Pa) on one grid.
struct FlowState {
  MacGrid grid;
  Velocity velocity;
  Field pressure;

  FlowState() = default;
  explicit FlowState(const MacGrid& g) : grid(g), velocity(g), pressure(g, kCellCentres) {}
};

/// Checkpoints (core/state_archive.hpp): a field's samples, ghosts included, bit for bit.
void archive(core::StateArchive& a, std::string_view name, Field& f);
void archive(core::StateArchive& a, std::string_view name, Velocity& v);

}  // namespace jellysim::fluid
