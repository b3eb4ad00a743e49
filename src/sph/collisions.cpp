#include "jellysim/sph/collisions.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::sph {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Closest point parameter u in [0, 1] of x on segment a–b.
double closest_parameter(Vec2 a, Vec2 b, Vec2 x) {
  const Vec2 e = b - a;
  const double len2 = norm_squared(e);
  return len2 > 0.0 ? std::clamp(dot(x - a, e) / len2, 0.0, 1.0) : 0.0;
}

double segment_distance(Vec2 a, Vec2 b, Vec2 x) { return norm(x - (a + (b - a) * closest_parameter(a, b, x))); }

/// Outward unit normal of a counter-clockwise edge a → b (its right-hand side).
Vec2 outward_normal(Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double len = norm(e);
  return len > 0.0 ? Vec2{e.y / len, -e.x / len} : Vec2{0.0, 0.0};
}

/// Smallest root in [0, 1] of c0 + c1 τ + c2 τ², or +inf.
double first_root(double c0, double c1, double c2) {
  const double scale = std::abs(c0) + std::abs(c1) + std::abs(c2);
  if (std::abs(c2) <= 1e-14 * scale) {
    if (c1 == 0.0) return kInf;
    const double t = -c0 / c1;
    return (t >= 0.0 && t <= 1.0) ? t : kInf;
  }
  const double disc = c1 * c1 - 4.0 * c2 * c0;
  if (disc < 0.0) return kInf;
  const double sq = std::sqrt(disc);
  // Numerically stable pair of roots.
  const double q = -0.5 * (c1 + (c1 >= 0.0 ? sq : -sq));
  double r1 = q / c2, r2 = q != 0.0 ? c0 / q : r1;
  if (r1 > r2) std::swap(r1, r2);
  if (r1 >= 0.0 && r1 <= 1.0) return r1;
  if (r2 >= 0.0 && r2 <= 1.0) return r2;
  return kInf;
}

Vec2 lerp(Vec2 a, Vec2 b, double t) { return a + (b - a) * t; }

}  // namespace

void CollisionOutline::add_loop(const std::vector<int>& ccw_points) {
  for (std::size_t k = 0; k < ccw_points.size(); ++k) {
    a.push_back(ccw_points[k]);
    b.push_back(ccw_points[(k + 1) % ccw_points.size()]);
  }
}

double boundary_width(const CollisionOutline& outline, const std::vector<Vec2>& x) {
  double width = kInf;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    for (std::size_t e = 0; e < outline.size(); ++e) {
      const int p = outline.a[k];
      const int ea = outline.a[e], eb = outline.b[e];
      if (p == ea || p == eb) continue;
      // Skip edges touching an edge that contains p (the neighbours along the outline).
      bool adjacent = false;
      for (std::size_t f = 0; f < outline.size() && !adjacent; ++f) {
        const bool contains_p = outline.a[f] == p || outline.b[f] == p;
        const bool touches_e = outline.a[f] == ea || outline.b[f] == ea || outline.a[f] == eb || outline.b[f] == eb;
        adjacent = contains_p && touches_e;
      }
      if (adjacent) continue;
      width = std::min(width, segment_distance(x[static_cast<std::size_t>(ea)], x[static_cast<std::size_t>(eb)],
                                               x[static_cast<std::size_t>(p)]));
    }
  }
  return width;
}

bool inside_outline(const CollisionOutline& outline, const std::vector<Vec2>& points, Vec2 x) {
  bool inside = false;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const Vec2 a = points[static_cast<std::size_t>(outline.a[k])], b = points[static_cast<std::size_t>(outline.b[k])];
    if ((a.y > x.y) != (b.y > x.y)) {
      const double xc = a.x + (x.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x.x < xc) inside = !inside;
    }
  }
  return inside;
}

