#include "jellysim/geometry/rendering_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {
namespace {

bool finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

void validate_points(const std::vector<Vec2>& pts, const std::string& what) {
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!finite(pts[i])) throw InputError(what + "[" + std::to_string(i) + "] is not finite");
    if (i > 0 && pts[i] == pts[i - 1])
      throw InputError(what + "[" + std::to_string(i) + "] coincides with its predecessor");
  }
}

/// Twice the signed area of the polygon (shoelace); positive when counter-clockwise.
double twice_signed_area(const std::vector<Vec2>& poly) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) sum += cross(poly[i], poly[(i + 1) % poly.size()]);
  return sum;
}

}  // namespace

void validate_slice(const jellyfish::SliceFrame& frame) {
  const std::size_t n = frame.umbrella.size();
  if (n < 5 || n % 2 == 0)
    throw InputError("slice umbrella has " + std::to_string(n) + " points; needs an odd count ≥ 5");
  validate_points(frame.umbrella, "slice umbrella");
  if (!(frame.thickness_m > 0.0) || !std::isfinite(frame.thickness_m))
    throw InputError("slice thickness_m = " + std::to_string(frame.thickness_m) + " must be in (0, inf)");
  if (!finite(frame.axis) || std::abs(norm(frame.axis) - 1.0) > 1e-6)
    throw InputError("slice axis must be a unit vector");
  for (const auto& m : frame.muscles) {
    if (m.a < 0 || m.b < 0 || static_cast<std::size_t>(m.a) >= n || static_cast<std::size_t>(m.b) >= n)
      throw InputError("slice muscle indices (" + std::to_string(m.a) + ", " + std::to_string(m.b) +
                       ") out of range [0, " + std::to_string(n - 1) + "]");
    if (!(m.rest_length_m > 0.0) || !std::isfinite(m.length_m))
      throw InputError("slice muscle rest length must be in (0, inf) and its length finite");
  }
  for (std::size_t t = 0; t < frame.tentacles.size(); ++t) {
    if (frame.tentacles[t].size() < 2)
      throw InputError("slice tentacle " + std::to_string(t) + " has fewer than 2 points");
    validate_points(frame.tentacles[t], "slice tentacle " + std::to_string(t));
  }
}

double outward_orientation(const std::vector<Vec2>& umbrella, Vec2 axis) {
  const std::size_t n = umbrella.size();
  double extent = 0.0;
  for (const Vec2& p : umbrella) extent = std::max(extent, norm_squared(p - umbrella[0]));
  const double area2 = twice_signed_area(umbrella);
  // (dx, dy) × ẑ = (dy, −dx) is the right-hand side of the direction of travel: outward of a
  // counter-clockwise polygon, i.e. away from the cavity when the closed umbrella is CCW.
  if (std::abs(area2) > 1e-9 * extent) return area2 > 0.0 ? 1.0 : -1.0;
  const std::size_t m = n / 2;
  const Vec2 d = umbrella[m + 1] - umbrella[m - 1];
  return dot(Vec2{d.y, -d.x}, axis) >= 0.0 ? 1.0 : -1.0;
}

std::vector<Vec2> exumbrellar_normals(const std::vector<Vec2>& umbrella, Vec2 axis) {
  const std::size_t n = umbrella.size();
  const double sign = outward_orientation(umbrella, axis);
  std::vector<Vec2> normals(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 d = umbrella[std::min(i + 1, n - 1)] - umbrella[i == 0 ? 0 : i - 1];
    const Vec2 nrm{d.y, -d.x};  // eq. 7.6: (x_{i+1} − x_{i−1}) × ẑ
    normals[i] = (sign / norm(nrm)) * nrm;
  }
  return normals;
}

std::vector<Vec2> exumbrellar_points(const std::vector<Vec2>& umbrella, Vec2 axis, double thickness_m) {
  const std::vector<Vec2> normals = exumbrellar_normals(umbrella, axis);
  std::vector<Vec2> out(umbrella.size());
  for (std::size_t i = 0; i < umbrella.size(); ++i) out[i] = umbrella[i] + thickness_m * normals[i];  // eq. 7.7
  return out;
}

std::vector<Vec2> closed_hull(const std::vector<Vec2>& subumbrella, const std::vector<Vec2>& exumbrella) {
  std::vector<Vec2> hull(subumbrella);
  hull.insert(hull.end(), exumbrella.rbegin(), exumbrella.rend());
  return hull;
}

RenderingSlice make_rendering_slice(const jellyfish::SliceFrame& frame, int latitude_samples,
                                    int tentacle_samples, Interpolant interpolant) {
  if (latitude_samples < 5 || latitude_samples % 2 == 0)
    throw InputError("latitude_samples = " + std::to_string(latitude_samples) + " must be odd and ≥ 5");
  if (tentacle_samples < 2)
    throw InputError("tentacle_samples = " + std::to_string(tentacle_samples) + " must be ≥ 2");
  validate_slice(frame);
  RenderingSlice slice;
  slice.time_s = frame.time_s;
  slice.axis = frame.axis;
  slice.subumbrella = resample_open_curve(frame.umbrella, latitude_samples, interpolant);
  slice.exumbrella = resample_open_curve(exumbrellar_points(frame.umbrella, frame.axis, frame.thickness_m),
                                         latitude_samples, interpolant);
  const double pieces = static_cast<double>(frame.umbrella.size() - 1);
  for (int k = 0; k < latitude_samples; ++k)
    slice.umbrella_parameter.push_back(pieces * k / (latitude_samples - 1));
  for (const auto& strand : frame.tentacles)
    slice.tentacles.push_back(resample_open_curve(strand, tentacle_samples, interpolant));
  return slice;
}

double bell_height(const jellyfish::SliceFrame& frame) {
  const Vec2 centre = 0.5 * (frame.umbrella.front() + frame.umbrella.back());
  double h = 0.0;
  for (const Vec2& p : frame.umbrella) h = std::max(h, dot(p - centre, frame.axis));
  return h;
}

}  // namespace jellysim::geometry
