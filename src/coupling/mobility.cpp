#include "jellysim/coupling/mobility.hpp"

#include "jellysim/core/parallel.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "jellysim/fluid/poisson.hpp"
#include "jellysim/fluid/projection.hpp"

namespace jellysim::coupling {

namespace {

using fluid::BoundaryType;

/// One axis of the box as the transfer sees it: n cells between a low and a high side.
struct Axis {
  int n = 0;
  BoundaryType low = BoundaryType::free_slip, high = BoundaryType::free_slip;
  bool mirror_low = false;  ///< samples beyond the low side read the mirror image (half tank)
  bool periodic() const { return low == BoundaryType::periodic; }
};

Axis x_axis(const TransferGeometry& g) { return {g.grid.nx, g.sides.west.type, g.sides.east.type, g.west_mirror}; }
Axis y_axis(const TransferGeometry& g) { return {g.grid.ny, g.sides.south.type, g.sides.north.type, false}; }

bool wall_like(BoundaryType t) { return t != BoundaryType::outflow && t != BoundaryType::periodic; }

/// Sign of a component's mirror image across a side: the pressure is even across a wall (normal
/// velocity odd, tangential even) and odd across an outflow (normal even, tangential odd).
double reflection_sign(BoundaryType side, bool normal) {
  const bool even_pressure = wall_like(side);
  return (even_pressure == normal) ? -1.0 : 1.0;
}

/// The tangential ghost's factor on its neighbour (fluid/boundary.cpp, homogeneous sides):
/// no-slip and in-flow negate it, free-slip and outflow copy it.
double tangential_ghost_factor(BoundaryType side) {
  return (side == BoundaryType::no_slip || side == BoundaryType::inflow) ? -1.0 : 1.0;
}

/// Maps stencil sample i (normal: faces at integer positions, tangential: cells) onto a real face
/// of the axis and a factor, by the ghost rules; false when the sample is not stored (weight 0 in
/// make_stencil) or reads nothing.
bool real_sample(const Axis& a, bool normal, int i, int& out, double& factor) {
  const int count = normal ? a.n + 1 : a.n;  // stored interior samples 0 … count − 1
  factor = 1.0;
  if (a.mirror_low && i < 0) {  // the half tank's axis: the mirror image at any depth, then as usual
    i = normal ? -i : -1 - i;
    factor = normal ? -1.0 : 1.0;
  }
  if (a.periodic()) {  // any sample wraps around the seam (make_stencil with Periodicity)
    out = ((i % a.n) + a.n) % a.n;
    return true;
  }
  if (i < -1 || i > count) return false;
  if (i >= 0 && i < count) {
    out = i;
    return true;
  }
  const bool low = i < 0;
  const BoundaryType side = low ? a.low : a.high;
  if (normal) {
    if (wall_like(side)) {  // u(−1) = −u(1): the wall value is zero
      out = low ? 1 : a.n - 1;
      factor = -factor;
    } else {  // outflow: the ghost repeats the side's value
      out = low ? 0 : a.n;
    }
  } else {
    out = low ? 0 : a.n - 1;
    factor *= tangential_ghost_factor(side);
  }
  return true;
}

/// Is sample i an interior sample of the axis (one the momentum equation updates, hence one that
/// spreading keeps)?
bool interior_sample(const Axis& a, bool normal, int i) {
  if (!normal || a.periodic()) return i >= 0 && i < a.n;
  return i >= 1 && i < a.n;
}

/// Sample i moved into [0, n) along a periodic axis (the kernel wraps around the seam); unchanged
/// along any other.
int wrap_periodic(const Axis& a, int i) { return a.periodic() ? ((i % a.n) + a.n) % a.n : i; }

/// Kernel weights of the samples along one axis around continuous sample coordinate f.
struct AxisWeights {
  int first = 0;
  int width = 0;
  double w[4] = {0, 0, 0, 0};
};
AxisWeights axis_weights(Kernel k, double f) {
  const int r = kernel_radius(k);
  AxisWeights a;
  a.width = 2 * r;
  a.first = static_cast<int>(std::floor(f)) - r + 1;
  for (int s = 0; s < a.width; ++s) a.w[s] = kernel_weight(k, f - (a.first + s));
  return a;
}

/// Continuous sample coordinates of p for a component (u: faces in x, v: faces in y).
Vec2 sample_coordinates(const fluid::MacGrid& grid, Vec2 p, int component) {
  const Vec2 gc = grid.grid_from_world(p);
  return component == 0 ? Vec2{gc.x, gc.y - 0.5} : Vec2{gc.x - 0.5, gc.y};
}

/// A face's images on the torus along one axis: (index, sign), duplicates merged.
struct AxisImages {
  int index[4];
  double sign[4];
  int count = 0;
  void add(int i, double s, int period) {
    i = ((i % period) + period) % period;
    for (int k = 0; k < count; ++k)
      if (index[k] == i) {  // a face on a mirror plane is its own image
        if (sign[k] != s) sign[k] = 0.0;  // odd across the plane: the value there is zero
        return;
      }
    index[count] = i;
    sign[count] = s;
    ++count;
  }
};

int torus_period(const Axis& a) {
  if (a.periodic()) return a.n;
  return wall_like(a.low) == wall_like(a.high) ? 2 * a.n : 4 * a.n;
}

AxisImages axis_images(const Axis& a, bool normal, int i) {
  AxisImages im;
  const int period = torus_period(a);
  im.add(i, 1.0, period);
  if (a.periodic()) return im;
  // Positions in cells: normal samples at i, tangential at i + ½. Reflection about 0: s → −s;
  // about n: s → 2n − s; both: s → s + 2n.
  const int reflect_low = normal ? -i : -1 - i;
  const int reflect_high = normal ? 2 * a.n - i : 2 * a.n - 1 - i;
  const double s_low = reflection_sign(a.low, normal), s_high = reflection_sign(a.high, normal);
  im.add(reflect_low, s_low, period);
  if (period == 4 * a.n) {
    im.add(reflect_high, s_high, period);
    im.add(i + 2 * a.n, s_low * s_high, period);
  }
  return im;
}

}  // namespace

/// An image of a contiguous run of samples along one axis: sample k of the run maps to
/// start + step·k on the torus, with a sign.
struct ImageRun {
  int start = 0, step = 1;
  double sign = 1.0;
};

struct MobilityMatrix::Transfer {
  struct Source {
    int i, j;
    double w;
  };
  FaceTerms read;               ///< faces interpolation reads
  std::vector<Source> sources;  ///< torus sources of spreading: spread faces' images, weight × sign
  /// Reading and spreading use one tensor-product stencil of interior faces (the marker is away
  /// from the sides): entries then follow from 1D correlations of the weights (the fast path).
  bool separable = false;
  int width = 0, i0 = 0, j0 = 0;
  double wx[4] = {0, 0, 0, 0}, wy[4] = {0, 0, 0, 0};
  ImageRun x_images[4], y_images[4];
  int x_image_count = 0, y_image_count = 0;
};

FaceTerms interpolation_terms(const TransferGeometry& g, Vec2 p, int component) {
  const Axis ax = x_axis(g), ay = y_axis(g);
  const Vec2 f = sample_coordinates(g.grid, p, component);
  const AxisWeights wx = axis_weights(g.kernel, f.x), wy = axis_weights(g.kernel, f.y);
  FaceTerms t;
  for (int b = 0; b < wy.width; ++b) {
    int j;
    double fj;
    if (wy.w[b] == 0.0 || !real_sample(ay, component == 1, wy.first + b, j, fj)) continue;
    for (int a = 0; a < wx.width; ++a) {
      int i;
      double fi;
      if (wx.w[a] == 0.0 || !real_sample(ax, component == 0, wx.first + a, i, fi)) continue;
      t.add(i, j, wx.w[a] * wy.w[b] * fi * fj);
    }
  }
  return t;
}

FaceTerms spreading_terms(const TransferGeometry& g, Vec2 p, int component) {
  const Axis ax = x_axis(g), ay = y_axis(g);
  const Vec2 f = sample_coordinates(g.grid, p, component);
  const AxisWeights wx = axis_weights(g.kernel, f.x), wy = axis_weights(g.kernel, f.y);
  FaceTerms t;
  for (int b = 0; b < wy.width; ++b) {
    const int j = wrap_periodic(ay, wy.first + b);
    if (wy.w[b] == 0.0 || !interior_sample(ay, component == 1, j)) continue;
    for (int a = 0; a < wx.width; ++a) {
      const int i = wrap_periodic(ax, wx.first + a);
      if (wx.w[a] == 0.0 || !interior_sample(ax, component == 0, i)) continue;
      const double w = wx.w[a] * wy.w[b];
      t.add(i, j, w);
      // apply_velocity_boundaries sets an outflow side's normal velocity to its first face's.
      if (component == 0 && i == 1 && ax.low == BoundaryType::outflow) t.add(0, j, w);
      if (component == 0 && i == ax.n - 1 && ax.high == BoundaryType::outflow) t.add(ax.n, j, w);
      if (component == 1 && j == 1 && ay.low == BoundaryType::outflow) t.add(i, 0, w);
      if (component == 1 && j == ay.n - 1 && ay.high == BoundaryType::outflow) t.add(i, ay.n, w);
    }
  }
  return t;
}

void interpolate_velocities(const TransferGeometry& g, const fluid::Velocity& vel, std::span<const Vec2> points,
                            std::span<Vec2> out) {
  for (std::size_t p = 0; p < points.size(); ++p) {
    double value[2] = {0.0, 0.0};
    for (int c = 0; c < 2; ++c) {
      const fluid::Field& field = c == 0 ? vel.u : vel.v;
      for (const FaceTerm& t : interpolation_terms(g, points[p], c)) value[c] += t.weight * field(t.i, t.j);
    }
    out[p] = {value[0], value[1]};
  }
}

MobilityMatrix::MobilityMatrix(const TransferGeometry& geometry) : geometry_(geometry) {
  const Axis ax = x_axis(geometry_), ay = y_axis(geometry_);
  if (ax.periodic() != (ax.high == BoundaryType::periodic) || ay.periodic() != (ay.high == BoundaryType::periodic))
    throw std::invalid_argument("mobility: a periodic side needs a periodic opposite side");
  period_x_ = torus_period(ax);
  period_y_ = torus_period(ay);
  // The torus's response to a unit value on face (0, 0) of each component: one projection each.
  const fluid::MacGrid& g = geometry_.grid;
  const fluid::MacGrid torus(period_x_, period_y_, period_x_ * g.dx(), period_y_ * g.dy());
  const fluid::Boundaries periodic = fluid::Boundaries::all(BoundaryType::periodic);
  fluid::Projector projector(fluid::make_pressure_solver("fft"));
  const std::size_t size = static_cast<std::size_t>(period_x_) * static_cast<std::size_t>(period_y_);
  table_.resize(4 * size);
  for (int from = 0; from < 2; ++from) {
    fluid::FlowState state(torus);
    (from == 0 ? state.velocity.u : state.velocity.v)(0, 0) = 1.0;
    fluid::apply_velocity_boundaries(state.velocity, periodic);
    projector.project(state, periodic, 1.0, 1.0);
    for (int to = 0; to < 2; ++to) {
      const fluid::Field& f = to == 0 ? state.velocity.u : state.velocity.v;
      for (int j = 0; j < period_y_; ++j)
        for (int i = 0; i < period_x_; ++i)
          table_[4 * (static_cast<std::size_t>(j) * period_x_ + i) + 2 * to + from] = f(i, j);
    }
  }
}

double MobilityMatrix::table(int c_to, int c_from, int di, int dj) const {
  di = ((di % period_x_) + period_x_) % period_x_;
  dj = ((dj % period_y_) + period_y_) % period_y_;
  return table_[4 * (static_cast<std::size_t>(dj) * period_x_ + di) + 2 * c_to + c_from];
}

void MobilityMatrix::images_of(int component, int i, int j, std::vector<Image>& out) const {
  const AxisImages ix = axis_images(x_axis(geometry_), component == 0, i);
  const AxisImages iy = axis_images(y_axis(geometry_), component == 1, j);
  for (int b = 0; b < iy.count; ++b)
    for (int a = 0; a < ix.count; ++a) {
      const double s = ix.sign[a] * iy.sign[b];
      if (s != 0.0) out.push_back({ix.index[a], iy.index[b], s});
    }
}

double MobilityMatrix::response(int c_to, int i_to, int j_to, int c_from, int i_from, int j_from) const {
  std::vector<Image> images;
  images_of(c_from, i_from, j_from, images);
  double sum = 0.0;
  for (const Image& im : images) sum += im.sign * table(c_to, c_from, i_to - im.i, j_to - im.j);
  return sum;
}

namespace {

/// Is every sample of the run [first, first + width) interior (or on a periodic axis), with no
/// outflow copy?
bool clean_run(const Axis& a, bool normal, int first, int width) {
  if (a.periodic()) return true;  // every sample is interior; the torus offsets wrap (correlate)
  for (int k = 0; k < width; ++k) {
    const int i = first + k;
    if (!interior_sample(a, normal, i)) return false;
    if (normal && ((i == 1 && a.low == BoundaryType::outflow) || (i == a.n - 1 && a.high == BoundaryType::outflow)))
      return false;
  }
  return true;
}

/// The images of an interior run along an axis (none lies on a mirror plane, so none merge).
int image_runs(const Axis& a, bool normal, int first, ImageRun* out) {
  int count = 0;
  out[count++] = {first, 1, 1.0};
  if (a.periodic()) return count;
  const int period = torus_period(a);
  const double s_low = reflection_sign(a.low, normal), s_high = reflection_sign(a.high, normal);
  out[count++] = {normal ? -first : -1 - first, -1, s_low};
  if (period == 4 * a.n) {
    out[count++] = {normal ? 2 * a.n - first : 2 * a.n - 1 - first, -1, s_high};
    out[count++] = {first + 2 * a.n, 1, s_low * s_high};
  }
  return count;
}

/// Correlation of read weights (samples r0 + m) with an image run of source weights (samples
/// start + step·k): c[o] = Σ w_read[m] w_source[k] over m − step·k = o + o_min; returns the torus
/// offset (read − source) of c[0], reduced into [0, period). W: the kernel's width.
template <int W>
int correlate(const double* w_read, int r0, const double* w_source, const ImageRun& run, int period, double* c) {
  const int o_min = run.step > 0 ? -(W - 1) : 0;
  for (int o = 0; o < 2 * W - 1; ++o) c[o] = 0.0;
  if (run.step > 0) {
    for (int m = 0; m < W; ++m)
      for (int k = 0; k < W; ++k) c[m - k + W - 1] += w_read[m] * w_source[k];
  } else {
    for (int m = 0; m < W; ++m)
      for (int k = 0; k < W; ++k) c[m + k] += w_read[m] * w_source[k];
  }
  int d = r0 - run.start + o_min;  // within a few periods: no division
  while (d < 0) d += period;
  while (d >= period) d -= period;
  return d;
}

/// Σ over image pairs of Σ_ox Σ_oy cx[ox] cy[oy] T(dx + ox, dy + oy): (2W − 1)² table reads per
/// image pair instead of W⁴.
template <int W>
double separable_entry(const double* table, int period_x, int period_y, const double* read_wx,
                       const double* read_wy, int i0, int j0, const double* wx, const double* wy,
                       const ImageRun* x_images, int x_count, const ImageRun* y_images, int y_count) {
  constexpr int kSpan = 2 * W - 1;
  double cx[4][kSpan], cy[4][kSpan];
  int dx[4], dy[4];
  for (int a = 0; a < x_count; ++a) dx[a] = correlate<W>(read_wx, i0, wx, x_images[a], period_x, cx[a]);
  for (int b = 0; b < y_count; ++b) dy[b] = correlate<W>(read_wy, j0, wy, y_images[b], period_y, cy[b]);
  const auto px = static_cast<std::size_t>(period_x);
  double sum = 0.0;
  for (int b = 0; b < y_count; ++b) {
    for (int oy = 0; oy < kSpan; ++oy) {
      int j = dy[b] + oy;
      if (j >= period_y) j -= period_y;
      const double* row = table + 4 * static_cast<std::size_t>(j) * px;
      double across = 0.0;
      for (int a = 0; a < x_count; ++a) {
        double partial = 0.0;
        if (dx[a] + kSpan <= period_x) {
          for (int ox = 0; ox < kSpan; ++ox) partial += cx[a][ox] * row[4 * (dx[a] + ox)];
        } else {
          for (int ox = 0; ox < kSpan; ++ox) partial += cx[a][ox] * row[4 * ((dx[a] + ox) % period_x)];
        }
        across += x_images[a].sign * partial;
      }
      sum += y_images[b].sign * cy[b][oy] * across;
    }
  }
  return sum;
}

}  // namespace

MobilityMatrix::~MobilityMatrix() = default;

void MobilityMatrix::prepare(Vec2 p, int component, Transfer& t) const {
  const Axis ax = x_axis(geometry_), ay = y_axis(geometry_);
  t.read = interpolation_terms(geometry_, p, component);
  t.sources.clear();
  std::vector<Image> images;
  for (const FaceTerm& f : spreading_terms(geometry_, p, component)) {
    images.clear();
    images_of(component, f.i, f.j, images);
    for (const Image& im : images) t.sources.push_back({im.i, im.j, f.weight * im.sign});
  }
  const Vec2 f = sample_coordinates(geometry_.grid, p, component);
  const AxisWeights wx = axis_weights(geometry_.kernel, f.x), wy = axis_weights(geometry_.kernel, f.y);
  const bool normal_x = component == 0, normal_y = component == 1;
  t.separable = clean_run(ax, normal_x, wx.first, wx.width) &&
                clean_run(ay, normal_y, wy.first, wy.width);
  if (!t.separable) return;
  t.width = wx.width;
  t.i0 = wx.first;
  t.j0 = wy.first;
  std::copy(wx.w, wx.w + 4, t.wx);
  std::copy(wy.w, wy.w + 4, t.wy);
  t.x_image_count = image_runs(ax, normal_x, wx.first, t.x_images);
  t.y_image_count = image_runs(ay, normal_y, wy.first, t.y_images);
}

double MobilityMatrix::entry(const Transfer& to, int c_to, const Transfer& from, int c_from) const {
  const double* table = table_.data() + 2 * c_to + c_from;  // stride 4
  const auto px = static_cast<std::size_t>(period_x_);
  if (from.sources.empty()) return 0.0;
  if (!(to.separable && from.separable)) {
    double sum = 0.0;
    for (const Transfer::Source& s : from.sources) {
      double partial = 0.0;
      for (const FaceTerm& f : to.read) {
        int di = f.i - s.i, dj = f.j - s.j;
        if (di < 0) di += period_x_;
        if (dj < 0) dj += period_y_;
        partial += f.weight * table[4 * (static_cast<std::size_t>(dj) * px + static_cast<std::size_t>(di))];
      }
      sum += s.w * partial;
    }
    return sum;
  }
  auto separable = to.width == 2 ? separable_entry<2> : separable_entry<4>;
  return separable(table, period_x_, period_y_, to.wx, to.wy, to.i0, to.j0, from.wx, from.wy, from.x_images,
                   from.x_image_count, from.y_images, from.y_image_count);
}

void MobilityMatrix::assemble(std::span<const Vec2> points, std::span<const char> masked, double density_kg_per_m3,
                              std::span<const int> rows, Eigen::MatrixXd& r, WorkerPool* pool) const {
  const std::size_t n = points.size();
  std::vector<int> all;
  if (rows.empty()) {
    all.resize(n);
    for (std::size_t p = 0; p < n; ++p) all[p] = static_cast<int>(p);
    rows = all;
  }
  r.setZero(2 * static_cast<Eigen::Index>(rows.size()), 2 * static_cast<Eigen::Index>(n));
  const fluid::MacGrid& g = geometry_.grid;
  const double scale = 1.0 / (density_kg_per_m3 * g.dx() * g.dy());  // eq. 4.19
  auto is_masked = [&](std::size_t p) { return p < masked.size() && masked[p]; };
  std::vector<Transfer>& transfer = transfer_;  // kept between calls: no allocations per step
  transfer.resize(2 * n);
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 2; ++c) {
      Transfer& t = transfer[2 * p + static_cast<std::size_t>(c)];
      if (is_masked(p)) t.sources.clear(), t.separable = false;
      else prepare(points[p], c, t);
    }
  // R is symmetric where reading and spreading use the same stencil (P is an orthogonal projector):
  // R(a, b) = R(b, a)ᵀ for two separable markers; such entries are copied from the earlier row,
  // after every row has computed its own (the rows may be computed on several threads).
  std::vector<int> row_of(n, -1);
  for (std::size_t k = 0; k < rows.size(); ++k) row_of[static_cast<std::size_t>(rows[k])] = static_cast<int>(k);
  auto separable = [&](std::size_t p) { return transfer[2 * p].separable && transfer[2 * p + 1].separable; };
  // A marker that spreads onto no face of the fluid (west of a half tank's axis) has zero columns.
  auto spreads = [&](std::size_t p) { return !transfer[2 * p].sources.empty() || !transfer[2 * p + 1].sources.empty(); };
  auto copied = [&](std::size_t k, std::size_t a, std::size_t b) {
    const int l = row_of[b];
    return l >= 0 && static_cast<std::size_t>(l) < k && separable(a) && separable(b);
  };
  auto live = [&](std::size_t b) { return !is_masked(b) && spreads(b); };
  const auto compute_row = [&](std::size_t k) {
    const auto a = static_cast<std::size_t>(rows[k]);
    if (is_masked(a)) return;
    const auto ra = 2 * static_cast<Eigen::Index>(k);
    for (std::size_t b = 0; b < n; ++b) {
      if (!live(b) || copied(k, a, b)) continue;
      const auto cb = 2 * static_cast<Eigen::Index>(b);
      for (int c_to = 0; c_to < 2; ++c_to)
        for (int c_from = 0; c_from < 2; ++c_from)
          r(ra + c_to, cb + c_from) = scale * entry(transfer[2 * a + static_cast<std::size_t>(c_to)], c_to,
                                                    transfer[2 * b + static_cast<std::size_t>(c_from)], c_from);
    }
  };
  if (pool != nullptr && pool->threads() > 1) pool->run_tasks(rows.size(), compute_row);
  else for (std::size_t k = 0; k < rows.size(); ++k) compute_row(k);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto a = static_cast<std::size_t>(rows[k]);
    if (is_masked(a)) continue;
    for (std::size_t b = 0; b < n; ++b)
      if (live(b) && copied(k, a, b))
        r.block<2, 2>(2 * static_cast<Eigen::Index>(k), 2 * static_cast<Eigen::Index>(b)) =
            r.block<2, 2>(2 * static_cast<Eigen::Index>(row_of[b]), 2 * static_cast<Eigen::Index>(a)).transpose();
  }
}

}  // namespace jellysim::coupling

