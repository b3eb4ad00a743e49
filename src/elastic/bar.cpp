#include "jellysim/elastic/bar.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace jellysim::elastic {

namespace {

template <typename T>
void require(bool ok, const char* field, T value, const char* range) {
  if (ok) return;
  std::ostringstream message;
  message << "bar." << field << " = " << value << " is out of range " << range;
  throw std::invalid_argument(message.str());
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }
bool non_negative(double v) { return v >= 0.0 && std::isfinite(v); }

void validate(const BarSpec& s) {
  require(positive(s.length), "length", s.length, "(0, inf)");
  require(positive(s.width), "width", s.width, "(0, inf)");
  require(s.segments >= 1 && s.segments <= 10000, "segments", s.segments, "[1, 10000]");
  require(positive(s.point_mass), "point_mass", s.point_mass, "(0, inf)");
  require(positive(s.stiffness), "stiffness", s.stiffness, "(0, inf)");
  require(non_negative(s.angular_stiffness), "angular_stiffness", s.angular_stiffness, "[0, inf)");
  require(std::isfinite(s.angle_rad), "angle_rad", s.angle_rad, "(-inf, inf)");
  require(non_negative(s.drag), "drag", s.drag, "[0, inf)");
  require(std::isfinite(s.pivot.x), "pivot.x", s.pivot.x, "(-inf, inf)");
  require(std::isfinite(s.pivot.y), "pivot.y", s.pivot.y, "(-inf, inf)");
  require(std::isfinite(s.gravity.x), "gravity.x", s.gravity.x, "(-inf, inf)");
  require(std::isfinite(s.gravity.y), "gravity.y", s.gravity.y, "(-inf, inf)");
}

void add_row_points(const BarSpec& s, double offset_down, Body& body) {
  const double dx = s.length / s.segments;
  for (int c = 0; c <= s.segments; ++c) {
    const Vec2 local{c * dx, -offset_down};
    const PointKind kind = (c == 0 && offset_down == 0.0) ? PointKind::Pinned : PointKind::Free;
    body.add_point(s.pivot + rotated(local, s.angle_rad), s.point_mass, kind);
  }
}

void add_springs(const BarSpec& s, Body& body) {
  const int n = s.segments;
  const auto top = [](int c) { return c; };
  const auto bottom = [n](int c) { return n + 1 + c; };
  for (int c = 0; c <= n; ++c) body.add_linear_spring(top(c), bottom(c), s.stiffness);
  for (int c = 0; c < n; ++c) {
    body.add_linear_spring(top(c), top(c + 1), s.stiffness);
    body.add_linear_spring(bottom(c), bottom(c + 1), s.stiffness);
    body.add_linear_spring(top(c), bottom(c + 1), s.stiffness);
    body.add_linear_spring(bottom(c), top(c + 1), s.stiffness);
  }
  if (s.angular_stiffness == 0.0) return;
  constexpr double at_rest = std::numeric_limits<double>::quiet_NaN();
  for (int c = 1; c < n; ++c) {
    body.add_angular_spring(top(c - 1), top(c), top(c + 1), s.angular_stiffness, at_rest);
    body.add_angular_spring(bottom(c - 1), bottom(c), bottom(c + 1), s.angular_stiffness, at_rest);
  }
}

}  // namespace

Body make_bar(const BarSpec& spec) {
  validate(spec);
  Body body;
  body.gravity = spec.gravity;
  body.drag_coefficient = spec.drag;
  add_row_points(spec, 0.0, body);
  add_row_points(spec, spec.width, body);
  add_springs(spec, body);
  return body;
}

}  // namespace jellysim::elastic
