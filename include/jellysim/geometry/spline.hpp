#pragma once
// Cubic interpolation of the 2D rendering model (thesis §7.2, eq. 7.8).
//
// Eq. 7.8 writes the piece between x_i and x_{i+1} as Q_c(s) = P s³ + Q s² + R s + W with
//   P = (x_{i+2} − x_{i+1}) − (x_{i−1} − x_i),  Q = (x_{i−1} − x_i) − P,  R = x_{i+1} − x_{i−1},  W = x_i.
// Checked: Q_c(0) = x_i, Q_c(1) = x_{i+1}, Q_c'(0) = x_{i+1} − x_{i−1} and Q_c'(1) = x_{i+2} − x_i,
// which is the next piece's Q_c'(0): the curve interpolates and is C1. It is the cubic Hermite
// piece with central-difference tangents, i.e. Catmull–Rom with its tangents doubled (Catmull–Rom
// uses ½(x_{i+1} − x_{i−1})). Both are offered; the doubled tangents overshoot twice as far where
// the spacing changes abruptly, Catmull–Rom is the common choice (docs/rendering.md).
#include <string>
#include <vector>

#include "jellysim/math/vec2.hpp"

namespace jellysim::geometry {

enum class Interpolant {
  thesis_cubic,  ///< eq. 7.8 as printed (tangent x_{i+1} − x_{i−1})
  catmull_rom,   ///< uniform Catmull–Rom (tangent ½(x_{i+1} − x_{i−1}))
};

/// "thesis" or "catmull-rom"; throws InputError naming `field` otherwise.
Interpolant parse_interpolant(const std::string& name, const std::string& field);
std::string interpolant_name(Interpolant interpolant);

/// Power-basis coefficients P, Q, R, W of eq. 7.8 for the piece from x0 to x1 (xm1 = x_{i−1},
/// x2 = x_{i+2}).
struct CubicPiece {
  Vec2 p, q, r, w;
  Vec2 at(double s) const { return ((p * s + q) * s + r) * s + w; }
  Vec2 derivative(double s) const { return (3.0 * p * s + 2.0 * q) * s + r; }
};
CubicPiece cubic_piece(Vec2 xm1, Vec2 x0, Vec2 x1, Vec2 x2, Interpolant interpolant);

/// The C1 curve through `points` (open: phantom end points by linear extrapolation, x_{−1} =
/// 2x_0 − x_1), evaluated at parameter u ∈ [0, n − 1] (u = i + s on the piece from x_i to x_{i+1}).
Vec2 curve_point(const std::vector<Vec2>& points, double u, Interpolant interpolant);

/// `samples` points at uniformly spaced parameters from the first to the last point (both kept
/// exactly). Reversing the input reverses the output, so opposing pairs of a left–right ordered
/// curve stay opposing pairs: sample k pairs with sample samples − 1 − k. Needs ≥ 2 points and
/// samples ≥ 2.
std::vector<Vec2> resample_open_curve(const std::vector<Vec2>& points, int samples, Interpolant interpolant);

}  // namespace jellysim::geometry
