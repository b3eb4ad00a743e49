#include "jellysim/sph/neighbour_grid.hpp"

#include <stdexcept>

namespace jellysim::sph {

GridLayout GridLayout::make(const Bounds& bounds, double cell_size_m, std::size_t points) {
  if (!(cell_size_m > 0.0)) throw std::invalid_argument("NeighbourGrid: cell size must be positive");
  GridLayout g;
  if (points == 0) return g;
  Vec2 lo = bounds.lo, hi = bounds.hi;
  if (!(lo.x <= hi.x)) lo = hi = {0.0, 0.0};  // no finite point
  // Cap the cell count at 4n + 16 by growing the cells (a query still covers radius cell_size_m).
  g.cell = cell_size_m;
  const double max_cells = 4.0 * static_cast<double>(points) + 16.0;
  while (((hi.x - lo.x) / g.cell + 1.0) * ((hi.y - lo.y) / g.cell + 1.0) > max_cells) g.cell *= 2.0;
  g.inverse_cell = 1.0 / g.cell;
  g.min = lo;
  g.nx = static_cast<int>((hi.x - lo.x) * g.inverse_cell) + 1;
  g.ny = static_cast<int>((hi.y - lo.y) * g.inverse_cell) + 1;
  return g;
}

void NeighbourGrid::build(const std::vector<Vec2>& points, double cell_size_m) {
  Bounds bounds;
  for (const Vec2& p : points) bounds.add(p);
  const GridLayout layout = GridLayout::make(bounds, cell_size_m, points.size());
  reserve(points.size(), 1);
  count(layout, points.data(), 0, points.size(), 0);
  const Slot all{0, 0, points.size()};
  place(layout, std::span<const Slot>(&all, 1), 1);
}

void NeighbourGrid::reserve(std::size_t max_points, std::size_t slots) {
  const std::size_t max_cells = 4 * max_points + 16;
  if (cell_start_.size() < max_cells + 1) cell_start_.resize(max_cells + 1);
  if (sorted_.size() < max_points) {
    sorted_.resize(max_points);
    cell_of_.resize(max_points);
  }
  if (histogram_.size() < slots) {
    histogram_.resize(slots);
    cursor_.resize(slots);
  }
  for (std::size_t s = 0; s < slots; ++s) {
    if (histogram_[s].size() < max_cells) {
      histogram_[s].resize(max_cells);
      cursor_[s].resize(max_cells);
    }
  }
}

void NeighbourGrid::count(const GridLayout& layout, const Vec2* points, std::size_t begin, std::size_t end,
                          std::size_t slot) {
  std::uint32_t* histogram = histogram_[slot].data();
  std::fill(histogram, histogram + layout.cells(), 0u);
  for (std::size_t i = begin; i < end; ++i) {
    const std::uint32_t c = layout.cell_of(points[i]);
    cell_of_[i] = c;
    ++histogram[c];
  }
}

void NeighbourGrid::place(const GridLayout& layout, std::span<const Slot> mine, std::size_t slots) {
  // Exclusive prefix over (cell, slot) in that order: slot s of cell c starts after every point of
  // the cells before c and of the slots before s in c. Each thread computes it for its own slots.
  const std::size_t cells = layout.cells();
  const bool publish = std::any_of(mine.begin(), mine.end(), [](const Slot& s) { return s.slot == 0; });
  std::uint32_t running = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    if (publish) cell_start_[c] = running;
    for (std::size_t s = 0, k = 0; s < slots; ++s) {
      if (k < mine.size() && mine[k].slot == s) {
        cursor_[s][c] = running;
        ++k;
      }
      running += histogram_[s][c];
    }
  }
  for (const Slot& s : mine) {
    std::uint32_t* cursor = cursor_[s.slot].data();
    for (std::size_t i = s.begin; i < s.end; ++i) sorted_[cursor[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  }
  if (publish) {
    cell_start_[cells] = running;
    layout_ = layout;
  }
}

std::vector<std::size_t> brute_force_neighbours(const std::vector<Vec2>& points, std::size_t i, double radius) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (j != i && norm_squared(points[j] - points[i]) < radius * radius) out.push_back(j);
  }
  return out;
}

}  // namespace jellysim::sph
