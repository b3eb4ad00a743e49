#include "jellysim/fluid/semi_lagrangian.hpp"

#include "jellysim/fluid/eulerian_solver.hpp"

#include "double2.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <utility>


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

namespace {

// Two faces at a time (double2.hpp): the same bits as the scalar formulas.
using simd::Double2;
using simd::Int2;
using simd::load2;
using simd::store2;

// The four samples around continuous sample indices (fx, fy) of two points and the weights
// within the cell (base = sample (0, 0), row stride). The caller guarantees −1 ≤ fx < count_x and
// −1 ≤ fy < count_y (true for every point confined to the domain), so unlike Field::sample there
// is no clamping.
struct Cell2 {
  Double2 q00, q01, q10, q11, tx, ty;
};
inline Cell2 cell2(const double* base, int stride, Double2 fx, Double2 fy) {
  // floor(f) = trunc(f + 1) − 1 as f ≥ −1; the flat index j0·stride + i0 is computed exactly in
  // doubles and converted once.
  const Double2 i0 = __builtin_convertvector(__builtin_convertvector(fx + 1.0, Int2), Double2) - 1.0;
  const Double2 j0 = __builtin_convertvector(__builtin_convertvector(fy + 1.0, Int2), Double2) - 1.0;
  const Int2 k = __builtin_convertvector(j0 * static_cast<double>(stride) + i0, Int2);
  const double* a = base + k[0];
  const double* b = base + k[1];
  Cell2 c;
  c.q00 = Double2{a[0], b[0]};
  c.q01 = Double2{a[1], b[1]};
  c.q10 = Double2{a[stride], b[stride]};
  c.q11 = Double2{a[stride + 1], b[stride + 1]};
  c.tx = fx - i0;
  c.ty = fy - j0;
  return c;
}

// Bilinear interpolation of two points: same weights and operation order as Field::sample.
inline Double2 bilinear2(const Cell2& c) {
  const Double2 bottom = (1.0 - c.tx) * c.q00 + c.tx * c.q01;
  const Double2 top = (1.0 - c.tx) * c.q10 + c.tx * c.q11;
  return (1.0 - c.ty) * bottom + c.ty * top;
}
inline Double2 bilinear2(const double* base, int stride, Double2 fx, Double2 fy) {
  return bilinear2(cell2(base, stride, fx, fy));
}

inline bool inside_axis(double x, double n) { return x >= 0.0 && x <= n; }
// Periodic wrap of a point more than a period away (Δt·|u| above the domain size), or NaN → 0.
inline double wrap_far(double x, double n) {
  if (inside_axis(x, n)) return x;
  x = std::fmod(x, n);
  if (x < 0.0) x += n;
  return inside_axis(x, n) ? x : 0.0;
}

// confine_to_domain along one axis in grid coordinates (cells), for two points: clamp onto
// [0, n], or wrap by whole periods on a periodic axis. A NaN coordinate goes to 0, which keeps
// the sample indices in range.
template <bool Periodic, bool Confine = true>
inline Double2 confine2(Double2 x, double n) {
  if constexpr (!Confine) {
    (void)n;
    return x;
  } else if constexpr (!Periodic) {
    x = x > 0.0 ? x : 0.0;  // branch-free max/min; NaN → 0
    return x < n ? x : n;
  } else {
    x = x < 0.0 ? x + n : x;  // within one period: branch-free
    x = x > n ? x - n : x;
    if (!(inside_axis(x[0], n) && inside_axis(x[1], n))) [[unlikely]] {
      x[0] = wrap_far(x[0], n);
      x[1] = wrap_far(x[1], n);
    }
    return x;
  }
}

// max |value| over every stored sample (ghosts included); NaN if a sample is NaN or infinite.
double max_abs_stored(const Field& f) {
  const std::span<const double> x = f.raw();
  simd::Max4 m;
  Double2 non_finite{0.0, 0.0};  // stays 0 unless some x·0 is NaN
  std::size_t k = 0;
  for (; k + 4 <= x.size(); k += 4) {
    const Double2 a = load2(x.data() + k);
    const Double2 b = load2(x.data() + k + 2);
    m.a = simd::max2(m.a, simd::abs2(a));
    m.b = simd::max2(m.b, simd::abs2(b));
    non_finite += a * 0.0 + b * 0.0;
  }
  double result = m.total();
  double tail = non_finite[0] + non_finite[1];
  for (; k < x.size(); ++k) {
    result = std::max(result, std::abs(x[k]));
    tail += x[k] * 0.0;
  }
  return tail == 0.0 ? result : std::numeric_limits<double>::quiet_NaN();
}

// What one advection pass reads and writes: the carrier velocity that is traced back along, the
// field that is sampled at the end points (the carrier itself for Stam's step), and optionally
// the per-face sample range of the final interpolation.
struct AdvectionPass {
  const Velocity& carrier;
  const Velocity& quantity;
  Velocity& dst;
  VelocityBounds* bounds = nullptr;
};

// The faces of one row of a component and what its advection reads there: the velocity at the
// faces is the component itself and the average of the other one's four surrounding faces
// (velocity_at_u_face / velocity_at_v_face), o0 the row below and o1 the row above.
struct FaceRow {
  double gy;  // the row's y in grid coordinates
  const double* own;
  const double* o0;
  const double* o1;
  double* out;
  double* out_lo;  // the sample ranges (Bounds), else null
  double* out_hi;
};

// Advects one component (0: u on x-faces, 1: v on y-faces). Positions are in grid coordinates
// (cells from the origin corner); the sample indices of u are (x, y − ½), of v (x − ½, y).
// Midpoint back-trace as back_trace(): x − Δt·u(x − ½Δt·u(x)), u the carrier; ax = Δt/Δx and
// ay = Δt/Δy are negative for a forward (reverse-in-time) trace.
// Each row is done in chunks of kChunk faces and three passes (midpoints; velocity there and end
// points; final sample), two faces at a time; the independent faces of a pass overlap in the CPU
// instead of each face waiting on its own chain of three dependent interpolations. An odd face
// count is padded with the next face (its inputs are stored samples or ghosts; its result is
// dropped). The passes are always inlined into the row loop, whose locals they take by value.
template <int Component, bool PeriodicX, bool PeriodicY, bool Bounds>
class ComponentAdvection {
 public:
  static constexpr int kChunk = 128;
  static constexpr double sx = Component == 0 ? 0.0 : 0.5;  // staggering of the component
  static constexpr double sy = Component == 0 ? 0.5 : 0.0;

