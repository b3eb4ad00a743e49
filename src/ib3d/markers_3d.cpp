#include "jellysim/ib3d/markers_3d.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace jellysim::ib3d {

namespace {

using Triplet = Eigen::Triplet<double>;

/// B = ∂F_a/∂x_b of a linear spring a–b with d = x_b − x_a, l = |d|: k[(1 − L/l) I + (L/l) d̂d̂ᵀ].
std::array<std::array<double, 3>, 3> spring_block(const SpringNet3d::Spring& s, const Vec3& d) {
  const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double ratio = l > 0.0 ? s.rest_length_m / l : 0.0;
  std::array<std::array<double, 3>, 3> b{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dd = l > 0.0 ? d[static_cast<std::size_t>(i)] * d[static_cast<std::size_t>(j)] / (l * l) : 0.0;
      b[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
          s.stiffness_n_per_m * ((i == j ? 1.0 - ratio : 0.0) + ratio * dd);
    }
  return b;
}

Vec3 difference(std::span<const Vec3> x, int a, int b) {
  const Vec3& xa = x[static_cast<std::size_t>(a)];
  const Vec3& xb = x[static_cast<std::size_t>(b)];
  return {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
}

}  // namespace

bool ForceModel3d::stiffness(double, std::span<const Vec3>, Eigen::SparseMatrix<double>&) const { return false; }

Tethers3d::Tethers3d(std::vector<Vec3> anchors, std::vector<double> stiffness_n_per_m)
    : anchors_(std::move(anchors)), stiffness_(std::move(stiffness_n_per_m)) {
  if (anchors_.size() != stiffness_.size()) throw std::invalid_argument("Tethers3d: one stiffness per anchor");
}

void Tethers3d::forces(double, std::span<const Vec3> x, std::span<Vec3> f) const {
  for (std::size_t m = 0; m < x.size(); ++m)
    for (std::size_t d = 0; d < 3; ++d) f[m][d] = stiffness_[m] * (anchors_[m][d] - x[m][d]);
}

void Tethers3d::jacobian_times(double, std::span<const Vec3>, std::span<const Vec3> dx, std::span<Vec3> df) const {
  for (std::size_t m = 0; m < dx.size(); ++m)
    for (std::size_t d = 0; d < 3; ++d) df[m][d] = -stiffness_[m] * dx[m][d];
}

bool Tethers3d::stiffness(double, std::span<const Vec3> x, Eigen::SparseMatrix<double>& k) const {
  const auto n = 3 * static_cast<Eigen::Index>(x.size());
  k.resize(n, n);
  std::vector<Triplet> t;
  for (Eigen::Index i = 0; i < n; ++i) t.emplace_back(i, i, -stiffness_[static_cast<std::size_t>(i / 3)]);
  k.setFromTriplets(t.begin(), t.end());
  return true;
}

SpringNet3d::SpringNet3d(std::vector<Spring> springs, const ForceModel3d* also)
    : springs_(std::move(springs)), also_(also) {}

void SpringNet3d::forces(double t_s, std::span<const Vec3> x, std::span<Vec3> f) const {
  if (also_) also_->forces(t_s, x, f);
  else std::fill(f.begin(), f.end(), Vec3{});
  for (const Spring& s : springs_) {
    const Vec3 d = difference(x, s.a, s.b);
    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double scale = l > 0.0 ? s.stiffness_n_per_m * (l - s.rest_length_m) / l : 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      f[static_cast<std::size_t>(s.a)][c] += scale * d[c];
      f[static_cast<std::size_t>(s.b)][c] -= scale * d[c];
    }
  }
}

void SpringNet3d::jacobian_times(double t_s, std::span<const Vec3> x, std::span<const Vec3> dx,
                                 std::span<Vec3> df) const {
  if (also_) also_->jacobian_times(t_s, x, dx, df);
  else std::fill(df.begin(), df.end(), Vec3{});
  for (const Spring& s : springs_) {
    const auto b = spring_block(s, difference(x, s.a, s.b));
    const Vec3 rel = difference(dx, s.a, s.b);  // dx_b − dx_a
    for (std::size_t i = 0; i < 3; ++i) {
      const double v = b[i][0] * rel[0] + b[i][1] * rel[1] + b[i][2] * rel[2];
      df[static_cast<std::size_t>(s.a)][i] += v;
      df[static_cast<std::size_t>(s.b)][i] -= v;
    }
  }
}

bool SpringNet3d::stiffness(double t_s, std::span<const Vec3> x, Eigen::SparseMatrix<double>& k) const {
  const auto n = 3 * static_cast<Eigen::Index>(x.size());
  Eigen::SparseMatrix<double> base(n, n);
  if (also_ && !also_->stiffness(t_s, x, base)) return false;
  std::vector<Triplet> t;
  for (const Spring& s : springs_) {
    const auto b = spring_block(s, difference(x, s.a, s.b));
    const Eigen::Index pa = 3 * s.a, pb = 3 * s.b;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double v = b[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        t.emplace_back(pa + i, pb + j, v);   // ∂F_a/∂x_b = B
        t.emplace_back(pa + i, pa + j, -v);  // ∂F_a/∂x_a = −B
        t.emplace_back(pb + i, pa + j, v);   // ∂F_b/∂x_a = B
        t.emplace_back(pb + i, pb + j, -v);  // ∂F_b/∂x_b = −B
      }
  }
  k.resize(n, n);
  k.setFromTriplets(t.begin(), t.end());
  if (also_) k += base;
  return true;
}

std::vector<Vec3> sphere_surface_markers(const Vec3& centre, double radius_m, double spacing_m, bool quarter_only) {
  std::vector<Vec3> x;
  const int rings = std::max(2, static_cast<int>(std::ceil(std::numbers::pi * radius_m / spacing_m)));
  for (int i = 0; i < rings; ++i) {
    const double theta = std::numbers::pi * (i + 0.5) / rings;
    const double ring = radius_m * std::sin(theta);
    const int around = 4 * std::max(1, static_cast<int>(std::lround(0.5 * std::numbers::pi * ring / spacing_m)));
    for (int j = 0; j < around; ++j) {
      const double phi = 2.0 * std::numbers::pi * (j + 0.5) / around;
      const Vec3 p{centre[0] + ring * std::cos(phi), centre[1] - radius_m * std::cos(theta), centre[2] + ring * std::sin(phi)};
      if (!quarter_only || (p[0] > centre[0] && p[2] > centre[2])) x.push_back(p);
    }
  }
  return x;
}

std::vector<SpringNet3d::Spring> neighbour_springs(std::span<const Vec3> x, double max_distance_m, double stiffness_n_per_m) {
  std::vector<SpringNet3d::Spring> springs;
  for (std::size_t a = 0; a < x.size(); ++a)
    for (std::size_t b = a + 1; b < x.size(); ++b) {
      const Vec3 d = difference(x, static_cast<int>(a), static_cast<int>(b));
      const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (l < max_distance_m) springs.push_back({static_cast<int>(a), static_cast<int>(b), l, stiffness_n_per_m});
    }
  return springs;
}

}  // namespace jellysim::ib3d
