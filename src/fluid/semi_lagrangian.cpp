#include "fluid/semi_lagrangian.hpp"

#include <algorithm>
#include <cmath>


namespace jellysim::fluid {

double wrap_periodic(double x, double origin, double length) {
  double t = std::fmod(x - origin, length);
  if (t < 0.0) t += length;
  return origin + t;
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
  const double dx = g.dx();
  const double dy = g.dy();
  const FaceRange ru = interior_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j) {
    const double y = g.origin_m.y + (j + 0.5) * dy;
    for (int i = ru.i_begin; i < ru.i_end; ++i) {
      const Vec2 x{g.origin_m.x + i * dx, y};
      dst.u(i, j) = src.u.sample(back_trace(src, b, x, velocity_at_u_face(src, i, j), dt_s));
    }
  }
  const FaceRange rv = interior_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j) {
    const double y = g.origin_m.y + j * dy;
    for (int i = rv.i_begin; i < rv.i_end; ++i) {
      const Vec2 x{g.origin_m.x + (i + 0.5) * dx, y};
      dst.v(i, j) = src.v.sample(back_trace(src, b, x, velocity_at_v_face(src, i, j), dt_s));
    }
  }
  apply_velocity_boundaries(dst, b);
}

namespace {

// The interior faces of both components, row by row: fn(component, j, i_begin, i_end).
template <class Fn>
void for_interior_rows(const MacGrid& g, const Boundaries& b, Fn&& fn) {
  const FaceRange ru = interior_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j) fn(0, j, ru.i_begin, ru.i_end);
  const FaceRange rv = interior_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j) fn(1, j, rv.i_begin, rv.i_end);
}

inline Field& component(Velocity& v, int c) { return c == 0 ? v.u : v.v; }
inline const Field& component(const Velocity& v, int c) { return c == 0 ? v.u : v.v; }

double dot(const MacGrid& g, const Boundaries& b, const Velocity& x, const Velocity& y) {
  double s = 0.0;
  for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
    const double* xr = component(x, c).ptr(0, j);
    const double* yr = component(y, c).ptr(0, j);
    for (int i = i0; i < i1; ++i) s += xr[i] * yr[i];
  });
  return s;
}

double max_interior(const MacGrid& g, const Boundaries& b, const Velocity& x) {
  double m = 0.0;
  for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
    const double* xr = component(x, c).ptr(0, j);
    for (int i = i0; i < i1; ++i) m = std::max(m, std::abs(xr[i]));
  });
  return m;
}

// y += a·x on the interior faces.
void axpy(const MacGrid& g, const Boundaries& b, double a, const Velocity& x, Velocity& y) {
  for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
    const double* xr = component(x, c).ptr(0, j);
    double* yr = component(y, c).ptr(0, j);
    for (int i = i0; i < i1; ++i) yr[i] += a * xr[i];
  });
}

// out = x − νΔt ∇²x on the interior faces, with the boundary values of `b` put into x first.
void apply_helmholtz(Velocity& x, const Boundaries& b, double nu_dt, Velocity& out) {
  apply_velocity_boundaries(x, b);
  const MacGrid& g = x.u.grid();
  const double cx = nu_dt / (g.dx() * g.dx());
  const double cy = nu_dt / (g.dy() * g.dy());
  const double centre = 1.0 + 2.0 * cx + 2.0 * cy;
  for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
    const Field& f = component(x, c);
    const double* xr = f.ptr(0, j);
    const double* below = f.ptr(0, j - 1);
    const double* above = f.ptr(0, j + 1);
    double* o = component(out, c).ptr(0, j);
    for (int i = i0; i < i1; ++i)
      o[i] = centre * xr[i] - cx * (xr[i - 1] + xr[i + 1]) - cy * (below[i] + above[i]);
  });
}

}  // namespace

ImplicitDiffusion::ImplicitDiffusion(const MacGrid& g) : r_(g), d_(g), q_(g), e_(g) {}

int ImplicitDiffusion::solve(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
                             int max_iterations) {
  if (nu_dt_m2 <= 0.0) return 0;
  const MacGrid& g = vel.u.grid();
  const Boundaries zero = b.homogeneous();
  // Correction e with homogeneous boundaries: (I − νΔt∇²)e = u − (I − νΔt∇²)u = r.
  apply_helmholtz(vel, b, nu_dt_m2, q_);
  for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
    const double* u = component(vel, c).ptr(0, j);
    const double* q = component(q_, c).ptr(0, j);
    double* r = component(r_, c).ptr(0, j);
    double* e = component(e_, c).ptr(0, j);
    for (int i = i0; i < i1; ++i) {
      r[i] = u[i] - q[i];
      e[i] = 0.0;
    }
  });
  const double scale = std::max(max_interior(g, b, vel), max_interior(g, b, r_));
  const double target = relative_tolerance * scale;
  d_ = r_;
  double rr = dot(g, b, r_, r_);
  int it = 0;
  for (; it < max_iterations && max_interior(g, b, r_) > target; ++it) {
    apply_helmholtz(d_, zero, nu_dt_m2, q_);
    const double dq = dot(g, b, d_, q_);
    if (!(dq > 0.0)) break;
    const double alpha = rr / dq;
    axpy(g, b, alpha, d_, e_);
    axpy(g, b, -alpha, q_, r_);
    const double rr_new = dot(g, b, r_, r_);
    const double beta = rr_new / rr;
    rr = rr_new;
    for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
      const double* r = component(r_, c).ptr(0, j);
      double* d = component(d_, c).ptr(0, j);
      for (int i = i0; i < i1; ++i) d[i] = r[i] + beta * d[i];
    });
  }
  axpy(g, b, 1.0, e_, vel);
  apply_velocity_boundaries(vel, b);
  return it;
}

int diffuse_velocity_implicit(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
                              int max_iterations) {
  ImplicitDiffusion workspace(vel.u.grid());
  return workspace.solve(vel, b, nu_dt_m2, relative_tolerance, max_iterations);
}

}  // namespace jellysim::fluid
