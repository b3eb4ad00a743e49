#pragma once
// The 2D rendering model of thesis §7.2: the simulated subumbrellar points get an exumbrellar
// partner offset by the thickness ϑ (eqs. 7.6–7.7), and both surfaces are resampled at any
// resolution with a C1 cubic (eq. 7.8, geometry/spline.hpp).
#include <vector>

#include "jellysim/geometry/spline.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::geometry {

/// Throws InputError naming what is wrong: fewer than 5 umbrella points or an even count,
/// non-finite coordinates, ϑ ≤ 0 or non-finite, coincident neighbours, a non-unit axis, muscle
/// indices out of range, a tentacle with fewer than 2 points.
void validate_slice(const jellyfish::SliceFrame& frame);

/// +1 when the numerical normal (x_{i+1} − x_{i−1}) × ẑ of eq. 7.6 points away from the
/// subumbrellar cavity for this ordering, −1 when it points into it. Decided by the signed area of
/// the umbrella closed by its aperture chord (the cavity is that polygon's inside); for a flat
/// umbrella (no area) by the axis: the apex normal points along +axis.
double outward_orientation(const std::vector<Vec2>& umbrella, Vec2 axis);

/// Unit normals of eq. 7.6 (one-sided differences at the two ends), oriented away from the cavity.
std::vector<Vec2> exumbrellar_normals(const std::vector<Vec2>& umbrella, Vec2 axis);

/// Eq. 7.7: x̃_i = x_i + ϑ n̂_i.
std::vector<Vec2> exumbrellar_points(const std::vector<Vec2>& umbrella, Vec2 axis, double thickness_m);

/// The closed hull of §7.2: x_1 … x_n, x̃_n … x̃_1.
std::vector<Vec2> closed_hull(const std::vector<Vec2>& subumbrella, const std::vector<Vec2>& exumbrella);

/// The resampled rendering model of one slice.
struct RenderingSlice {
  double time_s = 0.0;
  Vec2 axis{0.0, 1.0};
  /// Both surfaces left tip → apex → right tip, same odd count; sample k opposes count − 1 − k and
  /// subumbrella[k] lies opposite exumbrella[k] across the thickness.
  std::vector<Vec2> subumbrella;
  std::vector<Vec2> exumbrella;
  /// Parameter of each sample on the simulated umbrella, u ∈ [0, n − 1] (umbrella point index).
  std::vector<double> umbrella_parameter;
  std::vector<std::vector<Vec2>> tentacles;  ///< each resampled to the same count
};

/// Resamples a validated slice: each umbrella surface at `latitude_samples` (odd ≥ 5) points, each
/// tentacle at `tentacle_samples` (≥ 2) points. The two surfaces are interpolated separately and
/// joined at the rim by the straight edge x_n → x̃_n (see docs/rendering.md: one uniform cubic
/// threaded through the whole hull loops at the rim, where the spacing drops from the simulation
/// spacing to ϑ).
RenderingSlice make_rendering_slice(const jellyfish::SliceFrame& frame, int latitude_samples,
                                    int tentacle_samples, Interpolant interpolant);

/// Height of the bell: the largest distance of an umbrella point from the aperture chord's
/// midpoint, measured along the axis (m).
double bell_height(const jellyfish::SliceFrame& frame);

}  // namespace jellysim::geometry
