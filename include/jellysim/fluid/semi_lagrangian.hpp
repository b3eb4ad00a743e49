#pragma once
// Building blocks of Stam's semi-Lagrangian method (§4.2): back-traced advection and implicit
// diffusion on the staggered grid.
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/fluid/schemes.hpp"
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
/// Per face, the smallest and largest of the samples an interpolation combined.
struct VelocityBounds {
  Velocity lo, hi;
  explicit VelocityBounds(const MacGrid& g);
};

/// The advection of `quantity`'s faces along `carrier`: dst(x) = quantity(x − Δt·c(x − ½Δt·c(x)))
/// with c the carrier (advect_velocity is carrier = quantity). A negative Δt traces forward: the
/// reverse step of the compensated schemes. With `bounds`, also stores for each face the range
/// of the four samples its interpolation used. Both inputs need filled ghosts.
void advect_velocity_by(const Velocity& carrier, const Velocity& quantity, const Boundaries& b, double dt_s,
                        Velocity& dst, VelocityBounds* bounds = nullptr);

/// Error-compensated semi-Lagrangian advection (issue 20): MacCormack (Selle, Fedkiw, Kim, Liu &
/// Rossignac 2008, "An unconditionally stable MacCormack method", J. Sci. Comput. 35) and BFECC
/// (Kim, Liu, Llamas & Rossignac 2005, "FlowFixer: using BFECC for fluid simulation"). Both
/// estimate the error of one trace by tracing back and forth, which makes them second order in
/// space and time for smooth flows; each value is then clamped to the range of the samples the
/// plain forward trace interpolated (Selle et al. §4), so no new extrema appear. Keeps its
/// intermediate fields.
class CompensatedAdvection {
 public:
  explicit CompensatedAdvection(const MacGrid& g);
  /// dst = the advection of `quantity` along `carrier` by Δt with the scheme (linear: one trace
  /// with bilinear interpolation; cubic: one trace with sample_monotone_cubic).
  void advect(AdvectionScheme scheme, const Velocity& carrier, const Velocity& quantity, const Boundaries& b,
              double dt_s, Velocity& dst);

 private:
  Velocity forward_, backward_;
  VelocityBounds bounds_;
};

/// Monotone cubic interpolation of a field at a world position (Fedkiw, Stam & Jensen 2001,
/// "Visual simulation of smoke", §5): a cubic Hermite curve through the 4 × 4 samples around the
/// point, first along x on each row, then along y, with slopes set to zero where they disagree in
/// sign with the interval's difference (or the difference is zero) and limited to three times it
/// (Fritsch & Carlson 1980), so that the value never leaves the range of the 2 × 2 samples around
/// the point. Samples beyond the stored ones wrap on a
/// periodic axis (of `b`) and repeat the outermost one otherwise.
double sample_monotone_cubic(const Field& f, const Boundaries& b, Vec2 p);

/// The same advection written point by point with back_trace() and Field::sample() in world
/// coordinates; the reference for tests and benchmarks.
void advect_velocity_reference(const Velocity& src, const Boundaries& b, double dt_s, Velocity& dst);

/// Implicit diffusion, eq. 4.17 with the time step: (I − νΔt∇²) u_new = u, solved by conjugate
/// gradients on the interior faces with the boundary values of `b`; keeps its work vectors.
/// Stops when the max-norm of the CG residual is at most relative_tolerance · max(max|u|, max|r₀|)
/// (the max is taken in the same pass that updates the residual).
class ImplicitDiffusion {
 public:
  /// On axisymmetric flow (fluid_solver.hpp) the operator is the axisymmetric one, (1/r)∂r(r∂u_r/∂r)
  /// − u_r/r² + ∂²u_r/∂z² and (1/r)∂r(r∂u_z/∂r) + ∂²u_z/∂z², solved by conjugate gradients in the
  /// volume-weighted inner product (in which it is symmetric).
  explicit ImplicitDiffusion(const MacGrid& g, Geometry geometry = Geometry::planar);
  /// Returns the CG iterations.
  int solve(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
            int max_iterations = 2000);
  /// The explicit half of a Crank–Nicolson step: u ← (I + νΔt∇²) u on the interior faces (called
  /// with ½νΔt; solve() with ½νΔt is the implicit half).
  void apply_explicit(Velocity& vel, const Boundaries& b, double nu_dt_m2);

 private:
  int solve_axisymmetric(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
                         int max_iterations);
  Geometry geometry_;
  Velocity r_, d_, q_;
};

/// Implicit diffusion, eq. 4.17 with the time step: (I − νΔt∇²) u_new = u, solved by conjugate
/// gradients on the interior faces with the boundary values of `b`. Returns the CG iterations.
int diffuse_velocity_implicit(Velocity& vel, const Boundaries& b, double nu_dt_m2,
                              double relative_tolerance, int max_iterations = 2000);

}  // namespace jellysim::fluid