// ---- Axisymmetric water ----

namespace jellysim::coupling {

namespace {

/// Along r: sample i of a stencil folded across the axis (a normal sample −i is face i with sign
/// −1, a cell-centred one −1 − i is cell i), then the ghost rules at the outer side.
Axis radial_axis(const TransferGeometry& g) { return {g.grid.nx, BoundaryType::free_slip, g.sides.east.type, true}; }

/// A run of kernel weights along r folded onto real samples: at most four distinct ones.
struct RadialTerms {
  int i[4];
  double w[4];
  int count = 0;
  void add(int index, double weight) {
    for (int k = 0; k < count; ++k)
      if (i[k] == index) {
        w[k] += weight;
        return;
      }
    i[count] = index;
    w[count] = weight;
    ++count;
  }
};

}  // namespace

struct AxisymmetricMobility::Transfer {
  struct Term {
    int i, j;
    double w;
  };
  std::vector<Term> read;     ///< faces interpolation reads (folded, ghosts mapped)
  std::vector<Term> sources;  ///< spread faces' z-images on the torus, weight × sign / (2π r Δr Δz)
  /// Along z the stencil is a run of interior samples (away from the south and north sides): an
  /// entry is then Σ over radial pairs of a correlation of the z weights with a table row.
  bool separable = false;
  int width = 0, j0 = 0;
  double wz[4] = {0, 0, 0, 0};
  RadialTerms read_r, source_r;  ///< radial weights (sources: divided by the face's radius and 2π Δr Δz)
  ImageRun z_images[4];
  int z_image_count = 0;
};

AxisymmetricMobility::AxisymmetricMobility(const TransferGeometry& geometry) : geometry_(geometry) {
  if (geometry_.west_mirror) throw std::invalid_argument("axisymmetric mobility: the axis is not a mirror half tank");
  if (geometry_.sides.east.type == BoundaryType::periodic)
    throw std::invalid_argument("axisymmetric mobility: the radial direction cannot be periodic");
  const Axis az = y_axis(geometry_);
  if (az.periodic() != (az.high == BoundaryType::periodic))
    throw std::invalid_argument("mobility: a periodic side needs a periodic opposite side");
  period_z_ = torus_period(az);
  columns_.resize(2 * static_cast<std::size_t>(geometry_.grid.nx + 1));
}

AxisymmetricMobility::~AxisymmetricMobility() = default;

const std::vector<double>& AxisymmetricMobility::column(int c_from, int i_from) const {
  std::vector<double>& table = columns_[2 * static_cast<std::size_t>(i_from) + static_cast<std::size_t>(c_from)];
  if (!table.empty()) return table;
  // The response on the z-torus (the real sides in r) to a unit value on face (i_from, 0).
  const fluid::MacGrid& g = geometry_.grid;
  const fluid::MacGrid torus(g.nx, period_z_, g.width_m, period_z_ * g.dy(), g.origin_m);
  fluid::Boundaries sides = fluid::Boundaries::all(BoundaryType::periodic);
  sides.west = {BoundaryType::free_slip, {}};
  sides.east = {geometry_.sides.east.type, {}};
  fluid::Projector projector(fluid::make_pressure_solver("fft"), fluid::Geometry::axisymmetric);
  fluid::FlowState state(torus);
  (c_from == 0 ? state.velocity.u : state.velocity.v)(i_from, 0) = 1.0;
  fluid::apply_velocity_boundaries(state.velocity, sides);
  projector.project(state, sides, 1.0, 1.0);
  const auto rows = static_cast<std::size_t>(g.nx + 1), pz = static_cast<std::size_t>(period_z_);
  table.assign(2 * rows * pz, 0.0);
  for (int to = 0; to < 2; ++to) {
    const fluid::Field& f = to == 0 ? state.velocity.u : state.velocity.v;
    const int count = to == 0 ? g.nx + 1 : g.nx;
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < period_z_; ++j)
        table[(static_cast<std::size_t>(to) * rows + static_cast<std::size_t>(i)) * pz + static_cast<std::size_t>(j)] = f(i, j);
  }
  ++columns_built_;
  return table;
}

