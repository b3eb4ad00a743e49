#include "jellysim/fluid/flow_mirror.hpp"

#include <cmath>
#include <stdexcept>

#include "jellysim/fluid/projection.hpp"

namespace jellysim::fluid {

namespace {

/// Column i's mirror image is column total − i: a sample at (i + s)Δx mirrors to
/// (n − i − s)Δx = (i' + s)Δx, so i' = n − 2s − i. Ghost columns map onto ghost columns.
int mirror_column_total(const Field& f) {
  return f.grid().nx - static_cast<int>(std::lround(2.0 * f.staggering().x));
}

/// f → ½(f + sign · M f), sign −1 for the x-velocity (it changes direction in the mirror).
void keep_symmetric_part(Field& f, double sign) {
  const int total = mirror_column_total(f);
  for (int j = -1; j <= f.count_y(); ++j) {
    double* row = f.ptr(0, j);
    for (int i = -1; 2 * i <= total; ++i) {
      const int m = total - i;
      const double a = row[i], b = row[m];
      row[i] = 0.5 * (a + sign * b);
      row[m] = sign * row[i];  // exactly the mirror image; 0 on the axis for sign −1
    }
  }
}

double field_asymmetry(const Field& f, double sign) {
  const int total = mirror_column_total(f);
  double worst = 0.0;
  for (int j = 0; j < f.count_y(); ++j)
    for (int i = 0; i < f.count_x(); ++i) worst = std::max(worst, std::abs(f(i, j) - sign * f(total - i, j)));
  return worst;
}

}  // namespace

void keep_mirror_symmetric_part(FlowState& flow) {
  keep_symmetric_part(flow.velocity.u, -1.0);
  keep_symmetric_part(flow.velocity.v, +1.0);
  keep_symmetric_part(flow.pressure, +1.0);
}

MacGrid east_half(const MacGrid& full) {
  if (full.nx % 2 != 0) throw std::invalid_argument("the half tank needs an even number of cells across");
  return MacGrid(full.nx / 2, full.ny, 0.5 * full.width_m, full.height_m,
                 {full.origin_m.x + 0.5 * full.width_m, full.origin_m.y});
}

namespace {

/// Interior samples of a full-tank field from the east half: column i of the full field is column
/// i − n/2 of the half east of the axis, and the mirror image (times sign) of column total − i west of it.
void unfold(const Field& half, Field& full, double sign) {
  const int offset = half.grid().nx;  // columns of the full tank west of the axis
  const int total = mirror_column_total(full);
  for (int j = 0; j < full.count_y(); ++j)
    for (int i = 0; i < full.count_x(); ++i)
      full(i, j) = i >= offset ? half(i - offset, j) : sign * half(total - i - offset, j);
}

}  // namespace

void unfold_east_half(const FlowState& half, FlowState& full, const Boundaries& full_sides) {
  if (full.grid.nx != 2 * half.grid.nx || full.grid.ny != half.grid.ny) full = FlowState(MacGrid(
      2 * half.grid.nx, half.grid.ny, 2 * half.grid.width_m, half.grid.height_m,
      {half.grid.origin_m.x - half.grid.width_m, half.grid.origin_m.y}));
  unfold(half.velocity.u, full.velocity.u, -1.0);
  unfold(half.velocity.v, full.velocity.v, +1.0);
  unfold(half.pressure, full.pressure, +1.0);
  refresh_velocity_ghosts(full.velocity, full_sides);
  fill_pressure_ghosts(full.pressure, full_sides);
}

double mirror_asymmetry(const Velocity& velocity) {
  return std::max(field_asymmetry(velocity.u, -1.0), field_asymmetry(velocity.v, +1.0));
}

}  // namespace jellysim::fluid
