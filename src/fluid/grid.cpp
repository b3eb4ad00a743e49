#include "jellysim/fluid/grid.hpp"

#include "jellysim/core/state_archive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace jellysim::fluid {

MacGrid::MacGrid(int cells_x, int cells_y, double width, double height, Vec2 origin)
    : nx(cells_x), ny(cells_y), width_m(width), height_m(height), origin_m(origin) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("MacGrid needs at least one cell per axis");
  if (!(width > 0.0) || !(height > 0.0))
    throw std::invalid_argument("MacGrid needs a positive width and height");
}

int sample_count_x(const MacGrid& grid, Staggering s) { return s.x == 0.0 ? grid.nx + 1 : grid.nx; }
int sample_count_y(const MacGrid& grid, Staggering s) { return s.y == 0.0 ? grid.ny + 1 : grid.ny; }

Field::Field(const MacGrid& grid, Staggering staggering, double value)
    : grid_(grid),
      stagger_(staggering),
      count_x_(sample_count_x(grid, staggering)),
      count_y_(sample_count_y(grid, staggering)),
      stride_(static_cast<std::size_t>(count_x_ + 2)),
      data_(stride_ * static_cast<std::size_t>(count_y_ + 2), value),
      origin_x_(grid.world_from_grid(staggering.x, staggering.y).x),
      origin_y_(grid.world_from_grid(staggering.x, staggering.y).y),
      inv_dx_(1.0 / grid.dx()),
      inv_dy_(1.0 / grid.dy()) {}

void Field::fill(double value) { std::fill(data_.begin(), data_.end(), value); }

void archive(core::StateArchive& a, std::string_view name, Field& f) { a.values(name, f.raw()); }

void archive(core::StateArchive& a, std::string_view name, Velocity& v) {
  const core::StateArchive::Scope scope(a, name);
  archive(a, "u", v.u);
  archive(a, "v", v.v);
}

double Field::max_abs_interior() const {
  // Four running maxima per row break the dependency chain so the compiler can use packed max
  // instructions; NaN is tracked apart, as a comparison with NaN is false.
  double m[4] = {0.0, 0.0, 0.0, 0.0};
  bool nan = false;
  for (int j = 0; j < count_y_; ++j) {
    const double* row = ptr(0, j);
    int i = 0;
    for (; i + 4 <= count_x_; i += 4)
      for (int l = 0; l < 4; ++l) {
        const double a = std::abs(row[i + l]);
        m[l] = a > m[l] ? a : m[l];
        nan |= a != a;
      }
    for (; i < count_x_; ++i) {
      const double a = std::abs(row[i]);
      m[0] = a > m[0] ? a : m[0];
      nan |= a != a;
    }
  }
  if (nan) return std::numeric_limits<double>::quiet_NaN();
  return std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
}

}  // namespace jellysim::fluid
