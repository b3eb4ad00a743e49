#pragma once
// The 3D staggered (MAC) grid of the 3D fluid (issue 40, docs/three-d.md): nx × ny × nz equal
// cells over [origin, origin + size] (metres); u on x-faces, v on y-faces, w on z-faces, the
// pressure at cell centres. Every field of a grid (the three velocity components, the pressure, the
// body force, scratch arrays) has the same padded layout: indices −2 … n + 2 along each axis (two
// ghost layers, room for the n + 1 faces), x fastest, so a neighbour along axis d is always
// `index ± stride(d)` whatever the field. Index (i, j, k) of component c is the face at
// x_c = index_c·h_c (the other two coordinates at cell centres); of the pressure the centre.
#include <array>
#include <cstddef>
#include <vector>

namespace jellysim::fluid3d {

using Vec3 = std::array<double, 3>;
using Index3 = std::array<int, 3>;

class Grid3d {
 public:
  static constexpr int ghosts = 2;
  /// cells[d] ≥ 2 cells along axis d over size_m[d] > 0 metres; throws std::invalid_argument.
  Grid3d(Index3 cells, Vec3 size_m, Vec3 origin_m = {0.0, 0.0, 0.0});

  int n(int axis) const { return cells_[static_cast<std::size_t>(axis)]; }
  double h(int axis) const { return spacing_[static_cast<std::size_t>(axis)]; }
  double size(int axis) const { return size_[static_cast<std::size_t>(axis)]; }
  const Vec3& origin() const { return origin_; }
  Index3 cells() const { return cells_; }
  std::size_t cell_count() const;
  double cell_volume() const { return spacing_[0] * spacing_[1] * spacing_[2]; }

  /// Samples in each padded field (all fields have this many).
  std::size_t padded_size() const { return padded_[0] * padded_[1] * padded_[2]; }
  std::size_t stride(int axis) const { return stride_[static_cast<std::size_t>(axis)]; }
  /// The padded array index of (i, j, k), each in [−2, n + 2].
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i + ghosts) + stride_[1] * static_cast<std::size_t>(j + ghosts) +
           stride_[2] * static_cast<std::size_t>(k + ghosts);
  }
  /// World position of sample (i, j, k) of component c (0, 1, 2: a face field) or of the
  /// pressure (c = 3: cell centres).
  Vec3 position(int c, int i, int j, int k) const;

 private:
  Index3 cells_;
  Vec3 size_, origin_, spacing_;
  std::array<std::size_t, 3> padded_, stride_;
};

/// Calls f(index, i, j, k) for every interior cell of g, in index order (x fastest).
template <class F>
void for_each_interior_cell(const Grid3d& g, F&& f) {
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i) f(g.index(i, j, k), i, j, k);
}

/// One scalar sample per padded index.
using Field3d = std::vector<double>;

/// u, v, w (m/s) on the faces normal to x, y, z.
struct Velocity3d {
  std::array<Field3d, 3> c;
  explicit Velocity3d(const Grid3d& g)
      : c{Field3d(g.padded_size(), 0.0), Field3d(g.padded_size(), 0.0), Field3d(g.padded_size(), 0.0)} {}
};

/// A flow on a grid: velocity (m/s) and pressure (Pa at cell centres), at time t (s).
struct FlowState3d {
  Grid3d grid;
  Velocity3d velocity;
  Field3d pressure;
  double time_s = 0.0;
  explicit FlowState3d(const Grid3d& g) : grid(g), velocity(g), pressure(g.padded_size(), 0.0) {}
};

}  // namespace jellysim::fluid3d