// Eqs. 5.22-5.27 along the axis c: the normal components follow the 1D elastic collision,
// u_p' = ((m_p − m_e) u_p + 2 m_e u_e)/(m_p + m_e) and symmetrically; tangential parts are kept.
// Equal masses swap their normal components (eq. 5.26); an infinite mass reflects the particle.
PairResult collide_pair(Vec2 v_particle, double m_particle, Vec2 v_endpoint, double m_endpoint, Vec2 c) {
  const double up = dot(v_particle, c), ue = dot(v_endpoint, c);
  if (up - ue >= 0.0) return {v_particle, v_endpoint};  // separating: no exchange
  double up_new = 0.0, ue_new = ue;
  if (std::isinf(m_endpoint)) {
    up_new = 2.0 * ue - up;
  } else {
    const double total = m_particle + m_endpoint;
    up_new = ((m_particle - m_endpoint) * up + 2.0 * m_endpoint * ue) / total;
    ue_new = ((m_endpoint - m_particle) * ue + 2.0 * m_particle * up) / total;
  }
  return {v_particle + c * (up_new - up), v_endpoint + c * (ue_new - ue)};
}

CollisionHandler::Hit CollisionHandler::find_crossing(const MovingPoints& body, const CollisionOutline& outline,
                                                      Vec2 p0, Vec2 p1) const {
  Hit best;
  double best_tau = kInf;
  const auto& x0 = *body.start;
  const auto& x1 = *body.end;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const auto ia = static_cast<std::size_t>(outline.a[k]), ib = static_cast<std::size_t>(outline.b[k]);
    const Vec2 e0 = x0[ib] - x0[ia], de = (x1[ib] - x1[ia]) - e0;
    const Vec2 q0 = p0 - x0[ia], dq = (p1 - x1[ia]) - q0;
    const double c0 = cross(e0, q0);
    if (c0 >= 0.0) continue;  // not on the outer side at the start
    const double tau = first_root(c0, cross(e0, dq) + cross(de, q0), cross(de, dq));
    if (!(tau < best_tau)) continue;
    const Vec2 a = lerp(x0[ia], x1[ia], tau), b = lerp(x0[ib], x1[ib], tau), p = lerp(p0, p1, tau);
    const Vec2 e = b - a;
    const double u = dot(p - a, e) / norm_squared(e);
    if (u < 0.0 || u > 1.0) continue;  // passed the line beside the edge
    best_tau = tau;
    best.edge = static_cast<int>(k);
    best.contact = p;
  }
  return best;
}

CollisionHandler::Hit CollisionHandler::find_edge_for_inside(const MovingPoints& body, const CollisionOutline& outline,
                                                             Vec2 p, Vec2 v) const {
  const auto& x = *body.end;
  Hit along, nearest;
  double best_lambda = kInf, best_distance = kInf;
  const double speed = norm(v);
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const Vec2 a = x[static_cast<std::size_t>(outline.a[k])], b = x[static_cast<std::size_t>(outline.b[k])];
    const Vec2 e = b - a;
    if (speed > 0.0) {  // line p + λ v against the segment a + u e
      const double denom = cross(v, e);
      if (denom != 0.0) {
        const double lambda = cross(a - p, e) / denom, u = cross(a - p, v) / denom;
        if (u >= 0.0 && u <= 1.0 && std::abs(lambda) < best_lambda) {
          best_lambda = std::abs(lambda);
          along = {static_cast<int>(k), p + v * lambda};
        }
      }
    }
    const double u = closest_parameter(a, b, p);
    const double d = norm(p - (a + e * u));
    if (d < best_distance) {
      best_distance = d;
      nearest = {static_cast<int>(k), a + e * u};
    }
  }
  return along.edge >= 0 ? along : nearest;
}