  ComponentAdvection(const AdvectionPass& pass, double ax, double ay)
      : pass_(pass), src_(pass.carrier), dst_(Component == 0 ? pass.dst.u : pass.dst.v),
        quantity_(Component == 0 ? pass.quantity.u : pass.quantity.v), ax_(ax), ay_(ay) {}

  FaceRow row(int j) const {
    FaceRow f{j + sy,
              Component == 0 ? src_.u.ptr(0, j) : src_.v.ptr(0, j),
              Component == 0 ? src_.v.ptr(-1, j) : src_.u.ptr(0, j - 1),
              Component == 0 ? src_.v.ptr(-1, j + 1) : src_.u.ptr(0, j),
              dst_.ptr(0, j),
              nullptr,
              nullptr};
    if constexpr (Bounds) {
      f.out_lo = (Component == 0 ? pass_.bounds->lo.u : pass_.bounds->lo.v).ptr(0, j);
      f.out_hi = (Component == 0 ? pass_.bounds->hi.u : pass_.bounds->hi.v).ptr(0, j);
    }
    return f;
  }

  // Pass 1: midpoints x − ½Δt·u(x) of faces [c0, c0 + n).
  template <bool Confine>
  [[gnu::always_inline]] void trace_midpoints(const FaceRow& f, int c0, int n, double* px, double* py) const {
    const double nx = src_.u.grid().nx, ny = src_.u.grid().ny;
    const double half_ax = 0.5 * ax_, half_ay = 0.5 * ay_;
    const Double2 lane{0.0, 1.0};
    for (int k = 0; k < n; k += 2) {
      const int i = c0 + k;
      const Double2 other = 0.25 * (load2(f.o0 + i) + load2(f.o0 + i + 1) + load2(f.o1 + i) + load2(f.o1 + i + 1));
      const Double2 uf = Component == 0 ? load2(f.own + i) : other;
      const Double2 vf = Component == 0 ? other : load2(f.own + i);
      const Double2 gx = (i + sx) + lane;
      store2(px + k, confine2<PeriodicX, Confine>(gx - half_ax * uf, nx));
      store2(py + k, confine2<PeriodicY, Confine>(f.gy - half_ay * vf, ny));
    }
  }

