#include "jellysim/elastic/mirror.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace jellysim::elastic {

namespace {

Vec2 mirror_image(Vec2 p, double axis_x) { return {2.0 * axis_x - p.x, p.y}; }

bool close(double a, double b, double relative) {
  return std::abs(a - b) <= relative * std::max({1.0, std::abs(a), std::abs(b)});
}

}  // namespace

std::vector<int> mirror_partners(const Body& body, double axis_x_m, double tolerance_m) {
  const PointMasses& pts = body.points;
  const std::size_t n = pts.size();
  // Points sorted by height, so that candidates are found by a search over a narrow band.
  std::vector<int> by_y(n);
  for (std::size_t p = 0; p < n; ++p) by_y[p] = static_cast<int>(p);
  std::sort(by_y.begin(), by_y.end(), [&](int a, int b) {
    return pts.position[static_cast<std::size_t>(a)].y < pts.position[static_cast<std::size_t>(b)].y;
  });
  std::vector<int> partner(n, -1);
  for (std::size_t p = 0; p < n; ++p) {
    const Vec2 target = mirror_image(pts.position[p], axis_x_m);
    auto first = std::lower_bound(by_y.begin(), by_y.end(), target.y - tolerance_m, [&](int q, double y) {
      return pts.position[static_cast<std::size_t>(q)].y < y;
    });
    for (auto it = first; it != by_y.end(); ++it) {
      const auto q = static_cast<std::size_t>(*it);
      if (pts.position[q].y > target.y + tolerance_m) break;
      if (norm(pts.position[q] - target) <= tolerance_m && pts.kind[q] == pts.kind[p] &&
          close(pts.mass[q], pts.mass[p], 1e-12)) {
        partner[p] = static_cast<int>(q);
        break;
      }
    }
    if (partner[p] < 0) return {};
  }
  for (std::size_t p = 0; p < n; ++p)
    if (partner[static_cast<std::size_t>(partner[p])] != static_cast<int>(p)) return {};  // not an involution
  return partner;
}

bool springs_mirror_symmetric(const Body& body, const std::vector<int>& partners) {
  if (partners.size() != body.points.size()) return false;
  auto m = [&](int p) { return partners[static_cast<std::size_t>(p)]; };
  std::multimap<std::pair<int, int>, std::size_t> linear;
  for (std::size_t s = 0; s < body.linear.size(); ++s)
    linear.emplace(std::minmax(body.linear.i[s], body.linear.j[s]), s);
  for (std::size_t s = 0; s < body.linear.size(); ++s) {
    const auto [lo, hi] = linear.equal_range(std::minmax(m(body.linear.i[s]), m(body.linear.j[s])));
    const bool found = std::any_of(lo, hi, [&](const auto& e) {
      return close(body.linear.stiffness[e.second], body.linear.stiffness[s], 1e-9) &&
             close(body.linear.rest_length[e.second], body.linear.rest_length[s], 1e-9);
    });
    if (!found) return false;
  }
  // A reflection negates the signed turning angle; so does walking the joint the other way round.
  std::multimap<std::tuple<int, int, int>, std::size_t> angular;
  for (std::size_t s = 0; s < body.angular.size(); ++s)
    angular.emplace(std::tuple{body.angular.j[s], body.angular.i[s], body.angular.k[s]}, s);
  for (std::size_t s = 0; s < body.angular.size(); ++s) {
    const int i = m(body.angular.i[s]), j = m(body.angular.j[s]), k = m(body.angular.k[s]);
    auto matches = [&](std::tuple<int, int, int> key, double expected_rest) {
      const auto [lo, hi] = angular.equal_range(key);
      return std::any_of(lo, hi, [&](const auto& e) {
        return close(body.angular.stiffness[e.second], body.angular.stiffness[s], 1e-9) &&
               std::abs(body.angular.rest_angle[e.second] - expected_rest) <= 1e-9;
      });
    };
    const double rest = body.angular.rest_angle[s];
    if (!matches({j, i, k}, -rest) && !matches({j, k, i}, rest)) return false;
  }
  return true;
}

void keep_mirror_symmetric_part(Body& body, const std::vector<int>& partners, double axis_x_m) {
  PointMasses& pts = body.points;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const auto q = static_cast<std::size_t>(partners[p]);
    if (q < p || pts.kind[p] != PointKind::Free) continue;  // each pair once
    const Vec2 x{0.5 * (pts.position[p].x + 2.0 * axis_x_m - pts.position[q].x),
                 0.5 * (pts.position[p].y + pts.position[q].y)};
    const Vec2 v{0.5 * (pts.velocity[p].x - pts.velocity[q].x), 0.5 * (pts.velocity[p].y + pts.velocity[q].y)};
    pts.position[p] = x;
    pts.velocity[p] = v;
    pts.position[q] = mirror_image(x, axis_x_m);
    pts.velocity[q] = {-v.x, v.y};
  }
}

}  // namespace jellysim::elastic
