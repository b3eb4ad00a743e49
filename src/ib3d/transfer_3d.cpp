#include "jellysim/ib3d/transfer_3d.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::ib3d {

namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

/// Folds sample i across the mirror planes of one axis; false when it carries nothing (the normal
/// component on the plane). normal: the samples along this axis are faces (the component is the
/// axis's own), else cell centres.
bool fold(const fluid3d::AxisBoundary3d& a, int n, bool normal, int& i, double& w) {
  if (a.symmetry[0] && (normal ? i <= 0 : i < 0)) {
    if (normal && i == 0) return false;
    i = normal ? -i : -1 - i;
    if (normal) w = -w;
  }
  if (a.symmetry[1] && (normal ? i >= n : i >= n)) {
    if (normal && i == n) return false;
    i = normal ? 2 * n - i : 2 * n - 1 - i;
    if (normal) w = -w;
  }
  return true;
}

}  // namespace

Transfer3d::Transfer3d(const fluid3d::Grid3d& grid, const fluid3d::Boundaries3d& boundaries, coupling::Kernel kernel,
                       WorkerPool* pool)
    : grid_(grid), boundaries_(boundaries), kernel_(kernel), pool_(pool) {
  boundaries_.validate();
}

void Transfer3d::axis_samples(int c, int d, double x, Stencil3d& s) const {
  const auto dd = static_cast<std::size_t>(d);
  const fluid3d::AxisBoundary3d& a = boundaries_.axis[dd];
  const bool normal = c == d;
  const int n = grid_.n(d), r = coupling::kernel_radius(kernel_);
  // Sample i of this component sits at grid coordinate i (faces) or i + ½ (cell centres).
  const double f = (x - grid_.origin()[dd]) / grid_.h(d) - (normal ? 0.0 : 0.5);
  const int i0 = static_cast<int>(std::floor(f)) - r + 1;
  int count = 0;
  for (int k = 0; k < 2 * r; ++k) {
    int i = i0 + k;
    double w = coupling::kernel_weight(kernel_, f - i);
    if (w == 0.0) continue;
    if (a.periodic) {
      i = wrap(i, n);
    } else {
      if (!fold(a, n, normal, i, w)) continue;
      if (i < -fluid3d::Grid3d::ghosts || i > n + fluid3d::Grid3d::ghosts) continue;  // beyond the stored range
    }
    s.index[dd][static_cast<std::size_t>(count)] = i;
    s.weight[dd][static_cast<std::size_t>(count)] = w;
    ++count;
  }
  s.count[dd] = count;
}

Stencil3d Transfer3d::stencil(int c, const Vec3& x) const {
  Stencil3d s;
  for (int d = 0; d < 3; ++d) axis_samples(c, d, x[static_cast<std::size_t>(d)], s);
  return s;
}

void Transfer3d::interpolate(const fluid3d::Velocity3d& vel, std::span<const Vec3> x, std::span<Vec3> out) {
  ensure_stencils(x);
  auto body = [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t m = begin; m < end; ++m)
      for (int c = 0; c < 3; ++c) {
        const Stencil3d& s = stencils_[3 * m + static_cast<std::size_t>(c)];
        const fluid3d::Field3d& q = vel.c[static_cast<std::size_t>(c)];
        double sum = 0.0;
        for (int kz = 0; kz < s.count[2]; ++kz)
          for (int ky = 0; ky < s.count[1]; ++ky) {
            const double wyz = s.weight[2][kz] * s.weight[1][ky];
            for (int kx = 0; kx < s.count[0]; ++kx)
              sum += wyz * s.weight[0][kx] * q[grid_.index(s.index[0][kx], s.index[1][ky], s.index[2][kz])];
          }
        out[m][static_cast<std::size_t>(c)] = sum;
      }
  };
  if (pool_) pool_->run(x.size(), body);
  else body(0, x.size(), 0);
}

// The semi-implicit step spreads and interpolates many times at the same marker positions (each
// Krylov iteration): the stencils are kept with the positions they were made for and remade only
// when the positions differ (compared value by value, so the results are those of fresh stencils).
void Transfer3d::ensure_stencils(std::span<const Vec3> x) {
  if (stencil_positions_.size() == x.size() && std::equal(x.begin(), x.end(), stencil_positions_.begin())) return;
  compute_stencils(x);
  stencil_positions_.assign(x.begin(), x.end());
}

void Transfer3d::compute_stencils(std::span<const Vec3> x) {
  stencils_.resize(3 * x.size());
  auto body = [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t m = begin; m < end; ++m)
      for (int c = 0; c < 3; ++c) stencils_[3 * m + static_cast<std::size_t>(c)] = stencil(c, x[m]);
  };
  if (pool_) pool_->run(x.size(), body);
  else body(0, x.size(), 0);
}

// Adds, marker by marker in order, the contributions whose z index lies in [k_begin, k_end).
void Transfer3d::spread_slab(std::span<const Vec3> force_n, double scale, int k_begin, int k_end,
                             fluid3d::Velocity3d& acc) const {
  for (std::size_t m = 0; m < force_n.size(); ++m)
    for (int c = 0; c < 3; ++c) {
      const double value = force_n[m][static_cast<std::size_t>(c)] * scale;
      if (value == 0.0) continue;
      const Stencil3d& s = stencils_[3 * m + static_cast<std::size_t>(c)];
      fluid3d::Field3d& q = acc.c[static_cast<std::size_t>(c)];
      for (int kz = 0; kz < s.count[2]; ++kz) {
        const int k = s.index[2][kz];
        if (k < k_begin || k >= k_end) continue;
        for (int ky = 0; ky < s.count[1]; ++ky) {
          const double wyz = s.weight[2][kz] * s.weight[1][ky] * value;
          for (int kx = 0; kx < s.count[0]; ++kx)
            q[grid_.index(s.index[0][kx], s.index[1][ky], k)] += wyz * s.weight[0][kx];
        }
      }
    }
}

void Transfer3d::spread(std::span<const Vec3> x, std::span<const Vec3> force_n, double density_kg_per_m3,
                        fluid3d::Velocity3d& acc) {
  ensure_stencils(x);
  const double scale = 1.0 / (density_kg_per_m3 * grid_.cell_volume());  // force density / ρ
  const int lowest = -fluid3d::Grid3d::ghosts;
  const auto planes = static_cast<std::size_t>(grid_.n(2) + 1 + 2 * fluid3d::Grid3d::ghosts);
  if (!pool_ || pool_->threads() == 1) {
    spread_slab(force_n, scale, lowest, lowest + static_cast<int>(planes), acc);
    return;
  }
  // One slab of z-planes per thread (the pool's fixed ranges): each face is written by one thread.
  const WorkerPool::Phase phase = [&](int part) {
    const auto [begin, end] = pool_->range(planes, part);
    spread_slab(force_n, scale, lowest + static_cast<int>(begin), lowest + static_cast<int>(end), acc);
  };
  pool_->run_phases(std::span<const WorkerPool::Phase>(&phase, 1));
}

}  // namespace jellysim::ib3d
