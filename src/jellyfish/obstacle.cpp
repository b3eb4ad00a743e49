#include "jellysim/jellyfish/obstacle.hpp"

#include "jellysim/jellyfish/segment_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace jellysim::jellyfish {

namespace {

void require(bool ok, const ObstacleSpec& spec, const std::string& field, const std::string& range) {
  if (!ok) throw std::invalid_argument(spec.name + ": field '" + field + "' is out of range " + range);
}

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

/// The closed polygon's edges, edge i from vertex i to vertex i + 1 (the last one closing it).
std::vector<Segment> edges(const std::vector<Vec2>& p) {
  std::vector<Segment> e(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) e[i] = {p[i], p[(i + 1) % p.size()]};
  return e;
}

bool polygon_self_intersects(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  return any_pair_crosses(
      edges(p), [](const Segment& a, const Segment& b) { return segments_cross(a[0], a[1], b[0], b[1]); },
      // Neighbouring edges meet at their shared vertex; the closing edge neighbours the first.
      [n](std::size_t i, std::size_t j) { return j == i + 1 || (i == 0 && j + 1 == n); });
}

}  // namespace

bool ObstacleMotion::moving() const {
  return velocity_m_per_s.x != 0 || velocity_m_per_s.y != 0 ||
         (frequency_hz > 0 && (amplitude_m.x != 0 || amplitude_m.y != 0));
}

Vec2 ObstacleMotion::offset(double t) const {
  return t * velocity_m_per_s + std::sin(2.0 * std::numbers::pi * frequency_hz * t) * amplitude_m;
}

Vec2 ObstacleMotion::velocity(double t) const {
  const double w = 2.0 * std::numbers::pi * frequency_hz;
  return velocity_m_per_s + (w * std::cos(w * t)) * amplitude_m;
}

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

bool point_in_polygon(Vec2 q, const std::vector<Vec2>& p) {
  bool inside = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
      inside = !inside;
  }
  return inside;
}

bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  std::vector<Segment> both = edges(a);
  const std::vector<Segment> eb = edges(b);
  both.insert(both.end(), eb.begin(), eb.end());
  const std::size_t na = a.size();
  if (any_pair_crosses(
          both, [](const Segment& p, const Segment& q) { return segments_cross(p[0], p[1], q[0], q[1]); },
          [na](std::size_t i, std::size_t j) { return (i < na) == (j < na); }))  // only an edge of each
    return true;
  return (!a.empty() && point_in_polygon(a.front(), b)) || (!b.empty() && point_in_polygon(b.front(), a));
}

void validate(const ObstacleSpec& s) {
  require(std::isfinite(s.centre_m.x) && std::isfinite(s.centre_m.y), s, "centre", "finite numbers");
  switch (s.shape) {
    case ObstacleShape::circle: require(s.radius_m > 0, s, "radius", "(0, inf) m"); break;
    case ObstacleShape::box: require(s.size_m.x > 0 && s.size_m.y > 0, s, "size", "(0, inf) m each"); break;
    case ObstacleShape::polygon: {
      require(s.vertices_m.size() >= 3, s, "points", "at least 3 vertices");
      if (polygon_self_intersects(s.vertices_m))
        throw std::invalid_argument(s.name + ": field 'points' describes a self-intersecting polygon");
      require(std::abs(polygon_area(s.vertices_m)) > 0, s, "points", "a polygon of non-zero area");
      break;
    }
  }
  require(s.tether_stiffness_n_per_m2 > 0, s, "tether_stiffness", "(0, inf) N/m²");
  require(s.tether_stiffness_n_per_m >= 0, s, "stiffness", "(0, inf) N/m");
  require(s.motion.frequency_hz >= 0, s, "frequency", "[0, inf) Hz");
}

