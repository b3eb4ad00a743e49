#include "jellysim/fluid3d/pressure_3d.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fft_pressure_3d.hpp"
#include "multigrid_3d.hpp"

namespace jellysim::fluid3d {

double centre_laplacian(const Grid3d& g, const Field3d& p, int i, int j, int k) {
  const std::size_t I = g.index(i, j, k);
  double sum = 0.0;
  for (int d = 0; d < 3; ++d) {
    const std::size_t s = g.stride(d);
    sum += (p[I + s] - 2.0 * p[I] + p[I - s]) / (g.h(d) * g.h(d));
  }
  return sum;
}

double interior_mean(const Grid3d& g, const Field3d& f) {
  double sum = 0.0;
  for_each_interior_cell(g, [&](std::size_t I, int, int, int) { sum += f[I]; });
  return sum / static_cast<double>(g.cell_count());
}

namespace {

// Conjugate gradients on A p = −b, A = −∇² (symmetric positive semi-definite; mean-free fields),
// written for r = b − ∇²p: d = −r; α = r·r / d·Ad; p += αd; r += αAd; β = r'·r' / r·r; d = −r + βd.
class CgPressure3d final : public PressureSolver3d {
 public:
  CgPressure3d(const Grid3d& g, const Boundaries3d& b, const PressureSettings3d& s)
      : g_(g), b_(b), s_(s), r_(g.padded_size(), 0.0), d_(g.padded_size(), 0.0), ad_(g.padded_size(), 0.0) {}
  std::string_view name() const override { return "cg"; }

  PressureReport3d solve(const Field3d& b, Field3d& p) override {
    const double mean = interior_mean(g_, b);
    double bmax = 0.0;
    for_each_interior_cell(g_, [&](std::size_t I, int, int, int) { bmax = std::max(bmax, std::abs(b[I] - mean)); });
    apply_pressure_boundaries(g_, b_, p);
    double rr = 0.0;
    for_each_interior_cell(g_, [&](std::size_t I, int i, int j, int k) {
      r_[I] = (b[I] - mean) - centre_laplacian(g_, p, i, j, k);  // residual of ∇²p = b, i.e. of A p = −b
      d_[I] = -r_[I];
      rr += r_[I] * r_[I];
    });
    PressureReport3d report;
    for (; report.iterations < s_.max_iterations; ++report.iterations) {
      if ((report.residual_max = max_abs(r_)) <= s_.relative_tolerance * bmax) break;
      apply_pressure_boundaries(g_, b_, d_);
      double dad = 0.0;
      for_each_interior_cell(g_, [&](std::size_t I, int i, int j, int k) {
        ad_[I] = -centre_laplacian(g_, d_, i, j, k);
        dad += d_[I] * ad_[I];
      });
      const double alpha = rr / dad;
      double rr_new = 0.0;
      for_each_interior_cell(g_, [&](std::size_t I, int, int, int) {
        p[I] += alpha * d_[I];
        r_[I] += alpha * ad_[I];  // r = b − ∇²p = A p + b falls by α A d along d = −r + βd
        rr_new += r_[I] * r_[I];
      });
      const double beta = rr_new / rr;
      rr = rr_new;
      for_each_interior_cell(g_, [&](std::size_t I, int, int, int) { d_[I] = -r_[I] + beta * d_[I]; });
    }
    const double pmean = interior_mean(g_, p);
    for_each_interior_cell(g_, [&](std::size_t I, int, int, int) { p[I] -= pmean; });
    apply_pressure_boundaries(g_, b_, p);
    return report;
  }

 private:
  double max_abs(const Field3d& f) const {
    double m = 0.0;
    for_each_interior_cell(g_, [&](std::size_t I, int, int, int) { m = std::max(m, std::abs(f[I])); });
    return m;
  }

  Grid3d g_;
  Boundaries3d b_;
  PressureSettings3d s_;
  Field3d r_, d_, ad_;
};

}  // namespace

const std::vector<std::string>& pressure_solver_3d_names() {
  static const std::vector<std::string> names{"fft", "multigrid", "cg"};
  return names;
}

std::unique_ptr<PressureSolver3d> make_pressure_solver_3d(std::string_view name, const Grid3d& g, const Boundaries3d& b,
                                                          const PressureSettings3d& settings, WorkerPool* pool) {
  if (name == "fft") return make_fft_pressure_3d(g, b, pool);
  if (name == "multigrid") return make_multigrid_pressure_3d(g, b, settings);
  if (name == "cg") return std::make_unique<CgPressure3d>(g, b, settings);
  throw std::invalid_argument("unknown 3D pressure solver '" + std::string(name) + "' (fft, multigrid, cg)");
}

}  // namespace jellysim::fluid3d