  // Pass 2: end points x − Δt·u(midpoint), overwriting the midpoints.
  template <bool Confine>
  [[gnu::always_inline]] void trace_end_points(const FaceRow& f, int c0, int n, double* px, double* py) const {
    const double nx = src_.u.grid().nx, ny = src_.u.grid().ny;
    const double ax = ax_, ay = ay_;
    const double* U = src_.u.ptr(0, 0);
    const double* V = src_.v.ptr(0, 0);
    const int su = static_cast<int>(src_.u.stride());
    const int sv = static_cast<int>(src_.v.stride());
    const Double2 lane{0.0, 1.0};
    for (int k = 0; k < n; k += 2) {
      const Double2 x = load2(px + k);
      const Double2 y = load2(py + k);
      const Double2 um = bilinear2(U, su, x, y - 0.5);
      const Double2 vm = bilinear2(V, sv, x - 0.5, y);
      const Double2 gx = (c0 + k + sx) + lane;
      store2(px + k, confine2<PeriodicX, Confine>(gx - ax * um, nx));
      store2(py + k, confine2<PeriodicY, Confine>(f.gy - ay * vm, ny));
    }
  }

  // Pass 3: the quantity at the end points.
  [[gnu::always_inline]] void sample_end_points(const FaceRow& f, int c0, int n, const double* px,
                                                const double* py) const {
    const double* F = quantity_.ptr(0, 0);
    const int sf = static_cast<int>(quantity_.stride());
    double* out = f.out;
    int k = 0;
    for (; k + 2 <= n; k += 2) store2(out + c0 + k, bilinear2(F, sf, load2(px + k) - sx, load2(py + k) - sy));
    if (k < n) out[c0 + k] = bilinear2(F, sf, load2(px + k) - sx, load2(py + k) - sy)[0];
  }

  // Pass 3 with the sample ranges: the value and the smallest and largest of the four samples it
  // combined (the range a compensated scheme's value is clamped to).
  [[gnu::always_inline]] void sample_end_points_with_range(const FaceRow& f, int c0, int n, const double* px,
                                                           const double* py) const {
    const double* F = quantity_.ptr(0, 0);
    const int sf = static_cast<int>(quantity_.stride());
    for (int k = 0; k < n; k += 2) {
      const Cell2 c = cell2(F, sf, load2(px + k) - sx, load2(py + k) - sy);
      const Double2 value = bilinear2(c);
      const Double2 lo = simd::min2(simd::min2(c.q00, c.q01), simd::min2(c.q10, c.q11));
      const Double2 hi = simd::max2(simd::max2(c.q00, c.q01), simd::max2(c.q10, c.q11));
      const int m = std::min(2, n - k);
      for (int e = 0; e < m; ++e) {
        f.out[c0 + k + e] = value[e];
        f.out_lo[c0 + k + e] = lo[e];
        f.out_hi[c0 + k + e] = hi[e];
      }
    }
  }

  template <bool Confine>
  [[gnu::always_inline]] void advect_chunk(const FaceRow& f, int c0, int n, double* px, double* py) const {
    trace_midpoints<Confine>(f, c0, n, px, py);
    trace_end_points<Confine>(f, c0, n, px, py);
    if constexpr (Bounds)
      sample_end_points_with_range(f, c0, n, px, py);
    else
      sample_end_points(f, c0, n, px, py);
  }

  template <bool Confine>
  [[gnu::always_inline]] void advect_faces(const FaceRow& f, int from, int to, double* px, double* py) const {
    for (int c0 = from; c0 < to; c0 += kChunk) advect_chunk<Confine>(f, c0, std::min(kChunk, to - c0), px, py);
  }

  // A chunk whose faces lie at least reach_x (reach_y) cells inside the domain cannot trace back
  // out of it (|velocity| ≤ the field's max), so it needs no clamping or wrapping. Faces
  // [safe_begin, safe_end) of a row with row_inside qualify (a face at x needs x − reach ≥ 0 and
  // x + reach ≤ n; the end leaves room for the padding face of a pair).
  std::pair<int, int> faces_needing_no_confinement(double gy, double reach_x, double reach_y, const FaceRange& r) const {
    const double nx = src_.u.grid().nx, ny = src_.u.grid().ny;
    const bool row_inside = gy - reach_y >= 0.0 && gy + reach_y <= ny;
    int safe_begin = r.i_end, safe_end = r.i_end;
    if (row_inside && reach_x < nx) {
      safe_begin = std::clamp(static_cast<int>(std::ceil(reach_x - sx)), r.i_begin, r.i_end);
      safe_end = std::clamp(static_cast<int>(std::floor(nx - reach_x - sx)) - 1, safe_begin, r.i_end);
    }
    return {safe_begin, safe_end};
  }

