#include "fluid/grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace jellysim::fluid {

MacGrid::MacGrid(int cells_x, int cells_y, double width, double height, Vec2 origin)
    : nx(cells_x), ny(cells_y), width_m(width), height_m(height), origin_m(origin) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("MacGrid needs at least one cell per axis");
  if (!(width > 0.0) || !(height > 0.0))
    throw std::invalid_argument("MacGrid needs a positive width and height");
}

Vec2 MacGrid::clamp_to_domain(Vec2 p) const {
  return {std::clamp(p.x, origin_m.x, origin_m.x + width_m),
          std::clamp(p.y, origin_m.y, origin_m.y + height_m)};
}

int sample_count_x(const MacGrid& grid, Staggering s) { return s.x == 0.0 ? grid.nx + 1 : grid.nx; }
int sample_count_y(const MacGrid& grid, Staggering s) { return s.y == 0.0 ? grid.ny + 1 : grid.ny; }

Field::Field(const MacGrid& grid, Staggering staggering, double value)
    : grid_(grid),
      stagger_(staggering),
      count_x_(sample_count_x(grid, staggering)),
      count_y_(sample_count_y(grid, staggering)),
      stride_(static_cast<std::size_t>(count_x_ + 2)),
      data_(stride_ * static_cast<std::size_t>(count_y_ + 2), value) {}

double Field::sample(Vec2 p) const {
  const Vec2 g = grid_.grid_from_world(p);
  const double fx = g.x - stagger_.x;
  const double fy = g.y - stagger_.y;
  // Lower-left sample of the interpolation square, kept inside [-1, count - 1].
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), -1, count_x_ - 1);
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), -1, count_y_ - 1);
  const double tx = std::clamp(fx - i0, 0.0, 1.0);
  const double ty = std::clamp(fy - j0, 0.0, 1.0);
  const std::size_t k = index(i0, j0);
  const double bottom = (1.0 - tx) * data_[k] + tx * data_[k + 1];
  const double top = (1.0 - tx) * data_[k + stride_] + tx * data_[k + stride_ + 1];
  return (1.0 - ty) * bottom + ty * top;
}

void Field::fill(double value) { std::fill(data_.begin(), data_.end(), value); }

double Field::max_abs_interior() const {
  double m = 0.0;
  for (int j = 0; j < count_y_; ++j)
    for (int i = 0; i < count_x_; ++i) m = std::max(m, std::abs((*this)(i, j)));
  return m;
}

}  // namespace jellysim::fluid
