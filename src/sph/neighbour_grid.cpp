#include "sph/neighbour_grid.hpp"

#include <limits>
#include <stdexcept>

namespace jellysim::sph {

void NeighbourGrid::build(const std::vector<Vec2>& points, double cell_size_m) {
  if (!(cell_size_m > 0.0)) throw std::invalid_argument("NeighbourGrid: cell size must be positive");
  const std::size_t n = points.size();
  nx_ = ny_ = 0;
  if (n == 0) return;
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 hi = -lo;
  for (const Vec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  if (!(lo.x <= hi.x)) lo = hi = {0.0, 0.0};
  // Cap the cell count at 4n + 16 by growing the cells (a query still covers radius cell_size_m).
  cell_ = cell_size_m;
  const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
  while (((hi.x - lo.x) / cell_ + 1.0) * ((hi.y - lo.y) / cell_ + 1.0) > max_cells) cell_ *= 2.0;
  inverse_cell_ = 1.0 / cell_;
  min_ = lo;
  nx_ = static_cast<int>((hi.x - lo.x) * inverse_cell_) + 1;
  ny_ = static_cast<int>((hi.y - lo.y) * inverse_cell_) + 1;
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  cell_start_.assign(cells + 1, 0);
  cell_of_.resize(n);
  sorted_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::uint32_t>(cell_coordinate(points[i].y, min_.y, ny_) * nx_ +
                                              cell_coordinate(points[i].x, min_.x, nx_));
    cell_of_[i] = c;
    ++cell_start_[c + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  // Stable placement: ascending indices within each cell.
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[fill_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
}

std::vector<std::size_t> brute_force_neighbours(const std::vector<Vec2>& points, std::size_t i, double radius) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (j != i && norm_squared(points[j] - points[i]) < radius * radius) out.push_back(j);
  }
  return out;
}

}  // namespace jellysim::sph
