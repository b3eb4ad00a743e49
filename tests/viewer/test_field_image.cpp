// The 2D panel's colours (src/viewer/field_image.cpp): the overlays (tracers, muscle springs) stand
// apart from every colour of both field maps, and the colour bar's map is the field image's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "jellysim/viewer/field_image.hpp"

namespace jellysim::viewer {
namespace {

double distance(const std::array<std::uint8_t, 3>& a, const std::array<std::uint8_t, 3>& b) {
  return std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]);
}

/// The smallest RGB distance (0–441) from `c` to the map's colours, sampled finely over its range.
double nearest_in_map(const std::array<std::uint8_t, 3>& c, FieldShown shown) {
  double nearest = 1e9;
  const double lo = shown == FieldShown::vorticity ? -1.0 : 0.0;
  for (int k = 0; k <= 2000; ++k) nearest = std::min(nearest, distance(c, field_colour(shown, lo + (1.0 - lo) * k / 2000.0)));
  return nearest;
}

// Measured (RGB distance, 0–441): tracers 203 from the vorticity map and 130 from the speed map,
// muscles 150 and 160; the muscles' red of before sat 43 from the vorticity map's red.
TEST(FieldImage, OverlayColoursStandApartFromBothMaps) {
  for (const FieldShown shown : {FieldShown::vorticity, FieldShown::speed}) {
    EXPECT_GT(nearest_in_map(kTracerColour, shown), 120.0);
    EXPECT_GT(nearest_in_map(kMuscleColour, shown), 120.0);
  }
  EXPECT_LT(nearest_in_map({255, 70, 60}, FieldShown::vorticity), 50.0);  // the old muscle red
}

// The ends of the vorticity map are its counter-clockwise (warm) and clockwise (cold) extremes.
TEST(FieldImage, VorticityMapRunsFromColdToWarm) {
  const auto warm = field_colour(FieldShown::vorticity, 1.0), cold = field_colour(FieldShown::vorticity, -1.0);
  EXPECT_GT(warm[0], warm[2]);
  EXPECT_GT(cold[2], cold[0]);
  EXPECT_EQ(field_colour(FieldShown::vorticity, 2.0), warm);  // clamped beyond the range
}

}  // namespace
}  // namespace jellysim::viewer
