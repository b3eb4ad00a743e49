#include "fluid/mirror.hpp"

#include <cmath>

namespace jellysim::fluid {

namespace {

/// The stored column that is the mirror image of column i: a sample at (i + s)Δx mirrors to
/// (n − i − s)Δx = (i' + s)Δx, so i' = n − i − 2s. Ghost columns map onto ghost columns.
int mirror_column(const Field& f, int i) {
  return f.grid().nx - i - static_cast<int>(std::lround(2.0 * f.staggering().x));
}

/// f → ½(f + sign · M f), sign −1 for the x-velocity (it changes direction in the mirror).
void keep_symmetric_part(Field& f, double sign) {
  for (int j = -1; j <= f.count_y(); ++j)
    for (int i = -1; i <= f.count_x(); ++i) {
      const int m = mirror_column(f, i);
      if (m < i) continue;  // each pair once
      const double a = f(i, j), b = f(m, j);
      f(i, j) = 0.5 * (a + sign * b);
      f(m, j) = sign * f(i, j);  // exactly the mirror image; 0 on the axis for sign −1
    }
}

double field_asymmetry(const Field& f, double sign) {
  double worst = 0.0;
  for (int j = 0; j < f.count_y(); ++j)
    for (int i = 0; i < f.count_x(); ++i) worst = std::max(worst, std::abs(f(i, j) - sign * f(mirror_column(f, i), j)));
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
