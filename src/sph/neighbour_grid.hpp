#pragma once
// Uniform cell grid for fixed-radius neighbour search (thesis §5.1 needs every particle within h):
// cells of side >= h, so all neighbours of a point lie in its own cell and the eight around it.
// Building is a counting sort (O(n)); a query visits 3 × 3 cells. Within a cell, indices keep
// ascending order, so every traversal is deterministic.
#include "math/vec2.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace jellysim::sph {

class NeighbourGrid {
 public:
  /// Sorts `points` into cells of side `cell_size_m` (> 0) covering their bounding box. The number
  /// of cells is capped at a few per point (cells grow for very sparse sets), which keeps memory
  /// O(n) whatever the spread.
  void build(const std::vector<Vec2>& points, double cell_size_m);

  /// Calls f(j) for every point j in the 3 × 3 cells around p (a superset of the points within one
  /// cell size of p), in a fixed order.
  template <class F>
  void for_each_candidate(Vec2 p, F&& f) const {
    if (nx_ == 0) return;
    const int cx = cell_coordinate(p.x, min_.x, nx_), cy = cell_coordinate(p.y, min_.y, ny_);
    const int y0 = std::max(cy - 1, 0), y1 = std::min(cy + 1, ny_ - 1);
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx_ - 1);
    for (int y = y0; y <= y1; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_);
      // Cells x0..x1 of one row are contiguous in the sorted order.
      const std::uint32_t begin = cell_start_[row + static_cast<std::size_t>(x0)];
      const std::uint32_t end = cell_start_[row + static_cast<std::size_t>(x1) + 1];
      for (std::uint32_t k = begin; k < end; ++k) f(static_cast<std::size_t>(sorted_[k]));
    }
  }

  double cell_size() const { return cell_; }
  int columns() const { return nx_; }
  int rows() const { return ny_; }

 private:
  int cell_coordinate(double v, double lo, int count) const {
    const double c = std::floor((v - lo) * inverse_cell_);
    if (!(c >= 0.0)) return 0;  // also catches NaN
    return c >= count - 1 ? count - 1 : static_cast<int>(c);
  }

  Vec2 min_{};
  double cell_ = 1.0, inverse_cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> cell_start_;  ///< size cells + 1
  std::vector<std::uint32_t> sorted_;      ///< point indices ordered by cell
  std::vector<std::uint32_t> cell_of_;     ///< scratch: cell of each point
  std::vector<std::uint32_t> fill_;        ///< scratch: insertion cursor per cell
};

/// Indices j ≠ i with |x_j − x_i| < radius, by brute force (for tests).
std::vector<std::size_t> brute_force_neighbours(const std::vector<Vec2>& points, std::size_t i, double radius);

}  // namespace jellysim::sph
