#include "jellysim/geometry/obstacle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

namespace jellysim::geometry {

namespace {

/// Twice the signed area (positive when counter-clockwise).
double twice_signed_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return a;
}

double squared_extent(const std::vector<Vec2>& p) {
  Vec2 lo = p.front(), hi = p.front();
  for (Vec2 q : p) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
  }
  return norm_squared(hi - lo);
}

/// Whether two edges that share no vertex cross or touch (orientation tests, `eps` an area).
bool edges_meet(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2, double eps) {
  const double d1 = cross(p2 - p1, q1 - p1), d2 = cross(p2 - p1, q2 - p1);
  const double d3 = cross(q2 - q1, p1 - q1), d4 = cross(q2 - q1, p2 - q1);
  const auto opposite = [eps](double a, double b) { return (a > eps && b < -eps) || (a < -eps && b > eps); };
  if (opposite(d1, d2) && opposite(d3, d4)) return true;
  const auto on_segment = [](Vec2 a, Vec2 b, Vec2 q) {
    return std::min(a.x, b.x) <= q.x && q.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= q.y && q.y <= std::max(a.y, b.y);
  };
  return (std::abs(d1) <= eps && on_segment(p1, p2, q1)) || (std::abs(d2) <= eps && on_segment(p1, p2, q2)) ||
         (std::abs(d3) <= eps && on_segment(q1, q2, p1)) || (std::abs(d4) <= eps && on_segment(q1, q2, p2));
}

bool crosses_itself(const std::vector<Vec2>& p, double eps) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // the closing edge is adjacent to the first
      if (edges_meet(p[i], p[i + 1], p[j], p[(j + 1) % n], eps)) return true;
    }
  return false;
}

/// Bends sharper than this between neighbouring side walls are drawn as edges (a box's corners);
/// gentler ones are smoothed (a circle's n markers are 360°/n apart: 12° for the 30 of a 3 cm ball on the default grid).
const double kSmoothCosine = std::cos(35.0 * std::numbers::pi / 180.0);

}  // namespace

// Ear clipping (Meisters' two-ears theorem): a convex vertex whose triangle with its neighbours
// holds no other vertex is cut off, until three remain.
std::vector<std::uint32_t> triangulate_polygon(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  if (n < 3) throw std::invalid_argument("a polygon needs at least 3 vertices, got " + std::to_string(n));
  const double eps = 1e-12 * squared_extent(p);  // cross products below are areas
  if (!(twice_signed_area(p) > eps)) throw std::invalid_argument("the polygon is clockwise or has no area");
  if (crosses_itself(p, eps)) throw std::invalid_argument("the polygon crosses or touches itself");
  std::vector<std::uint32_t> ring(n), triangles;
  std::iota(ring.begin(), ring.end(), 0u);
  triangles.reserve(3 * (n - 2));
  const auto turn = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) { return cross(p[b] - p[a], p[c] - p[b]); };
  const auto inside_or_on = [&](Vec2 q, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return cross(p[b] - p[a], q - p[a]) >= -eps && cross(p[c] - p[b], q - p[b]) >= -eps &&
           cross(p[a] - p[c], q - p[c]) >= -eps;
  };
  std::size_t i = 0, misses = 0;
  while (ring.size() > 3) {
    const std::size_t m = ring.size();
    i %= m;
    const std::uint32_t a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
    const double t = turn(a, b, c);
    bool cut = false, emit = false;
    if (std::abs(t) <= eps && dot(p[b] - p[a], p[c] - p[b]) > 0.0) {
      cut = true;  // b lies on a straight stretch: drop it, no triangle
    } else if (t > eps) {
      cut = emit = true;
      for (std::uint32_t v : ring) {
        if (v == a || v == b || v == c || p[v] == p[a] || p[v] == p[b] || p[v] == p[c]) continue;
        if (inside_or_on(p[v], a, b, c)) {
          cut = emit = false;
          break;
        }
      }
    }
    if (!cut) {
      ++i;
      if (++misses > m) throw std::invalid_argument("the polygon crosses or touches itself (no ear left to cut)");
      continue;
    }
    if (emit) triangles.insert(triangles.end(), {a, b, c});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
    misses = 0;
  }
  if (turn(ring[0], ring[1], ring[2]) > eps) triangles.insert(triangles.end(), {ring[0], ring[1], ring[2]});
  return triangles;
}

