#pragma once
// Uniform cell grid for fixed-radius neighbour search (thesis §5.1 needs every particle within h):
// cells of side >= h, so all neighbours of a point lie in its own cell and the eight around it.
// Building is a counting sort (O(n)); a query visits 3 × 3 cells. Within a cell, indices keep
// ascending order, so every traversal is deterministic.
//
// The build can run in parallel over consecutive index ranges ("slots", each owned by one thread):
// count() fills each slot's cell histogram, then place() scatters each slot's points after those of
// the slots before it in the same cell. The sorted order is exactly the serial one whatever the
// number of slots, so results stay bit-identical across thread counts.
#include "jellysim/math/vec2.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace jellysim::sph {

/// Axis-aligned bounds of a point set; non-finite points are ignored. Min/max are exact, so merging
/// partial bounds in any order gives the same result.
struct Bounds {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec2 lo{kInf, kInf}, hi{-kInf, -kInf};
  void add(Vec2 p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  void merge(const Bounds& o) {
    lo = {std::min(lo.x, o.lo.x), std::min(lo.y, o.lo.y)};
    hi = {std::max(hi.x, o.hi.x), std::max(hi.y, o.hi.y)};
  }
};

/// Placement of the cells: origin, side and counts.
struct GridLayout {
  Vec2 min{};
  double cell = 1.0, inverse_cell = 1.0;
  int nx = 0, ny = 0;
  std::size_t cells() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  /// Cells of side `cell_size_m` (> 0) covering `bounds`, grown (doubled) until there are at most
  /// 4 points + 16 of them, which keeps memory O(n) whatever the spread. No cells when points = 0.
  static GridLayout make(const Bounds& bounds, double cell_size_m, std::size_t points);
  int coordinate(double v, double lo, int count) const {
    const double c = std::floor((v - lo) * inverse_cell);
    if (!(c >= 0.0)) return 0;  // also catches NaN
    return c >= count - 1 ? count - 1 : static_cast<int>(c);
  }
  std::uint32_t cell_of(Vec2 p) const {
    return static_cast<std::uint32_t>(coordinate(p.y, min.y, ny) * nx + coordinate(p.x, min.x, nx));
  }
};

class NeighbourGrid {
 public:
  /// Sorts `points` into cells of side `cell_size_m` (> 0) covering their bounding box (serial).
  void build(const std::vector<Vec2>& points, double cell_size_m);

  // ---- parallel build -------------------------------------------------------------------------
  /// Before a parallel build (one thread): room for up to `max_points` points in `slots` slots.
  void reserve(std::size_t max_points, std::size_t slots);
  /// Phase 1, by the owner of slot `slot` = points [begin, end): histogram of their cells.
  void count(const GridLayout& layout, const Vec2* points, std::size_t begin, std::size_t end, std::size_t slot);
  /// One slot of a thread: points [begin, end).
  struct Slot {
    std::size_t slot, begin, end;
  };
  /// Phase 2, after every slot's count(): scatters the points of a thread's slots `mine` (ascending
  /// index within each cell, after the points of lower slots), in one pass over the cells. The
  /// owner of slot 0 also publishes the layout and the cell offsets used by queries. `slots` =
  /// number of slots in this build.
  void place(const GridLayout& layout, std::span<const Slot> mine, std::size_t slots);

  /// Calls f(j) for every point j in the 3 × 3 cells around p (a superset of the points within one
  /// cell size of p), in a fixed order.
  template <class F>
  void for_each_candidate(Vec2 p, F&& f) const {
    for_each_candidate_row(p, [&](const std::uint32_t* first, const std::uint32_t* last) {
      for (const std::uint32_t* k = first; k < last; ++k) f(static_cast<std::size_t>(*k));
    });
  }
  /// The same points, a row of cells at a time: f(first, last) for each of the up to three rows
  /// (their point indices are contiguous in the sorted order).
  template <class F>
  void for_each_candidate_row(Vec2 p, F&& f) const {
    if (layout_.nx == 0) return;
    const int nx = layout_.nx, ny = layout_.ny;
    const int cx = layout_.coordinate(p.x, layout_.min.x, nx), cy = layout_.coordinate(p.y, layout_.min.y, ny);
    const int y0 = std::max(cy - 1, 0), y1 = std::min(cy + 1, ny - 1);
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx - 1);
    for (int y = y0; y <= y1; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx);
      // Cells x0..x1 of one row are contiguous in the sorted order.
      const std::uint32_t begin = cell_start_[row + static_cast<std::size_t>(x0)];
      const std::uint32_t end = cell_start_[row + static_cast<std::size_t>(x1) + 1];
      f(sorted_.data() + begin, sorted_.data() + end);
    }
  }

  double cell_size() const { return layout_.cell; }
  int columns() const { return layout_.nx; }
  int rows() const { return layout_.ny; }

 private:
  GridLayout layout_;
  std::vector<std::uint32_t> cell_start_;  ///< size cells + 1
  std::vector<std::uint32_t> sorted_;      ///< point indices ordered by cell
  std::vector<std::uint32_t> cell_of_;     ///< scratch: cell of each point
  std::vector<std::vector<std::uint32_t>> histogram_, cursor_;  ///< per slot, per cell
};

/// Indices j ≠ i with |x_j − x_i| < radius, by brute force (for tests).
std::vector<std::size_t> brute_force_neighbours(const std::vector<Vec2>& points, std::size_t i, double radius);

}  // namespace jellysim::sph