std::vector<Vec2> obstacle_outline(const ObstacleSpec& s) {
  std::vector<Vec2> p;
  switch (s.shape) {
    case ObstacleShape::circle: {
      const int n = 256;
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * std::numbers::pi * k / n;
        p.push_back(s.centre_m + s.radius_m * Vec2{std::cos(a), std::sin(a)});
      }
      return p;
    }
    case ObstacleShape::box: {
      const Vec2 h = 0.5 * s.size_m;
      for (Vec2 c : {Vec2{-h.x, -h.y}, Vec2{h.x, -h.y}, Vec2{h.x, h.y}, Vec2{-h.x, h.y}})
        p.push_back(s.centre_m + rotated(c, s.angle_rad));
      return p;
    }
    case ObstacleShape::polygon:
      p = s.vertices_m;
      if (polygon_area(p) < 0) std::reverse(p.begin(), p.end());
      return p;
  }
  return p;
}

std::vector<Vec2> obstacle_markers(const ObstacleSpec& s, double max_spacing_m) {
  if (s.shape == ObstacleShape::circle) {
    // Evenly around the circle, exactly on it; an even count, so that the markers are mirror
    // images of each other about the circle's vertical and horizontal diameters.
    int n = std::max(8, static_cast<int>(std::ceil(2.0 * std::numbers::pi * s.radius_m / max_spacing_m)));
    n += n % 2;
    std::vector<Vec2> p;
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * std::numbers::pi * k / n;
      p.push_back(s.centre_m + s.radius_m * Vec2{std::cos(a), std::sin(a)});
    }
    return p;
  }
  // Polygons: every vertex, and evenly spaced points along each edge.
  const std::vector<Vec2> outline = obstacle_outline(s);
  std::vector<Vec2> p;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec2 a = outline[i], b = outline[(i + 1) % outline.size()];
    const int pieces = std::max(1, static_cast<int>(std::ceil(norm(b - a) / max_spacing_m)));
    for (int k = 0; k < pieces; ++k) p.push_back(a + (static_cast<double>(k) / pieces) * (b - a));
  }
  return p;
}

ObstacleParts add_obstacle(const ObstacleSpec& spec, double max_spacing_m, elastic::Body& body) {
  ObstacleParts parts;
  const ObstacleMotion motion = spec.motion;
  parts.shift = std::make_shared<Vec2>();
  std::shared_ptr<const Vec2> shift = parts.shift;
  constexpr double kMarkerMass = 1e-6;  // unused by the coupling: the markers are massless
  const std::vector<Vec2> starts = obstacle_markers(spec, max_spacing_m);
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const Vec2 start = starts[k];
    // The outline each marker stands for: half of each neighbouring gap on the closed outline.
    const double share = 0.5 * (norm(starts[(k + 1) % starts.size()] - start) +
                                norm(start - starts[(k + starts.size() - 1) % starts.size()]));
    const double tether = spec.tether_stiffness_n_per_m > 0 ? spec.tether_stiffness_n_per_m
                                                            : spec.tether_stiffness_n_per_m2 * share;
    const int marker = body.add_point(start, kMarkerMass);
    // Every target is prescribed (a fixed obstacle has a path that stays put), so that dragging
    // can move it through `shift`.
    const int target = body.add_prescribed_point([start, motion, shift](double t) {
      return elastic::PrescribedState{start + *shift + motion.offset(t), motion.velocity(t), {}};
    });
    body.add_linear_spring(marker, target, tether, 0.0);
    parts.markers.push_back(marker);
    parts.targets.push_back(target);
    parts.tethers.push_back(static_cast<int>(body.linear.size()) - 1);
  }
  return parts;
}

Vec2 obstacle_fluid_force(const ObstacleParts& parts, const elastic::Body& body) {
  // The tether pulls the marker with k (x_target − x_marker); the marker hands that force to the
  // fluid, so the fluid pushes the obstacle with the opposite: k (x_marker − x_target).
  Vec2 f{};
  for (std::size_t k = 0; k < parts.markers.size(); ++k) {
    const auto s = static_cast<std::size_t>(parts.tethers[k]);
    const Vec2 stretch = body.points.position[static_cast<std::size_t>(parts.markers[k])] -
                         body.points.position[static_cast<std::size_t>(parts.targets[k])];
    f += body.linear.stiffness[s] * stretch;
  }
  return f;
}

}  // namespace jellysim::jellyfish