 private:
  const AdvectionPass& pass_;
  const Velocity& src_;
  Field& dst_;
  const Field& quantity_;
  double ax_, ay_;
};

// Advects one component over the faces of `r` (ComponentAdvection), row by row.
template <int Component, bool PeriodicX, bool PeriodicY, bool Bounds>
void advect_component(const AdvectionPass& pass, double ax, double ay, double reach_x, double reach_y,
                      const FaceRange& r) {
  using Advection = ComponentAdvection<Component, PeriodicX, PeriodicY, Bounds>;
  const Advection advection(pass, ax, ay);
  alignas(16) double px[Advection::kChunk], py[Advection::kChunk];
  for (int j = r.j_begin; j < r.j_end; ++j) {
    const FaceRow f = advection.row(j);
    const auto [safe_begin, safe_end] = advection.faces_needing_no_confinement(f.gy, reach_x, reach_y, r);
    advection.template advect_faces<true>(f, r.i_begin, safe_begin, px, py);
    advection.template advect_faces<false>(f, safe_begin, safe_end, px, py);
    advection.template advect_faces<true>(f, safe_end, r.i_end, px, py);
  }
}

template <bool PeriodicX, bool PeriodicY, bool Bounds>
void advect_both(const AdvectionPass& pass, const Boundaries& b, double dt_s) {
  const Velocity& src = pass.carrier;
  const MacGrid& g = src.u.grid();
  const double ax = dt_s / g.dx();  // cells per (m/s) of velocity
  const double ay = dt_s / g.dy();
  // Largest distance (cells) a back-trace can move; NaN (a non-finite velocity) makes every
  // "inside" test false, so every chunk is then confined.
  const double reach_x = std::abs(ax) * max_abs_stored(src.u);
  const double reach_y = std::abs(ay) * max_abs_stored(src.v);
  advect_component<0, PeriodicX, PeriodicY, Bounds>(pass, ax, ay, reach_x, reach_y, interior_u_faces(g, b));
  advect_component<1, PeriodicX, PeriodicY, Bounds>(pass, ax, ay, reach_x, reach_y, interior_v_faces(g, b));
}

template <bool Bounds>
void advect_pass(const AdvectionPass& pass, const Boundaries& b, double dt_s) {
  if (b.periodic_x()) {
    if (b.periodic_y()) advect_both<true, true, Bounds>(pass, b, dt_s);
    else advect_both<true, false, Bounds>(pass, b, dt_s);
  } else {
    if (b.periodic_y()) advect_both<false, true, Bounds>(pass, b, dt_s);
    else advect_both<false, false, Bounds>(pass, b, dt_s);
  }
  apply_velocity_boundaries(pass.dst, b);
}

}  // namespace

void advect_velocity(const Velocity& src, const Boundaries& b, double dt_s, Velocity& dst) {
  advect_pass<false>(AdvectionPass{src, src, dst}, b, dt_s);
}

void advect_velocity_by(const Velocity& carrier, const Velocity& quantity, const Boundaries& b, double dt_s,
                        Velocity& dst, VelocityBounds* bounds) {
  if (bounds) advect_pass<true>(AdvectionPass{carrier, quantity, dst, bounds}, b, dt_s);
  else advect_pass<false>(AdvectionPass{carrier, quantity, dst}, b, dt_s);
}

VelocityBounds::VelocityBounds(const MacGrid& g) : lo(g), hi(g) {}

CompensatedAdvection::CompensatedAdvection(const MacGrid& g) : forward_(g), backward_(g), bounds_(g) {}

namespace {

// Over the interior faces of both components: out = f(a, b, c, lo, hi) sample by sample.
template <class Fn>
void combine_interior(const Boundaries& b, const Velocity& x, const Velocity& y, const VelocityBounds& range,
                      Velocity& out, Fn&& fn) {
  const MacGrid& g = x.u.grid();
  for (int c = 0; c < 2; ++c) {
    const FaceRange r = c == 0 ? interior_u_faces(g, b) : interior_v_faces(g, b);
    const Field& fx = c == 0 ? x.u : x.v;
    const Field& fy = c == 0 ? y.u : y.v;
    const Field& lo = c == 0 ? range.lo.u : range.lo.v;
    const Field& hi = c == 0 ? range.hi.u : range.hi.v;
    Field& fo = c == 0 ? out.u : out.v;
    for (int j = r.j_begin; j < r.j_end; ++j)
      for (int i = r.i_begin; i < r.i_end; ++i) fo(i, j) = fn(fx(i, j), fy(i, j), fo(i, j), lo(i, j), hi(i, j));
  }
}

}  // namespace

namespace {
void advect_cubic(const Velocity& carrier, const Velocity& quantity, const Boundaries& b, double dt_s, Velocity& dst);
}  // namespace

