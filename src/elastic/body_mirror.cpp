#include "jellysim/elastic/body_mirror.hpp"

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

namespace {

using Partner = std::vector<int>;

int mirrored(const Partner& partners, int p) { return partners[static_cast<std::size_t>(p)]; }

/// Every two-point element s has an image on the partners' points (either order) for which
/// same(s, image) holds.
template <typename Same>
bool two_point_set_mirrored(const std::vector<int>& i, const std::vector<int>& j, const Partner& partners,
                            Same&& same) {
  std::multimap<std::pair<int, int>, std::size_t> by_ends;
  for (std::size_t s = 0; s < i.size(); ++s) by_ends.emplace(std::minmax(i[s], j[s]), s);
  for (std::size_t s = 0; s < i.size(); ++s) {
    const auto [lo, hi] = by_ends.equal_range(std::minmax(mirrored(partners, i[s]), mirrored(partners, j[s])));
    if (!std::any_of(lo, hi, [&](const auto& e) { return same(s, e.second); })) return false;
  }
  return true;
}

// A reflection negates the signed turning angle; so does walking the joint the other way round.
bool angular_mirrored(const AngularSprings& ang, const Partner& partners) {
  std::multimap<std::tuple<int, int, int>, std::size_t> by_points;
  for (std::size_t s = 0; s < ang.size(); ++s) by_points.emplace(std::tuple{ang.j[s], ang.i[s], ang.k[s]}, s);
  for (std::size_t s = 0; s < ang.size(); ++s) {
    const int i = mirrored(partners, ang.i[s]), j = mirrored(partners, ang.j[s]), k = mirrored(partners, ang.k[s]);
    auto matches = [&](std::tuple<int, int, int> key, double expected_rest) {
      const auto [lo, hi] = by_points.equal_range(key);
      return std::any_of(lo, hi, [&](const auto& e) {
        return close(ang.stiffness[e.second], ang.stiffness[s], 1e-9) &&
               std::abs(ang.rest_angle[e.second] - expected_rest) <= 1e-9;
      });
    };
    const double rest = ang.rest_angle[s];
    if (!matches({j, i, k}, -rest) && !matches({j, k, i}, rest)) return false;
  }
  return true;
}

// c = (x_r − x_m) × (x_m − x_l) changes sign under a reflection and when l and r swap: the image
// of (l, m, r; C) is (l', m', r'; −C) or (r', m', l'; C).
bool torsional_mirrored(const TorsionalBeams& tb, const Partner& partners) {
  std::multimap<std::tuple<int, int, int>, std::size_t> by_points;
  for (std::size_t s = 0; s < tb.size(); ++s) by_points.emplace(std::tuple{tb.j[s], tb.i[s], tb.k[s]}, s);
  for (std::size_t s = 0; s < tb.size(); ++s) {
    const int l = mirrored(partners, tb.i[s]), m = mirrored(partners, tb.j[s]), r = mirrored(partners, tb.k[s]);
    auto matches = [&](std::tuple<int, int, int> key, double expected_curvature) {
      const auto [lo, hi] = by_points.equal_range(key);
      return std::any_of(lo, hi, [&](const auto& e) {
        return close(tb.stiffness[e.second], tb.stiffness[s], 1e-9) &&
               close(tb.curvature[e.second], expected_curvature, 1e-9);
      });
    };
    const double c = tb.curvature[s];
    if (!matches({m, l, r}, -c) && !matches({m, r, l}, c)) return false;
  }
  return true;
}

// D = x_l − 2 x_m + x_r is symmetric in l and r, and a reflection about a vertical line negates
// its x-component: the image of (l, m, r; C) is (l', m', r' in either order; (−C_x, C_y)).
bool non_invariant_mirrored(const NonInvariantBeams& nb, const Partner& partners) {
  std::multimap<std::tuple<int, int, int>, std::size_t> by_points;
  const auto key = [](int l, int m, int r) { return std::tuple{m, std::min(l, r), std::max(l, r)}; };
  for (std::size_t s = 0; s < nb.size(); ++s) by_points.emplace(key(nb.i[s], nb.j[s], nb.k[s]), s);
  for (std::size_t s = 0; s < nb.size(); ++s) {
    const auto [lo, hi] = by_points.equal_range(
        key(mirrored(partners, nb.i[s]), mirrored(partners, nb.j[s]), mirrored(partners, nb.k[s])));
    const Vec2 expected{-nb.curvature[s].x, nb.curvature[s].y};
    const bool found = std::any_of(lo, hi, [&](const auto& e) {
      return close(nb.stiffness[e.second], nb.stiffness[s], 1e-9) &&
             close(nb.curvature[e.second].x, expected.x, 1e-9) && close(nb.curvature[e.second].y, expected.y, 1e-9);
    });
    if (!found) return false;
  }
  return true;
}

}  // namespace

bool springs_mirror_symmetric(const Body& body, const std::vector<int>& partners) {
  if (partners.size() != body.points.size()) return false;
  const LinearSprings& lin = body.linear;
  const PowerSprings& pw = body.power;
  const Dashpots& dp = body.dashpots;
  return two_point_set_mirrored(lin.i, lin.j, partners,
                                [&](std::size_t s, std::size_t e) {
                                  return close(lin.stiffness[e], lin.stiffness[s], 1e-9) &&
                                         close(lin.rest_length[e], lin.rest_length[s], 1e-9);
                                }) &&
         angular_mirrored(body.angular, partners) && torsional_mirrored(body.torsional, partners) &&
         non_invariant_mirrored(body.non_invariant, partners) &&
         two_point_set_mirrored(pw.i, pw.j, partners,
                                [&](std::size_t s, std::size_t e) {
                                  return close(pw.stiffness[e], pw.stiffness[s], 1e-9) &&
                                         close(pw.rest_length[e], pw.rest_length[s], 1e-9) &&
                                         close(pw.degree[e], pw.degree[s], 1e-9);
                                }) &&
         two_point_set_mirrored(dp.i, dp.j, partners, [&](std::size_t s, std::size_t e) {
           return close(dp.coefficient[e], dp.coefficient[s], 1e-9);
         });
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
