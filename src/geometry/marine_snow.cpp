#include "jellysim/geometry/marine_snow.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace jellysim::geometry {

namespace {

constexpr double kGoldenAngle = 2.399963229728653;  // π (3 − √5)

}  // namespace

MarineSnow::MarineSnow(const std::vector<Vec2>& first_frame, double axis_x_m, const std::array<Vec3, 2>& box,
                       double radius_m, double density)
    : axis_x_(axis_x_m), radius_(radius_m) {
  if (!(radius_m > 0.0)) throw std::invalid_argument("marine snow: the speck size must be > 0");
  if (!(density >= 0.0 && density <= 1.0)) throw std::invalid_argument("marine snow: the density must be in [0, 1]");
  std::size_t candidate = 0;
  for (std::size_t i = 0; i < first_frame.size(); ++i) {
    const Vec3 p = place(i, first_frame[i]);
    if (p.x >= box[0].x && p.x <= box[1].x && p.y >= box[0].y && p.y <= box[1].y && p.z >= box[0].z && p.z <= box[1].z) {
      const double k = static_cast<double>(candidate++);
      if (std::floor((k + 1.0) * density) > std::floor(k * density)) kept_.push_back(i);
    }
  }
}

Vec3 MarineSnow::place(std::size_t particle, Vec2 slice) const {
  const double theta = std::fmod(kGoldenAngle * static_cast<double>(particle), 2.0 * std::numbers::pi);
  const double r = slice.x - axis_x_;
  return {axis_x_ + r * std::cos(theta), slice.y, r * std::sin(theta)};
}

void MarineSnow::append(const std::vector<Vec2>& tracers, Mesh& mesh) const {
  // A regular tetrahedron about each particle, counter-clockwise seen from outside.
  static const Vec3 kCorners[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  static const std::uint32_t kFaces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  const auto first_index = static_cast<std::uint32_t>(mesh.indices.size());
  for (std::size_t i : kept_) {
    if (i >= tracers.size()) throw std::invalid_argument("marine snow: a frame has fewer tracers than the first");
    const Vec3 centre = place(i, tracers[i]);
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (const Vec3& c : kCorners) {
      const Vec3 n = normalized(c);
      mesh.positions.push_back(centre + radius_ * n);
      mesh.normals.push_back(n);
    }
    for (const auto& f : kFaces)
      for (std::uint32_t v : f) mesh.indices.push_back(base + v);
  }
  const auto count = static_cast<std::uint32_t>(mesh.indices.size()) - first_index;
  if (count > 0) mesh.parts.push_back({"snow", first_index, count});
}

}  // namespace jellysim::geometry