void CompensatedAdvection::advect(AdvectionScheme scheme, const Velocity& carrier, const Velocity& quantity,
                                  const Boundaries& b, double dt_s, Velocity& dst) {
  if (scheme == AdvectionScheme::linear) {
    advect_velocity_by(carrier, quantity, b, dt_s, dst);
    return;
  }
  if (scheme == AdvectionScheme::cubic) {
    advect_cubic(carrier, quantity, b, dt_s, dst);
    return;
  }
  // φ̂ = A(φ) with the range of the samples each face used, then the reverse trace of φ̂.
  advect_velocity_by(carrier, quantity, b, dt_s, forward_, &bounds_);
  advect_velocity_by(carrier, forward_, b, -dt_s, backward_);
  if (scheme == AdvectionScheme::maccormack) {
    // Selle et al. (2008) eq. 5: φ = φ̂ + ½(φⁿ − A^R(φ̂)), clamped to the forward samples' range.
    dst = forward_;
    combine_interior(b, quantity, backward_, bounds_, dst, [](double q, double back, double fwd, double lo, double hi) {
      return std::clamp(fwd + 0.5 * (q - back), lo, hi);
    });
  } else {
    // Kim et al. (2005): φ̃ = φⁿ + ½(φⁿ − A^R(A(φⁿ))), then A(φ̃) (the same end points as the
    // first trace, so the same sample range), clamped as Selle et al. suggest.
    Velocity& compensated = backward_;
    combine_interior(b, quantity, backward_, bounds_, compensated,
                     [](double q, double back, double, double, double) { return q + 0.5 * (q - back); });
    apply_velocity_boundaries(compensated, b);
    advect_velocity_by(carrier, compensated, b, dt_s, dst);
    combine_interior(b, dst, dst, bounds_, dst,
                     [](double value, double, double, double lo, double hi) { return std::clamp(value, lo, hi); });
  }
  apply_velocity_boundaries(dst, b);
}

namespace {

// Monotone cubic Hermite interpolation at t ∈ [0, 1] between f1 and f2 (f0, f3 their outer
// neighbours): central slopes, zeroed where their sign differs from the interval's difference
// (Fedkiw et al.) and at most three times it (Fritsch & Carlson 1980: with slopes in [0, 3Δ] the
// cubic stays between f1 and f2).
double monotone_cubic(double f0, double f1, double f2, double f3, double t) {
  const double delta = f2 - f1;
  double d1 = 0.5 * (f2 - f0);
  double d2 = 0.5 * (f3 - f1);
  if (delta == 0.0) {
    d1 = d2 = 0.0;
  } else {
    d1 = std::clamp(d1 / delta, 0.0, 3.0) * delta;
    d2 = std::clamp(d2 / delta, 0.0, 3.0) * delta;
  }
  const double t2 = t * t, t3 = t2 * t;
  return f1 + d1 * t + (3.0 * delta - 2.0 * d1 - d2) * t2 + (d1 + d2 - 2.0 * delta) * t3;
}

}  // namespace

double sample_monotone_cubic(const Field& f, const Boundaries& b, Vec2 p) {
  const MacGrid& g = f.grid();
  const Staggering s = f.staggering();
  const Vec2 c = g.grid_from_world(p);
  const double fx = Field::clamp_index(c.x - s.x, f.count_x());
  const double fy = Field::clamp_index(c.y - s.y, f.count_y());
  const int i0 = std::min(static_cast<int>(std::floor(fx)), f.count_x() - 1);
  const int j0 = std::min(static_cast<int>(std::floor(fy)), f.count_y() - 1);
  const StencilReader q(f, b);
  double rows[4];
  for (int r = 0; r < 4; ++r) {
    const int j = j0 - 1 + r;
    rows[r] = monotone_cubic(q(i0 - 1, j), q(i0, j), q(i0 + 1, j), q(i0 + 2, j), fx - i0);
  }
  return monotone_cubic(rows[0], rows[1], rows[2], rows[3], fy - j0);
}

namespace {

// One trace per face along `carrier` (midpoint back_trace), then the monotone cubic sample of
// `quantity` there.
void advect_cubic(const Velocity& carrier, const Velocity& quantity, const Boundaries& b, double dt_s, Velocity& dst) {
  const MacGrid& g = carrier.u.grid();
  const FaceRange ru = interior_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i)
      dst.u(i, j) = sample_monotone_cubic(
          quantity.u, b, back_trace(carrier, b, quantity.u.position(i, j), velocity_at_u_face(carrier, i, j), dt_s));
  const FaceRange rv = interior_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i)
      dst.v(i, j) = sample_monotone_cubic(
          quantity.v, b, back_trace(carrier, b, quantity.v.position(i, j), velocity_at_v_face(carrier, i, j), dt_s));
  apply_velocity_boundaries(dst, b);
}

}  // namespace

