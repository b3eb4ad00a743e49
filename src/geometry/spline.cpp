#include "jellysim/geometry/spline.hpp"

#include <stdexcept>

#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {

Interpolant parse_interpolant(const std::string& name, const std::string& field) {
  if (name == "thesis") return Interpolant::thesis_cubic;
  if (name == "catmull-rom") return Interpolant::catmull_rom;
  throw InputError(field + " = '" + name + "' is not an interpolant (allowed: thesis, catmull-rom)");
}

std::string interpolant_name(Interpolant interpolant) {
  return interpolant == Interpolant::thesis_cubic ? "thesis" : "catmull-rom";
}

CubicPiece cubic_piece(Vec2 xm1, Vec2 x0, Vec2 x1, Vec2 x2, Interpolant interpolant) {
  if (interpolant == Interpolant::thesis_cubic) {
    // Eq. 7.8 exactly as printed.
    const Vec2 p = (x2 - x1) - (xm1 - x0);
    return {p, (xm1 - x0) - p, x1 - xm1, x0};
  }
  // Hermite piece with tangents m0 = ½(x1 − x_{−1}), m1 = ½(x2 − x0) in the same power basis.
  const Vec2 m0 = 0.5 * (x1 - xm1), m1 = 0.5 * (x2 - x0);
  return {2.0 * (x0 - x1) + m0 + m1, 3.0 * (x1 - x0) - 2.0 * m0 - m1, m0, x0};
}

namespace {
/// Point i of the open curve, with linearly extrapolated phantom points at i = −1 and i = n.
Vec2 extended_point(const std::vector<Vec2>& pts, long i) {
  const long n = static_cast<long>(pts.size());
  if (i < 0) return 2.0 * pts[0] - pts[1];
  if (i >= n) return 2.0 * pts[n - 1] - pts[n - 2];
  return pts[static_cast<std::size_t>(i)];
}

Vec2 piece_point(const std::vector<Vec2>& pts, long i, double s, Interpolant interpolant) {
  return cubic_piece(extended_point(pts, i - 1), extended_point(pts, i), extended_point(pts, i + 1),
                     extended_point(pts, i + 2), interpolant)
      .at(s);
}
}  // namespace

Vec2 curve_point(const std::vector<Vec2>& points, double u, Interpolant interpolant) {
  if (points.size() < 2) throw std::invalid_argument("curve_point: needs at least 2 points");
  const long last_piece = static_cast<long>(points.size()) - 2;
  long i = static_cast<long>(u);
  if (i > last_piece) i = last_piece;
  if (i < 0) i = 0;
  return piece_point(points, i, u - static_cast<double>(i), interpolant);
}

std::vector<Vec2> resample_open_curve(const std::vector<Vec2>& points, int samples, Interpolant interpolant) {
  if (points.size() < 2 || samples < 2) throw std::invalid_argument("resample_open_curve: needs ≥ 2 points and samples");
  const long pieces = static_cast<long>(points.size()) - 1;
  const long steps = samples - 1;
  std::vector<Vec2> out;
  out.reserve(static_cast<std::size_t>(samples));
  for (long k = 0; k <= steps; ++k) {
    // u = pieces·k/steps split exactly into piece index and fraction (integer arithmetic).
    long i = (pieces * k) / steps;
    long rem = (pieces * k) % steps;
    if (i == pieces) { i = pieces - 1; rem = steps; }
    if (rem == 0) { out.push_back(points[static_cast<std::size_t>(i)]); continue; }
    out.push_back(piece_point(points, i, static_cast<double>(rem) / static_cast<double>(steps), interpolant));
  }
  out.back() = points.back();
  return out;
}

}  // namespace jellysim::geometry