void AxisymmetricMobility::prepare(Vec2 p, int component, Transfer& t) const {
  const fluid::MacGrid& g = geometry_.grid;
  const Axis ar = radial_axis(geometry_), az = y_axis(geometry_);
  const bool normal_r = component == 0, normal_z = component == 1;
  const Vec2 f = sample_coordinates(g, p, component);
  const AxisWeights wr = axis_weights(geometry_.kernel, f.x), wz = axis_weights(geometry_.kernel, f.y);
  t.read.clear();
  t.sources.clear();
  t.read_r.count = t.source_r.count = 0;
  // Reading: the folded stencil with the ghost rules (interpolate_velocities_axisymmetric).
  for (int a = 0; a < wr.width; ++a) {
    int i;
    double fi;
    if (wr.w[a] == 0.0 || !real_sample(ar, normal_r, wr.first + a, i, fi)) continue;
    t.read_r.add(i, wr.w[a] * fi);
    for (int b = 0; b < wz.width; ++b) {
      int j;
      double fj;
      if (wz.w[b] == 0.0 || !real_sample(az, normal_z, wz.first + b, j, fj)) continue;
      t.read.push_back({i, j, wr.w[a] * fi * wz.w[b] * fj});
    }
  }
  // Spreading: folded across the axis, interior faces only, a ring's force over its volume element.
  const double element = 2.0 * std::numbers::pi * g.dx() * g.dy();
  for (int a = 0; a < wr.width; ++a) {
    int i = wr.first + a;
    double sign = 1.0;
    if (i < 0) i = normal_r ? -i : -1 - i, sign = normal_r ? -1.0 : 1.0;
    if (wr.w[a] == 0.0 || !interior_sample(ar, normal_r, i)) continue;
    const double radius = normal_r ? i * g.dx() : (i + 0.5) * g.dx();
    const double w = sign * wr.w[a] / (element * radius);
    t.source_r.add(i, w);
    for (int b = 0; b < wz.width; ++b) {
      const int j = wrap_periodic(az, wz.first + b);
      if (wz.w[b] == 0.0 || !interior_sample(az, normal_z, j)) continue;
      // apply_velocity_boundaries sets an outflow side's normal velocity to its first face's: the
      // face spread onto, and its copies on an outflow side.
      int rows_z[2] = {j, j}, rows_r[2] = {i, i};
      int count_z = 1, count_r = 1;
      if (normal_z && j == 1 && az.low == BoundaryType::outflow) rows_z[count_z++] = 0;
      if (normal_z && j == az.n - 1 && az.high == BoundaryType::outflow) rows_z[count_z++] = az.n;
      if (normal_r && i == ar.n - 1 && ar.high == BoundaryType::outflow) rows_r[count_r++] = ar.n;
      for (int cr = 0; cr < count_r; ++cr)
        for (int cz = 0; cz < count_z; ++cz) {
          const AxisImages images = axis_images(az, normal_z, rows_z[cz]);
          for (int k = 0; k < images.count; ++k)
            if (images.sign[k] != 0.0) t.sources.push_back({rows_r[cr], images.index[k], w * wz.w[b] * images.sign[k]});
        }
    }
  }
  t.separable = clean_run(az, normal_z, wz.first, wz.width) &&
                !(normal_r && ar.high == BoundaryType::outflow && wr.first + wr.width > ar.n - 1);
  if (!t.separable) return;
  t.width = wz.width;
  t.j0 = wz.first;
  std::copy(wz.w, wz.w + 4, t.wz);
  t.z_image_count = image_runs(az, normal_z, wz.first, t.z_images);
}