void advect_velocity_reference(const Velocity& src, const Boundaries& b, double dt_s, Velocity& dst) {
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

struct HelmholtzCoefficients {
  double cx, cy, centre;
  HelmholtzCoefficients(const MacGrid& g, double nu_dt)
      : cx(nu_dt / (g.dx() * g.dx())), cy(nu_dt / (g.dy() * g.dy())), centre(1.0 + 2.0 * cx + 2.0 * cy) {}
  // (I − νΔt∇²)x at x[i], with the rows below and above; one value or a pair.
  double apply(const double* x, const double* below, const double* above, int i) const {
    return centre * x[i] - cx * (x[i - 1] + x[i + 1]) - cy * (below[i] + above[i]);
  }
  Double2 apply2(const double* x, const double* below, const double* above, int i) const {
    return centre * load2(x + i) - cx * (load2(x + i - 1) + load2(x + i + 1)) -
           cy * (load2(below + i) + load2(above + i));
  }
};

}  // namespace

ImplicitDiffusion::ImplicitDiffusion(const MacGrid& g, Geometry geometry)
    : geometry_(geometry), r_(g), d_(g), q_(geometry == Geometry::axisymmetric ? g : MacGrid(1, 1, 1.0, 1.0)) {}

namespace {

/// (I − νΔt L) x at face (i, j) of component c, L the axisymmetric viscous operator.
double axisymmetric_helmholtz(const Velocity& x, int c, int i, int j, double nu_dt) {
  return c == 0 ? x.u(i, j) - nu_dt * axisymmetric_viscous_u(x.u, i, j)
                : x.v(i, j) - nu_dt * axisymmetric_viscous_v(x.v, i, j);
}

/// The volume weight of face (i, j) of component c: its radius (u_r faces at iΔr, u_z at (i + ½)Δr).
double face_radius(const MacGrid& g, int c, int i) { return c == 0 ? i * g.dx() : (i + 0.5) * g.dx(); }

}  // namespace

int ImplicitDiffusion::solve_axisymmetric(Velocity& vel, const Boundaries& b, double nu_dt, double relative_tolerance,
                                          int max_iterations) {
  // CG on (I − νΔt L) e = r for the correction e, in the inner product Σ r_face x y (L is
  // self-adjoint there; the −u_r/r² term is diagonal), plain loops: the ring form is young.
  const MacGrid& g = vel.u.grid();
  const Boundaries zero = b.homogeneous();
  apply_velocity_boundaries(vel, b);
  double vel_max = 0.0, r_max = 0.0, rr = 0.0;
  for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
    for (int i = i0; i < i1; ++i) {
      const double u = component(vel, c)(i, j);
      const double ri = u - axisymmetric_helmholtz(vel, c, i, j, nu_dt);
      component(r_, c)(i, j) = ri;
      component(d_, c)(i, j) = ri;
      vel_max = std::max(vel_max, std::abs(u));
      r_max = std::max(r_max, std::abs(ri));
      rr += face_radius(g, c, i) * ri * ri;
    }
  });
  const double target = relative_tolerance * std::max(vel_max, r_max);
  int it = 0;
  for (; it < max_iterations && r_max > target; ++it) {
    apply_velocity_boundaries(d_, zero);
    double dq = 0.0;
    for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
      for (int i = i0; i < i1; ++i) {
        const double q = axisymmetric_helmholtz(d_, c, i, j, nu_dt);
        component(q_, c)(i, j) = q;
        dq += face_radius(g, c, i) * component(d_, c)(i, j) * q;
      }
    });
    if (!(dq > 0.0)) break;
    const double alpha = rr / dq;
    double rr_new = 0.0;
    r_max = 0.0;
    for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
      for (int i = i0; i < i1; ++i) {
        component(vel, c)(i, j) += alpha * component(d_, c)(i, j);
        const double ri = component(r_, c)(i, j) - alpha * component(q_, c)(i, j);
        component(r_, c)(i, j) = ri;
        rr_new += face_radius(g, c, i) * ri * ri;
        r_max = std::max(r_max, std::abs(ri));
      }
    });
    if (!(rr_new == rr_new)) break;
    const double beta = rr_new / rr;
    rr = rr_new;
    for_interior_rows(g, b, [&](int c, int j, int i0, int i1) {
      for (int i = i0; i < i1; ++i) component(d_, c)(i, j) = component(r_, c)(i, j) + beta * component(d_, c)(i, j);
    });
  }
  apply_velocity_boundaries(vel, b);
  return it;
}