ObstaclePrisms::ObstaclePrisms(const std::vector<std::vector<Vec2>>& first, double depth_m)
    : half_depth_m_(0.5 * depth_m) {
  if (!(depth_m > 0.0 && std::isfinite(depth_m)))
    throw std::invalid_argument("obstacle depth = " + std::to_string(depth_m) + " m is out of range (0, inf)");
  for (std::size_t o = 0; o < first.size(); ++o) {
    Prism prism;
    prism.points = first[o].size();
    if (prism.points < 3)
      throw std::invalid_argument("obstacle " + std::to_string(o + 1) + " has " + std::to_string(prism.points) +
                                  " outline points; a prism needs at least 3");
    std::vector<Vec2> ccw = first[o];
    prism.reversed = twice_signed_area(ccw) < 0.0;
    if (prism.reversed) std::reverse(ccw.begin(), ccw.end());
    try {
      prism.cap = triangulate_polygon(ccw);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("obstacle " + std::to_string(o + 1) + ": " + e.what());
    }
    prisms_.push_back(std::move(prism));
  }
}

void ObstaclePrisms::append(const std::vector<std::vector<Vec2>>& outlines, Mesh& mesh) const {
  if (outlines.size() != prisms_.size())
    throw std::invalid_argument("expected " + std::to_string(prisms_.size()) + " obstacle outlines, got " +
                                std::to_string(outlines.size()));
  const auto first_index = static_cast<std::uint32_t>(mesh.indices.size());
  std::vector<Vec2> p;
  std::vector<Vec3> edge_normal;
  for (std::size_t o = 0; o < prisms_.size(); ++o) {
    const Prism& prism = prisms_[o];
    const std::size_t n = prism.points;
    if (outlines[o].size() != n)
      throw std::invalid_argument("obstacle " + std::to_string(o + 1) + " changed its outline point count");
    p = outlines[o];
    if (prism.reversed) std::reverse(p.begin(), p.end());
    Vec2 centroid{};
    for (Vec2 q : p) centroid += q / static_cast<double>(n);
    // Outward normal of edge k (p_k → p_k+1) of a counter-clockwise outline: the edge turned right.
    edge_normal.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 d = p[(k + 1) % n] - p[k];
      Vec3 e = normalized(Vec3{d.y, -d.x, 0.0});
      if (norm(e) == 0.0) e = normalized(lift(0.5 * (p[k] + p[(k + 1) % n]) - centroid));  // coincident markers
      edge_normal[k] = e;
    }
    // The wall's normal at vertex k seen from edge `side` (k − 1 or k): shared when the bend is gentle.
    const auto wall_normal = [&](std::size_t k, std::size_t side) {
      const Vec3 before = edge_normal[(k + n - 1) % n], after = edge_normal[k];
      return dot(before, after) >= kSmoothCosine ? normalized(before + after) : edge_normal[side];
    };
    const double h = half_depth_m_;
    for (std::size_t k = 0; k < n; ++k) {  // side walls: one quad per edge, four vertices of its own
      const std::size_t j = (k + 1) % n;
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      const Vec3 nk = wall_normal(k, k), nj = wall_normal(j, k);
      mesh.positions.insert(mesh.positions.end(), {Vec3{p[k].x, p[k].y, -h}, Vec3{p[j].x, p[j].y, -h},
                                                   Vec3{p[j].x, p[j].y, h}, Vec3{p[k].x, p[k].y, h}});
      mesh.normals.insert(mesh.normals.end(), {nk, nj, nj, nk});
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    for (const double z : {h, -h}) {  // caps: the outline's triangulation, reversed underneath
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      for (Vec2 q : p) {
        mesh.positions.push_back({q.x, q.y, z});
        mesh.normals.push_back({0.0, 0.0, z > 0.0 ? 1.0 : -1.0});
      }
      for (std::size_t t = 0; t + 2 < prism.cap.size(); t += 3) {
        const std::uint32_t a = base + prism.cap[t], b = base + prism.cap[t + 1], c = base + prism.cap[t + 2];
        if (z > 0.0)
          mesh.indices.insert(mesh.indices.end(), {a, b, c});
        else
          mesh.indices.insert(mesh.indices.end(), {a, c, b});
      }
    }
  }
  const auto count = static_cast<std::uint32_t>(mesh.indices.size()) - first_index;
  if (count > 0) mesh.parts.push_back({"obstacles", first_index, count});
}

}  // namespace jellysim::geometry
