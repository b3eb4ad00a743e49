#include "jellysim/geometry/synthetic_bell.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw InputError("synthetic bell: " + message);
}

/// Umbrella point at angle θ ∈ [−π/2, π/2] for a given contraction (relative to the aperture centre).
Vec2 bell_point(const SyntheticBell& s, double theta, double contraction) {
  const double shrink = 1.0 - contraction * (1.0 - s.max_contraction) * std::abs(std::sin(theta));
  const double radius = 0.5 * s.diameter_m * shrink;
  const double height = s.height_m * (1.0 + 0.2 * contraction);
  return {radius * std::sin(theta), height * std::cos(theta)};
}

std::vector<Vec2> tentacle(const SyntheticBell& s, Vec2 root, double side) {
  std::vector<Vec2> strand;
  const double step = s.tentacle_length_m / (s.tentacle_points - 1);
  Vec2 p = root;
  for (int m = 0; m < s.tentacle_points; ++m) {
    strand.push_back(p);
    // Hangs down, flaring outward when expanded and trailing inward when contracted.
    const double t = static_cast<double>(m) / (s.tentacle_points - 1);
    const double angle = (0.25 - 0.55 * s.contraction) * (0.3 + t);
    p += step * Vec2{side * std::sin(angle), -std::cos(angle)};
  }
  return strand;
}

}  // namespace

jellyfish::SliceFrame synthetic_bell(const SyntheticBell& s) {
  require(s.diameter_m > 0 && std::isfinite(s.diameter_m), "diameter_m must be in (0, inf)");
  require(s.height_m > 0 && std::isfinite(s.height_m), "height_m must be in (0, inf)");
  require(s.contraction >= 0 && s.contraction <= 1, "contraction must be in [0, 1]");
  require(s.max_contraction > 0 && s.max_contraction <= 1, "max_contraction must be in (0, 1]");
  require(s.umbrella_points >= 5 && s.umbrella_points % 2 == 1, "umbrella_points must be odd and ≥ 5");
  require(s.tentacle_points == 0 || s.tentacle_points >= 2, "tentacle_points must be 0 or ≥ 2");
  require(s.thickness_m > 0 && std::isfinite(s.thickness_m), "thickness_m must be in (0, inf)");
  require(s.tentacle_length_m > 0 && std::isfinite(s.tentacle_length_m), "tentacle_length_m must be in (0, inf)");

  jellyfish::SliceFrame frame;
  frame.time_s = s.time_s;
  frame.thickness_m = s.thickness_m;
  frame.axis = {0.0, 1.0};
  const int n = s.umbrella_points;
  std::vector<Vec2> expanded;
  for (int k = 0; k < n; ++k) {
    const double theta = std::numbers::pi * (static_cast<double>(k) / (n - 1) - 0.5);
    frame.umbrella.push_back(s.aperture_centre_m + bell_point(s, theta, s.contraction));
    expanded.push_back(bell_point(s, theta, 0.0));
  }
  for (int k = 0; k < n / 2; ++k) {
    const int b = n - 1 - k;
    frame.muscles.push_back({k, b, norm(frame.umbrella[static_cast<std::size_t>(b)] - frame.umbrella[static_cast<std::size_t>(k)]),
                             norm(expanded[static_cast<std::size_t>(b)] - expanded[static_cast<std::size_t>(k)])});
  }
  if (s.tentacle_points > 0) {
    frame.tentacles.push_back(tentacle(s, frame.umbrella.front(), -1.0));
    frame.tentacles.push_back(tentacle(s, frame.umbrella.back(), 1.0));
  }
  return frame;
}

jellyfish::SliceFrame synthetic_bell(double diameter_m, double height_m, double contraction, int umbrella_points,
                                     int tentacle_points) {
  SyntheticBell spec;
  spec.diameter_m = diameter_m;
  spec.height_m = height_m;
  spec.contraction = contraction;
  spec.umbrella_points = umbrella_points;
  spec.tentacle_points = tentacle_points;
  spec.thickness_m = 0.054 * height_m;
  spec.tentacle_length_m = 0.5 * height_m;
  return synthetic_bell(spec);
}

namespace {

/// The point at meridian radius r (from the axis x = axis_x) and height y, turned by σ about the axis.
Vec3 revolved(Vec2 p, double axis_x, double sigma) {
  const double r = p.x - axis_x;
  return {axis_x + r * std::cos(sigma), p.y, -r * std::sin(sigma)};
}

/// The apex fan and the quads between rings (ring m above ring m + 1), normals away from the cavity.
std::vector<std::array<std::uint32_t, 3>> revolved_triangles(int rings, int J) {
  const auto at = [J](int ring, int j) { return static_cast<std::uint32_t>(1 + (ring - 1) * J + (j % J)); };
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (int j = 0; j < J; ++j) triangles.push_back({0u, at(1, j), at(1, j + 1)});
  for (int m = 1; m < rings; ++m)
    for (int j = 0; j < J; ++j) {
      triangles.push_back({at(m, j), at(m + 1, j), at(m + 1, j + 1)});
      triangles.push_back({at(m, j), at(m + 1, j + 1), at(m, j + 1)});
    }
  return triangles;
}

}  // namespace

SurfaceFrames revolved_synthetic_bell(const std::vector<SyntheticBell>& specs, int ring_points, int strands) {
  require(!specs.empty(), "no frames asked for");
  require(ring_points >= 3, "ring_points must be ≥ 3");
  require(strands >= 0, "strands must be ≥ 0");
  SurfaceFrames out;
  out.thickness_m = specs.front().thickness_m;
  for (const SyntheticBell& spec : specs) {
    const jellyfish::SliceFrame slice = synthetic_bell(spec);
    const std::size_t apex = slice.umbrella.size() / 2;
    const double axis_x = spec.aperture_centre_m.x;
    std::vector<Vec3> surface{revolved(slice.umbrella[apex], axis_x, 0.0)};
    for (std::size_t m = apex + 1; m < slice.umbrella.size(); ++m)
      for (int j = 0; j < ring_points; ++j)
        surface.push_back(revolved(slice.umbrella[m], axis_x, 2.0 * std::numbers::pi * j / ring_points));
    std::vector<std::vector<Vec3>> tentacles(slice.tentacles.empty() ? 0 : static_cast<std::size_t>(strands));
    for (std::size_t t = 0; t < tentacles.size(); ++t)
      for (Vec2 p : slice.tentacles.back())
        tentacles[t].push_back(revolved(p, axis_x, 2.0 * std::numbers::pi * static_cast<double>(t) / strands));
    out.time_s.push_back(spec.time_s);
    out.surface.push_back(std::move(surface));
    out.tentacles.push_back(std::move(tentacles));
  }
  out.triangles = revolved_triangles(static_cast<int>(specs.front().umbrella_points / 2), ring_points);
  return out;
}

}  // namespace jellysim::geometry
