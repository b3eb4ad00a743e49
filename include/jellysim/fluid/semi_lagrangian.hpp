#pragma once
// Building blocks of Stam's semi-Lagrangian method (§4.2): back-traced advection and implicit
// diffusion on the staggered grid.
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

/// x moved by whole periods into [origin, origin + length].
double wrap_periodic(double x, double origin, double length);

/// Keeps a position inside the domain: wraps along periodic axes, clamps onto the sides
/// otherwise (Fedkiw et al.'s clamp of back-traced points, §4.2.2).
inline Vec2 confine_to_domain(const MacGrid& g, const Boundaries& b, Vec2 p) {
  const Vec2 c = g.clamp_to_domain(p);
  if (b.periodic_x() && c.x != p.x) p.x = wrap_periodic(p.x, g.origin_m.x, g.width_m);
  else p.x = c.x;
  if (b.periodic_y() && c.y != p.y) p.y = wrap_periodic(p.y, g.origin_m.y, g.height_m);
  else p.y = c.y;
  return p;
}

/// Velocity at the x-face (i, j): u itself and v averaged from the four surrounding y-faces.
Vec2 velocity_at_u_face(const Velocity& vel, int i, int j);
Vec2 velocity_at_v_face(const Velocity& vel, int i, int j);

/// Second-order (midpoint) back-trace: x − Δt·u(x − ½Δt·u(x)), confined to the domain.
Vec2 back_trace(const Velocity& vel, const Boundaries& b, Vec2 x, Vec2 velocity_at_x, double dt_s);

/// Semi-Lagrangian advection of the velocity by itself (§4.2.4 step 3, with the sign of the
/// back-trace corrected: u_c(x) = u_b(x − Δt u_b)). `src` must have filled ghosts; the interior
/// faces of `dst` are overwritten and its boundaries applied.
/// Works row by row in grid coordinates with the bilinear weights computed in place (no
/// per-sample clamping of the stored range: a confined point always lies inside it); equals
/// advect_velocity_reference up to round-off (the positions are computed in cells, not metres).
void advect_velocity(const Velocity& src, const Boundaries& b, double dt_s, Velocity& dst);
/// The same advection written point by point with back_trace() and Field::sample() in world
/// coordinates; the reference for tests and benchmarks.
void advect_velocity_reference(const Velocity& src, const Boundaries& b, double dt_s, Velocity& dst);

/// Implicit diffusion, eq. 4.17 with the time step: (I − νΔt∇²) u_new = u, solved by conjugate
/// gradients on the interior faces with the boundary values of `b`; keeps its work vectors.
/// Stops when the max-norm of the CG residual is at most relative_tolerance · max(max|u|, max|r₀|)
/// (the max is taken in the same pass that updates the residual).
class ImplicitDiffusion {
 public:
  explicit ImplicitDiffusion(const MacGrid& g);
  /// Returns the CG iterations.
  int solve(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
            int max_iterations = 2000);

 private:
  Velocity r_, d_;
};

/// Implicit diffusion, eq. 4.17 with the time step: (I − νΔt∇²) u_new = u, solved by conjugate
/// gradients on the interior faces with the boundary values of `b`. Returns the CG iterations.
int diffuse_velocity_implicit(Velocity& vel, const Boundaries& b, double nu_dt_m2,
                              double relative_tolerance, int max_iterations = 2000);

}  // namespace jellysim::fluid