void ImplicitDiffusion::apply_explicit(Velocity& vel, const Boundaries& b, double nu_dt_m2) {
  if (nu_dt_m2 <= 0.0) return;
  apply_velocity_boundaries(vel, b);
  if (geometry_ == Geometry::axisymmetric) {  // u ← (I + νΔt L) u, L the axisymmetric operator
    for_interior_rows(vel.u.grid(), b, [&](int c, int j, int i0, int i1) {
      for (int i = i0; i < i1; ++i) component(r_, c)(i, j) = axisymmetric_helmholtz(vel, c, i, j, -nu_dt_m2);
    });
    for_interior_rows(vel.u.grid(), b, [&](int c, int j, int i0, int i1) {
      for (int i = i0; i < i1; ++i) component(vel, c)(i, j) = component(r_, c)(i, j);
    });
    apply_velocity_boundaries(vel, b);
    return;
  }
  const HelmholtzCoefficients forward(vel.u.grid(), -nu_dt_m2);  // I + νΔt∇²
  for_interior_rows(vel.u.grid(), b, [&](int c, int j, int i0, int i1) {
    const Field& f = component(vel, c);
    const double* u = f.ptr(0, j);
    double* r = component(r_, c).ptr(0, j);
    for (int i = i0; i < i1; ++i) r[i] = forward.apply(u, f.ptr(0, j - 1), f.ptr(0, j + 1), i);
  });
  for_interior_rows(vel.u.grid(), b, [&](int c, int j, int i0, int i1) {
    std::copy(component(r_, c).ptr(i0, j), component(r_, c).ptr(i1, j), component(vel, c).ptr(i0, j));
  });
  apply_velocity_boundaries(vel, b);
}

namespace {

// The passes of ImplicitDiffusion::solve's conjugate gradients: two faces at a time, reductions
// with four partial results in a fixed order.

struct InitialResidual {
  double scale;  ///< max(max|u|, max|r|)
  double rr;     ///< r·r
  double r_max;  ///< max|r|
};

/// Pass 0: r = d = u − (I − νΔt∇²)u, with max|u|, max|r| and r·r.
InitialResidual initial_residual(const Velocity& vel, const Boundaries& b, const HelmholtzCoefficients& h, Velocity& r_,
                                 Velocity& d_) {
  using simd::abs2;
  using simd::max2;
  simd::Max4 vel_max, r_max;
  simd::Sum4 rr_sum;
  for_interior_rows(vel.u.grid(), b, [&](int c, int j, int i0, int i1) {
    const Field& f = component(vel, c);
    const double* u = f.ptr(0, j);
    const double* below = f.ptr(0, j - 1);
    const double* above = f.ptr(0, j + 1);
    double* r = component(r_, c).ptr(0, j);
    double* d = component(d_, c).ptr(0, j);
    auto pair = [&](int i, Double2& um, Double2& rm, Double2& rs) {
      const Double2 ui = load2(u + i);
      const Double2 ri = ui - h.apply2(u, below, above, i);
      store2(r + i, ri);
      store2(d + i, ri);
      um = max2(um, abs2(ui));
      rm = max2(rm, abs2(ri));
      rs += ri * ri;
    };
    simd::for_quads(
        i0, i1,
        [&](int i) {
          pair(i, vel_max.a, r_max.a, rr_sum.a);
          pair(i + 2, vel_max.b, r_max.b, rr_sum.b);
        },
        [&](int i) { pair(i, vel_max.a, r_max.a, rr_sum.a); },
        [&](int i) {
          const double ri = u[i] - h.apply(u, below, above, i);
          r[i] = ri;
          d[i] = ri;
          vel_max.a[0] = std::max(vel_max.a[0], std::abs(u[i]));
          r_max.a[0] = std::max(r_max.a[0], std::abs(ri));
          rr_sum.a[0] += ri * ri;
        });
  });
  return {std::max(vel_max.total(), r_max.total()), rr_sum.total(), r_max.total()};
}

/// Pass 1: d·Ad.
double d_dot_ad(const Velocity& d_, const Boundaries& b, const HelmholtzCoefficients& h) {
  simd::Sum4 dq_sum;
  for_interior_rows(d_.u.grid(), b, [&](int c, int j, int i0, int i1) {
    const Field& f = component(d_, c);
    const double* d = f.ptr(0, j);
    const double* below = f.ptr(0, j - 1);
    const double* above = f.ptr(0, j + 1);
    simd::for_quads(
        i0, i1,
        [&](int i) {
          dq_sum.a += load2(d + i) * h.apply2(d, below, above, i);
          dq_sum.b += load2(d + i + 2) * h.apply2(d, below, above, i + 2);
        },
        [&](int i) { dq_sum.a += load2(d + i) * h.apply2(d, below, above, i); },
        [&](int i) { dq_sum.a[0] += d[i] * h.apply(d, below, above, i); });
  });
  return dq_sum.total();
}

struct UpdatedResidual {
  double rr;     ///< r·r
  double r_max;  ///< max|r|
};

/// Pass 2: u += α d, r −= α Ad, with r·r and max|r|.
UpdatedResidual step_along(const Velocity& d_, const Boundaries& b, const HelmholtzCoefficients& h, double alpha,
                           Velocity& vel, Velocity& r_) {
  using simd::abs2;
  using simd::max2;
  simd::Sum4 rr_new_sum;
  simd::Max4 r_new_max;
  for_interior_rows(d_.u.grid(), b, [&](int c, int j, int i0, int i1) {
    const Field& f = component(d_, c);
    const double* d = f.ptr(0, j);
    const double* below = f.ptr(0, j - 1);
    const double* above = f.ptr(0, j + 1);
    double* r = component(r_, c).ptr(0, j);
    double* u = component(vel, c).ptr(0, j);
    auto pair = [&](int i, Double2& rs, Double2& rm) {
      store2(u + i, load2(u + i) + alpha * load2(d + i));
      const Double2 ri = load2(r + i) - alpha * h.apply2(d, below, above, i);
      store2(r + i, ri);
      rs += ri * ri;
      rm = max2(rm, abs2(ri));
    };
    simd::for_quads(
        i0, i1,
        [&](int i) {
          pair(i, rr_new_sum.a, r_new_max.a);
          pair(i + 2, rr_new_sum.b, r_new_max.b);
        },
        [&](int i) { pair(i, rr_new_sum.a, r_new_max.a); },
        [&](int i) {
          u[i] += alpha * d[i];
          const double ri = r[i] - alpha * h.apply(d, below, above, i);
          r[i] = ri;
          rr_new_sum.a[0] += ri * ri;
          r_new_max.a[0] = std::max(r_new_max.a[0], std::abs(ri));
        });
  });
  return {rr_new_sum.total(), r_new_max.total()};
}

/// Pass 3: d = r + β d.
void next_direction(const Velocity& r_, const Boundaries& b, double beta, Velocity& d_) {
  for_interior_rows(r_.u.grid(), b, [&](int c, int j, int i0, int i1) {
    const double* r = component(r_, c).ptr(0, j);
    double* d = component(d_, c).ptr(0, j);
    for (int i = i0; i < i1; ++i) d[i] = r[i] + beta * d[i];
  });
}

}  // namespace

