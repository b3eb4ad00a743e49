#include "fluid/semi_lagrangian.hpp"

#include <algorithm>
#include <cmath>

#include "fluid/eulerian_solver.hpp"

namespace jellysim::fluid {

namespace {
double wrap(double x, double origin, double length) {
  double t = std::fmod(x - origin, length);
  if (t < 0.0) t += length;
  return origin + t;
}
}  // namespace

Vec2 confine_to_domain(const MacGrid& g, const Boundaries& b, Vec2 p) {
  const Vec2 c = g.clamp_to_domain(p);
  return {b.periodic_x() ? wrap(p.x, g.origin_m.x, g.width_m) : c.x,
          b.periodic_y() ? wrap(p.y, g.origin_m.y, g.height_m) : c.y};
}

Vec2 velocity_at_u_face(const Velocity& vel, int i, int j) {
  const Field& v = vel.v;
  return {vel.u(i, j), 0.25 * (v(i - 1, j) + v(i, j) + v(i - 1, j + 1) + v(i, j + 1))};
}

Vec2 velocity_at_v_face(const Velocity& vel, int i, int j) {
  const Field& u = vel.u;
  return {0.25 * (u(i, j - 1) + u(i + 1, j - 1) + u(i, j) + u(i + 1, j)), vel.v(i, j)};
}

Vec2 back_trace(const Velocity& vel, const Boundaries& b, Vec2 x, Vec2 velocity_at_x, double dt_s) {
  const MacGrid& g = vel.u.grid();
  const Vec2 midpoint = confine_to_domain(g, b, x - 0.5 * dt_s * velocity_at_x);
  return confine_to_domain(g, b, x - dt_s * vel.sample(midpoint));
}

void advect_velocity(const Velocity& src, const Boundaries& b, double dt_s, Velocity& dst) {
  const MacGrid& g = src.u.grid();
  const FaceRange ru = interior_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i) {
      const Vec2 x = src.u.position(i, j);
      dst.u(i, j) = src.u.sample(back_trace(src, b, x, velocity_at_u_face(src, i, j), dt_s));
    }
  const FaceRange rv = interior_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i) {
      const Vec2 x = src.v.position(i, j);
      dst.v(i, j) = src.v.sample(back_trace(src, b, x, velocity_at_v_face(src, i, j), dt_s));
    }
  apply_velocity_boundaries(dst, b);
}

namespace {

// Operations on the interior faces of both components, treated as one vector.
template <class Fn>
void for_interior_faces(const MacGrid& g, const Boundaries& b, Fn&& fn) {
  const FaceRange ru = interior_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i) fn(0, i, j);
  const FaceRange rv = interior_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i) fn(1, i, j);
}

inline Field& component(Velocity& v, int c) { return c == 0 ? v.u : v.v; }
inline const Field& component(const Velocity& v, int c) { return c == 0 ? v.u : v.v; }

double dot(const MacGrid& g, const Boundaries& b, const Velocity& x, const Velocity& y) {
  double s = 0.0;
  for_interior_faces(g, b, [&](int c, int i, int j) { s += component(x, c)(i, j) * component(y, c)(i, j); });
  return s;
}

double max_interior(const MacGrid& g, const Boundaries& b, const Velocity& x) {
  double m = 0.0;
  for_interior_faces(g, b, [&](int c, int i, int j) { m = std::max(m, std::abs(component(x, c)(i, j))); });
  return m;
}

// out = x − νΔt ∇²x on the interior faces, with the boundary values of `b` put into x first.
void apply_helmholtz(Velocity& x, const Boundaries& b, double nu_dt, Velocity& out) {
  apply_velocity_boundaries(x, b);
  const MacGrid& g = x.u.grid();
  for_interior_faces(g, b, [&](int c, int i, int j) {
    const Field& f = component(x, c);
    component(out, c)(i, j) = f(i, j) - nu_dt * face_laplacian(f, i, j);
  });
}

}  // namespace

int diffuse_velocity_implicit(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
                              int max_iterations) {
  if (nu_dt_m2 <= 0.0) return 0;
  const MacGrid& g = vel.u.grid();
  const Boundaries zero = b.homogeneous();
  // Correction e with homogeneous boundaries: (I − νΔt∇²)e = u − (I − νΔt∇²)u = r.
  Velocity r(g), d(g), q(g), e(g);
  apply_helmholtz(vel, b, nu_dt_m2, q);
  for_interior_faces(g, b, [&](int c, int i, int j) {
    component(r, c)(i, j) = component(vel, c)(i, j) - component(q, c)(i, j);
  });
  const double target = relative_tolerance * std::max(max_interior(g, b, vel), 1e-300);
  d = r;
  double rr = dot(g, b, r, r);
  int it = 0;
  for (; it < max_iterations && max_interior(g, b, r) > target; ++it) {
    apply_helmholtz(d, zero, nu_dt_m2, q);
    const double alpha = rr / dot(g, b, d, q);
    for_interior_faces(g, b, [&](int c, int i, int j) {
      component(e, c)(i, j) += alpha * component(d, c)(i, j);
      component(r, c)(i, j) -= alpha * component(q, c)(i, j);
    });
    const double rr_new = dot(g, b, r, r);
    const double beta = rr_new / rr;
    rr = rr_new;
    for_interior_faces(g, b, [&](int c, int i, int j) {
      component(d, c)(i, j) = component(r, c)(i, j) + beta * component(d, c)(i, j);
    });
  }
  for_interior_faces(g, b, [&](int c, int i, int j) { component(vel, c)(i, j) += component(e, c)(i, j); });
  apply_velocity_boundaries(vel, b);
  return it;
}

}  // namespace jellysim::fluid