double AxisymmetricMobility::entry(const Transfer& to, int c_to, const Transfer& from, int c_from) const {
  const auto rows = static_cast<std::size_t>(geometry_.grid.nx + 1), pz = static_cast<std::size_t>(period_z_);
  auto row = [&](int i_from, int i_to) {
    return column(c_from, i_from).data() + (static_cast<std::size_t>(c_to) * rows + static_cast<std::size_t>(i_to)) * pz;
  };
  if (!(to.separable && from.separable)) {
    double sum = 0.0;
    for (const Transfer::Term& s : from.sources)
      for (const Transfer::Term& f : to.read) {
        int dj = f.j - s.j;
        if (dj < 0) dj += period_z_;
        sum += s.w * f.w * row(s.i, f.i)[dj];
      }
    return sum;
  }
  // Σ_images sign Σ_o c[o] T(dz + o): the z weights correlated once per image.
  const int w = to.width, span = 2 * w - 1;
  double c[4][7];
  int dz[4];
  for (int k = 0; k < from.z_image_count; ++k)
    dz[k] = w == 2 ? correlate<2>(to.wz, to.j0, from.wz, from.z_images[k], period_z_, c[k])
                   : correlate<4>(to.wz, to.j0, from.wz, from.z_images[k], period_z_, c[k]);
  double sum = 0.0;
  for (int a = 0; a < from.source_r.count; ++a)
    for (int b = 0; b < to.read_r.count; ++b) {
      const double* t = row(from.source_r.i[a], to.read_r.i[b]);
      double along = 0.0;
      for (int k = 0; k < from.z_image_count; ++k) {
        double partial = 0.0;
        if (dz[k] + span <= period_z_) {
          for (int o = 0; o < span; ++o) partial += c[k][o] * t[dz[k] + o];
        } else {
          for (int o = 0; o < span; ++o) partial += c[k][o] * t[(dz[k] + o) % period_z_];
        }
        along += from.z_images[k].sign * partial;
      }
      sum += from.source_r.w[a] * to.read_r.w[b] * along;
    }
  return sum;
}