// Eqs. 5.28-5.30: collide with each endpoint, blend by s, apply Δv from the start of the step.
void CollisionHandler::respond(const MovingPoints& particles, std::size_t p, const MovingPoints& body,
                               const CollisionOutline& outline, const Hit& hit, double dt_s) const {
  const auto ia = static_cast<std::size_t>(outline.a[static_cast<std::size_t>(hit.edge)]);
  const auto ib = static_cast<std::size_t>(outline.b[static_cast<std::size_t>(hit.edge)]);
  auto& xb = *body.end;
  auto& vb = *body.velocity;
  const Vec2 c = outward_normal(xb[ia], xb[ib]);
  const double da = norm(xb[ia] - hit.contact), db = norm(xb[ib] - hit.contact);
  const double s = da + db > 0.0 ? da / (da + db) : 0.5;  // eq. 5.28
  Vec2& vp = (*particles.velocity)[p];
  const double mp = (*particles.mass)[p];
  const PairResult ra = collide_pair(vp, mp, vb[ia], (*body.mass)[ia], c);
  const PairResult rb = collide_pair(vp, mp, vb[ib], (*body.mass)[ib], c);
  const Vec2 vp_new = ra.particle * (1.0 - s) + rb.particle * s;  // eq. 5.29
  const Vec2 va_new = ra.endpoint * (1.0 - s) + vb[ia] * s;       // eq. 5.30
  const Vec2 vb_new = rb.endpoint * s + vb[ib] * (1.0 - s);
  (*particles.end)[p] += (vp_new - vp) * dt_s;
  vp = vp_new;
  if (!std::isinf((*body.mass)[ia])) {
    xb[ia] += (va_new - vb[ia]) * dt_s;
    vb[ia] = va_new;
  }
  if (!std::isinf((*body.mass)[ib])) {
    xb[ib] += (vb_new - vb[ib]) * dt_s;
    vb[ib] = vb_new;
  }
}

namespace {

/// Outward direction at the point at parameter u of edge k: the edge normal inside the edge, the
/// bisector of the two edge normals at a vertex (it lies in the exterior wedge whether the vertex
/// is convex or reflex).
Vec2 outward_direction(const CollisionOutline& outline, const std::vector<Vec2>& x, std::size_t k, double u) {
  const Vec2 n = outward_normal(x[static_cast<std::size_t>(outline.a[k])], x[static_cast<std::size_t>(outline.b[k])]);
  if (u > 0.0 && u < 1.0) return n;
  const int vertex = u <= 0.0 ? outline.a[k] : outline.b[k];
  for (std::size_t f = 0; f < outline.size(); ++f) {
    if (f == k || (outline.a[f] != vertex && outline.b[f] != vertex)) continue;
    const Vec2 m = outward_normal(x[static_cast<std::size_t>(outline.a[f])], x[static_cast<std::size_t>(outline.b[f])]);
    const Vec2 sum = n + m;
    const double len = norm(sum);
    return len > 1e-12 ? sum / len : n;
  }
  return n;
}

}  // namespace

// Puts p at least separation_m outside the edge when it lies within the edge's slab behind or on
// it, or inside the body; a point still inside after that (a strongly deformed body) is moved out
// along the outward direction at its nearest outline point, at growing distances.
void CollisionHandler::separate(const MovingPoints& body, const CollisionOutline& outline, int edge, Vec2& p) const {
  const auto& x = *body.end;
  const auto k = static_cast<std::size_t>(edge);
  const Vec2 a = x[static_cast<std::size_t>(outline.a[k])], b = x[static_cast<std::size_t>(outline.b[k])];
  const double u = closest_parameter(a, b, p);
  const Vec2 foot = a + (b - a) * u;
  if (dot(p - foot, outward_normal(a, b)) >= settings_.separation_m && !inside_outline(outline, x, p)) return;
  p = foot + outward_direction(outline, x, k, u) * settings_.separation_m;
  double distance = settings_.separation_m;
  for (int attempt = 0; attempt < 40 && inside_outline(outline, x, p); ++attempt) {
    std::size_t nearest = 0;
    double best = kInf, best_u = 0.0;
    for (std::size_t f = 0; f < outline.size(); ++f) {
      const Vec2 fa = x[static_cast<std::size_t>(outline.a[f])], fb = x[static_cast<std::size_t>(outline.b[f])];
      const double fu = closest_parameter(fa, fb, p);
      const double d = norm(p - (fa + (fb - fa) * fu));
      if (d < best) { best = d; nearest = f; best_u = fu; }
    }
    const Vec2 fa = x[static_cast<std::size_t>(outline.a[nearest])], fb = x[static_cast<std::size_t>(outline.b[nearest])];
    distance *= 2.0;
    p = fa + (fb - fa) * best_u + outward_direction(outline, x, nearest, best_u) * distance;
  }
}

