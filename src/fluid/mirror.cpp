#include "fluid/mirror.hpp"

#include <cmath>

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

double mirror_asymmetry(const Velocity& velocity) {
  return std::max(field_asymmetry(velocity.u, -1.0), field_asymmetry(velocity.v, +1.0));
}

}  // namespace jellysim::fluid