int ImplicitDiffusion::solve(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
                             int max_iterations) {
  if (nu_dt_m2 <= 0.0) return 0;
  if (geometry_ == Geometry::axisymmetric) return solve_axisymmetric(vel, b, nu_dt_m2, relative_tolerance, max_iterations);
  const Boundaries zero = b.homogeneous();
  const HelmholtzCoefficients h(vel.u.grid(), nu_dt_m2);
  // Conjugate gradients for the correction e (homogeneous boundary values) of
  // (I − νΔt∇²)e = u − (I − νΔt∇²)u = r, added to u as it is found. Only r, d and u are stored
  // (A·d is recomputed where needed instead of kept), so that the solve streams three arrays.
  apply_velocity_boundaries(vel, b);
  const InitialResidual start = initial_residual(vel, b, h, r_, d_);
  const double target = relative_tolerance * start.scale;
  double rr = start.rr;
  double residual_max = start.r_max;
  // The max-norm stopping test uses the residual max taken in the pass that updates r.
  int it = 0;
  for (; it < max_iterations && residual_max > target; ++it) {
    apply_velocity_boundaries(d_, zero);
    const double dq = d_dot_ad(d_, b, h);
    if (!(dq > 0.0)) break;
    const UpdatedResidual updated = step_along(d_, b, h, rr / dq, vel, r_);
    residual_max = updated.r_max;
    if (!(updated.rr == updated.rr)) break;  // NaN: give up rather than run to max_iterations
    if (!(residual_max > target)) {          // converged: the next direction is not needed
      ++it;
      break;
    }
    next_direction(r_, b, updated.rr / rr, d_);
    rr = updated.rr;
  }
  apply_velocity_boundaries(vel, b);
  return it;
}

int diffuse_velocity_implicit(Velocity& vel, const Boundaries& b, double nu_dt_m2, double relative_tolerance,
                              int max_iterations) {
  ImplicitDiffusion workspace(vel.u.grid());
  return workspace.solve(vel, b, nu_dt_m2, relative_tolerance, max_iterations);
}

}  // namespace jellysim::fluid
