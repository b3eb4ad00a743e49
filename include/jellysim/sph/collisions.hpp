#pragma once
// Collisions between free particles (SPH fluid or solid point masses) and the boundary edges of a
// spring-mass body (thesis §5.2.1–5.2.2), and of both with static walls.
//
// Detection (§5.2.2): positions move linearly over the step. A particle collides with an edge when
// it enters the region the edge sweeps during the step: the side function
// f(τ) = (B(τ) − A(τ)) × (P(τ) − A(τ)) turns from outside (< 0) to inside with the foot of P on the
// edge; the earliest such τ over all edges wins. Because the body is an area, a particle found
// inside it at the end of the step also collides; its edge is the nearest one met by the line
// through the particle along its velocity (forwards or backwards), or the nearest edge when the
// particle is at rest (Figure 5.6).
//
// Response (§5.2.1): with the edge's outward normal c as the axis, the particle collides elastically
// with each endpoint separately (eqs. 5.22–5.27; for equal masses this is exactly the swap of
// eq. 5.26–5.27, for unequal or infinite masses the elastic solution of 5.22 and 5.24 along c), and
// the results are blended by s of eq. 5.28 (eqs. 5.29–5.30). Momentum is conserved exactly and,
// by convexity, kinetic energy never increases. Velocity changes Δv are applied from the start of
// the step (positions move by Δt Δv). A particle left within `separation_m` of the edge is placed
// that far outside it. A particle with a second boundary (another, non-adjacent edge or a wall)
// within `trap_radius_m` is trapped: its velocity is turned along the edge, keeping its speed.
#include "jellysim/math/vec2.hpp"
#include "jellysim/sph/walls.hpp"

#include <cstdint>
#include <limits>
#include <vector>

namespace jellysim::sph {

/// The boundary of a body for collisions: closed loops of point indices, counter-clockwise (the
/// outward normal lies to the right of a → b). Springs that are not outline edges, muscle springs
/// in particular, never collide.
struct CollisionOutline {
  std::vector<int> a, b;  ///< edge k runs from point a[k] to point b[k]
  std::size_t size() const { return a.size(); }
  /// Appends the edges of one closed counter-clockwise loop.
  void add_loop(const std::vector<int>& ccw_points);
};

/// w_b of eq. 5.31: the smallest distance from an outline point to an outline edge that neither
/// contains it nor touches an edge that does (e.g. the width of a strip), at positions x (m).
double boundary_width(const CollisionOutline& outline, const std::vector<Vec2>& x);

/// True when x lies inside the outline at positions `points` (even–odd rule).
bool inside_outline(const CollisionOutline& outline, const std::vector<Vec2>& points, Vec2 x);

struct CollisionSettings {
  double separation_m = 1e-6;  ///< distance outside an edge at which a pushed-out particle is put
  double trap_radius_m = 0.0;  ///< a second boundary this close makes a colliding particle trapped
};

/// Positions at the start and end of a step and velocities at the end, plus masses (kg). Infinite
/// mass (pinned points) is given as +inf.
struct MovingPoints {
  const std::vector<Vec2>* start = nullptr;
  std::vector<Vec2>* end = nullptr;
  std::vector<Vec2>* velocity = nullptr;
  const std::vector<double>* mass = nullptr;
};

struct CollisionStatistics {
  std::int64_t edge_collisions = 0;  ///< particle–edge collisions handled
  std::int64_t trapped = 0;          ///< of which trapped particles re-aimed along a boundary
  std::int64_t wall_collisions = 0;  ///< particles and body points reflected by walls
  CollisionStatistics& operator+=(const CollisionStatistics& o) {
    edge_collisions += o.edge_collisions;
    trapped += o.trapped;
    wall_collisions += o.wall_collisions;
    return *this;
  }
};

/// Result of the two-body elastic collision of a particle (mass m_p) with one endpoint (mass m_e,
/// may be +inf) along the unit axis c; unchanged when they are not approaching along c.
struct PairResult {
  Vec2 particle, endpoint;
};
PairResult collide_pair(Vec2 v_particle, double m_particle, Vec2 v_endpoint, double m_endpoint, Vec2 c);

/// Handles one step: body points against the walls, then each particle (in index order) against the
/// body outline and the walls. Modifies end positions and velocities in place.
class CollisionHandler {
 public:
  explicit CollisionHandler(CollisionSettings settings) : settings_(settings) {}
  CollisionStatistics handle(const MovingPoints& particles, const MovingPoints& body, const CollisionOutline& outline,
                             const std::vector<Wall>& walls, double dt_s);

 private:
  struct Hit {
    int edge = -1;
    Vec2 contact;  ///< l_c
  };
  Hit find_crossing(const MovingPoints& body, const CollisionOutline& outline, Vec2 p0, Vec2 p1) const;
  Hit find_edge_for_inside(const MovingPoints& body, const CollisionOutline& outline, Vec2 p, Vec2 v) const;
  void respond(const MovingPoints& particles, std::size_t p, const MovingPoints& body, const CollisionOutline& outline,
               const Hit& hit, double dt_s) const;
  void separate(const MovingPoints& body, const CollisionOutline& outline, int edge, Vec2& p) const;
  bool trapped(const MovingPoints& body, const CollisionOutline& outline, const std::vector<Wall>& walls, int edge,
               Vec2 p) const;

  CollisionSettings settings_;
};

}  // namespace jellysim::sph
