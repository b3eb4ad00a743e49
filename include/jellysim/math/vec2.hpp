#pragma once
// Small 2D vector and 2x2 matrix types used by the elastic model and geometry.
#include <cmath>

namespace jellysim {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2& operator+=(Vec2 o) { x += o.x; y += o.y; return *this; }
  constexpr Vec2& operator-=(Vec2 o) { x -= o.x; y -= o.y; return *this; }
  constexpr Vec2& operator*=(double s) { x *= s; y *= s; return *this; }
  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
  friend constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
  friend constexpr Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
  friend constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
  friend constexpr bool operator==(Vec2 a, Vec2 b) = default;
};

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// z-component of the 3D cross product of (a, 0) and (b, 0).
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// a rotated by +90 degrees.
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }
/// a rotated counter-clockwise by `angle` radians.
inline Vec2 rotated(Vec2 a, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}
constexpr double norm_squared(Vec2 a) { return dot(a, a); }

/// 2x2 matrix, row-major: [[xx, xy], [yx, yy]].
struct Mat2 {
  double xx = 0.0, xy = 0.0, yx = 0.0, yy = 0.0;

  static constexpr Mat2 identity() { return {1.0, 0.0, 0.0, 1.0}; }
  static constexpr Mat2 outer(Vec2 a, Vec2 b) { return {a.x * b.x, a.x * b.y, a.y * b.x, a.y * b.y}; }
  friend constexpr Mat2 operator+(Mat2 a, Mat2 b) { return {a.xx + b.xx, a.xy + b.xy, a.yx + b.yx, a.yy + b.yy}; }
  friend constexpr Mat2 operator-(Mat2 a, Mat2 b) { return {a.xx - b.xx, a.xy - b.xy, a.yx - b.yx, a.yy - b.yy}; }
  friend constexpr Mat2 operator-(Mat2 a) { return {-a.xx, -a.xy, -a.yx, -a.yy}; }
  friend constexpr Mat2 operator*(double s, Mat2 a) { return {s * a.xx, s * a.xy, s * a.yx, s * a.yy}; }
  friend constexpr Vec2 operator*(Mat2 m, Vec2 v) { return {m.xx * v.x + m.xy * v.y, m.yx * v.x + m.yy * v.y}; }
};

}  // namespace jellysim