void AxisymmetricMobility::assemble(std::span<const Vec2> points, std::span<const char> masked,
                                    std::span<const double> column_scale, double density_kg_per_m3,
                                    Eigen::MatrixXd& r) const {
  const std::size_t n = points.size();
  r.setZero(2 * static_cast<Eigen::Index>(n), 2 * static_cast<Eigen::Index>(n));
  auto is_masked = [&](std::size_t p) { return p < masked.size() && masked[p]; };
  transfer_.resize(2 * n);
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 2; ++c) {
      Transfer& t = transfer_[2 * p + static_cast<std::size_t>(c)];
      if (is_masked(p)) t.read.clear(), t.sources.clear(), t.separable = false;
      else prepare(points[p], c, t);
    }
  const double scale = 1.0 / density_kg_per_m3;
  for (std::size_t a = 0; a < n; ++a) {
    if (is_masked(a)) continue;
    for (std::size_t b = 0; b < n; ++b) {
      if (is_masked(b)) continue;
      for (int c_to = 0; c_to < 2; ++c_to)
        for (int c_from = 0; c_from < 2; ++c_from)
          r(2 * static_cast<Eigen::Index>(a) + c_to, 2 * static_cast<Eigen::Index>(b) + c_from) =
              scale * entry(transfer_[2 * a + static_cast<std::size_t>(c_to)], c_to,
                            transfer_[2 * b + static_cast<std::size_t>(c_from)], c_from);
    }
  }
  for (std::size_t b = 0; b < column_scale.size() && b < n; ++b)
    r.middleCols(2 * static_cast<Eigen::Index>(b), 2) *= column_scale[b];
}

}  // namespace jellysim::coupling
