#include "fft_pressure_3d.hpp"

#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <fftw3.h>

#include "jellysim/fluid/fftw_planner.hpp"

namespace jellysim::fluid3d {

namespace {

using fluid::fftw_planner_mutex;

// The transform pair of one axis, its round-trip scale, and the Laplacian's eigenvalue per slot.
struct AxisTransform {
  fftw_r2r_kind forward, inverse;
  double scale;
  std::vector<double> eigenvalue;
};

// Between walls (cell-centred Neumann): DCT-II, λ(k) = −(4/h²) sin²(πk/(2n)); periodic: the real
// DFT in half-complex order (slot m holds frequency min(m, n − m)), λ = −(4/h²) sin²(πk/n).
AxisTransform axis_transform(int n, double h, bool periodic) {
  AxisTransform t{periodic ? FFTW_R2HC : FFTW_REDFT10, periodic ? FFTW_HC2R : FFTW_REDFT01,
                  periodic ? static_cast<double>(n) : 2.0 * n, std::vector<double>(static_cast<std::size_t>(n))};
  for (int m = 0; m < n; ++m) {
    const double angle = periodic ? std::numbers::pi * std::min(m, n - m) / n : std::numbers::pi * m / (2.0 * n);
    const double s = std::sin(angle);
    t.eigenvalue[static_cast<std::size_t>(m)] = -4.0 * s * s / (h * h);
  }
  return t;
}

class FftPressure3d final : public PressureSolver3d {
 public:
  FftPressure3d(const Grid3d& g, const Boundaries3d& b) : g_(g), b_(b) {
    for (int d = 0; d < 3; ++d)
      axes_[static_cast<std::size_t>(d)] = axis_transform(g.n(d), g.h(d), b.axis[static_cast<std::size_t>(d)].periodic);
    std::lock_guard<std::recursive_mutex> lock(fftw_planner_mutex());
    data_ = static_cast<double*>(fftw_malloc(sizeof(double) * g.cell_count()));
    if (data_ == nullptr) throw std::bad_alloc();
    // FFTW's arrays are row-major (last index fastest): dimensions (nz, ny, nx).
    forward_ = fftw_plan_r2r_3d(g.n(2), g.n(1), g.n(0), data_, data_, axes_[2].forward, axes_[1].forward,
                                axes_[0].forward, FFTW_ESTIMATE);
    inverse_ = fftw_plan_r2r_3d(g.n(2), g.n(1), g.n(0), data_, data_, axes_[2].inverse, axes_[1].inverse,
                                axes_[0].inverse, FFTW_ESTIMATE);
    if (forward_ == nullptr || inverse_ == nullptr) {
      release();
      throw std::runtime_error("FFTW could not plan the 3D pressure transforms");
    }
  }
  ~FftPressure3d() override { release(); }
  FftPressure3d(const FftPressure3d&) = delete;
  FftPressure3d& operator=(const FftPressure3d&) = delete;

  std::string_view name() const override { return "fft"; }
  bool uses_initial_guess() const override { return false; }

  PressureReport3d solve(const Field3d& b, Field3d& p) override {
    copy_in(b);
    fftw_execute(forward_);
    divide_by_eigenvalues();
    fftw_execute(inverse_);
    copy_out(p);
    apply_pressure_boundaries(g_, b_, p);
    return {1, 0.0};
  }

 private:
  void release() {
    std::lock_guard<std::recursive_mutex> lock(fftw_planner_mutex());
    if (forward_ != nullptr) fftw_destroy_plan(forward_);
    if (inverse_ != nullptr) fftw_destroy_plan(inverse_);
    if (data_ != nullptr) fftw_free(data_);
    forward_ = inverse_ = nullptr;
    data_ = nullptr;
  }
  void copy_in(const Field3d& b) {
    std::size_t n = 0;
    for_each_interior_cell(g_, [&](std::size_t I, int, int, int) { data_[n++] = b[I]; });
  }
  void copy_out(Field3d& p) const {
    std::size_t n = 0;
    for_each_interior_cell(g_, [&](std::size_t I, int, int, int) { p[I] = data_[n++]; });
  }
  // p̂ = b̂ / (λx + λy + λz), scaled for the unnormalised round trip; the null mode (the mean, whose
  // eigenvalue is 0) is set to zero, which removes b's mean and makes p mean-free.
  void divide_by_eigenvalues() {
    const double scale = axes_[0].scale * axes_[1].scale * axes_[2].scale;
    std::size_t n = 0;
    for (int k = 0; k < g_.n(2); ++k)
      for (int j = 0; j < g_.n(1); ++j) {
        const double lyz = axes_[1].eigenvalue[static_cast<std::size_t>(j)] + axes_[2].eigenvalue[static_cast<std::size_t>(k)];
        for (int i = 0; i < g_.n(0); ++i, ++n) {
          const double lambda = axes_[0].eigenvalue[static_cast<std::size_t>(i)] + lyz;
          data_[n] = lambda == 0.0 ? 0.0 : data_[n] / (lambda * scale);
        }
      }
  }

  Grid3d g_;
  Boundaries3d b_;
  std::array<AxisTransform, 3> axes_;
  double* data_ = nullptr;
  fftw_plan forward_ = nullptr, inverse_ = nullptr;
};

}  // namespace

std::unique_ptr<PressureSolver3d> make_fft_pressure_3d(const Grid3d& g, const Boundaries3d& b) {
  return std::make_unique<FftPressure3d>(g, b);
}

}  // namespace jellysim::fluid3d