bool CollisionHandler::trapped(const MovingPoints& body, const CollisionOutline& outline, const std::vector<Wall>& walls,
                               int edge, Vec2 p) const {
  if (settings_.trap_radius_m <= 0.0) return false;
  const auto& x = *body.end;
  const auto ek = static_cast<std::size_t>(edge);
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const bool shares = outline.a[k] == outline.a[ek] || outline.a[k] == outline.b[ek] ||
                        outline.b[k] == outline.a[ek] || outline.b[k] == outline.b[ek];
    if (shares) continue;
    const Vec2 a = x[static_cast<std::size_t>(outline.a[k])], b = x[static_cast<std::size_t>(outline.b[k])];
    if (segment_distance(a, b, p) < settings_.trap_radius_m) return true;
  }
  for (const Wall& w : walls) {
    if (w.distance(p) < settings_.trap_radius_m) return true;
  }
  return false;
}

CollisionStatistics CollisionHandler::handle(const MovingPoints& particles, const MovingPoints& body,
                                             const CollisionOutline& outline, const std::vector<Wall>& walls,
                                             double dt_s) {
  CollisionStatistics stats;
  if (body.end != nullptr) {
    for (std::size_t i = 0; i < body.end->size(); ++i) {
      if (!std::isinf((*body.mass)[i]) && reflect_from_walls(walls, (*body.end)[i], (*body.velocity)[i])) {
        ++stats.wall_collisions;
      }
    }
  }
  const bool has_outline = body.end != nullptr && outline.size() > 0;
  // Box around the body at the start and end of the step: particles whose path misses it cannot
  // collide (it moves as particles push the body, so it is recomputed after each collision).
  Vec2 lo{kInf, kInf}, hi{-kInf, -kInf};
  const auto update_box = [&] {
    lo = {kInf, kInf};
    hi = {-kInf, -kInf};
    for (const auto* points : {body.start, static_cast<const std::vector<Vec2>*>(body.end)}) {
      for (Vec2 q : *points) {
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
      }
    }
  };
  if (has_outline) update_box();
  for (std::size_t p = 0; p < particles.end->size(); ++p) {
    Vec2& x = (*particles.end)[p];
    const Vec2 x0 = (*particles.start)[p];
    const bool near = std::max(x.x, x0.x) >= lo.x && std::min(x.x, x0.x) <= hi.x && std::max(x.y, x0.y) >= lo.y &&
                      std::min(x.y, x0.y) <= hi.y;
    if (has_outline && near) {
      Hit hit = find_crossing(body, outline, (*particles.start)[p], x);
      if (hit.edge < 0 && inside_outline(outline, *body.end, x)) {
        hit = find_edge_for_inside(body, outline, x, (*particles.velocity)[p]);
      }
      if (hit.edge >= 0) {
        ++stats.edge_collisions;
        respond(particles, p, body, outline, hit, dt_s);
        separate(body, outline, hit.edge, x);
        if (trapped(body, outline, walls, hit.edge, x)) {  // re-aim along the collided edge (§5.2.2)
          ++stats.trapped;
          const auto& xb = *body.end;
          const auto ek = static_cast<std::size_t>(hit.edge);
          Vec2 t = xb[static_cast<std::size_t>(outline.b[ek])] - xb[static_cast<std::size_t>(outline.a[ek])];
          t = t / norm(t);
          Vec2& v = (*particles.velocity)[p];
          v = t * (dot(v, t) >= 0.0 ? norm(v) : -norm(v));
          // Keep it in the gap: just outside the collided edge, where it met it.
          const Vec2 a = xb[static_cast<std::size_t>(outline.a[ek])];
          const Vec2 foot = a + t * dot(x - a, t);
          x = foot + Vec2{t.y, -t.x} * settings_.separation_m;
        }
        update_box();
      }
    }
    if (reflect_from_walls(walls, x, (*particles.velocity)[p])) ++stats.wall_collisions;
  }
  return stats;
}

}  // namespace jellysim::sph
