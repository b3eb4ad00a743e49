#include "fft_pressure_3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
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

// The chunks [first, last) of n items: kChunks (or n) nearly equal parts, fixed whatever the number
// of threads, so every line is transformed by the same plan on any thread count (the same bits).
constexpr int kChunks = 8;
std::vector<std::array<int, 2>> fixed_chunks(int n) {
  const int parts = std::min(kChunks, n);
  std::vector<std::array<int, 2>> chunks;
  for (int c = 0; c < parts; ++c) chunks.push_back({n * c / parts, n * (c + 1) / parts});
  return chunks;
}

// The transform in two passes, each split into fixed chunks run as the pool's tasks: the 2D (x, y)
// transforms of a slab of z-planes, and the 1D z transforms of the lines of a band of y-rows.
class FftPressure3d final : public PressureSolver3d {
 public:
  FftPressure3d(const Grid3d& g, const Boundaries3d& b, WorkerPool* pool)
      : g_(g), b_(b), pool_(pool), planes_(fixed_chunks(g.n(2))), rows_(fixed_chunks(g.n(1))) {
    for (int d = 0; d < 3; ++d)
      axes_[static_cast<std::size_t>(d)] = axis_transform(g.n(d), g.h(d), b.axis[static_cast<std::size_t>(d)].periodic);
    std::lock_guard<std::recursive_mutex> lock(fftw_planner_mutex());
    data_ = static_cast<double*>(fftw_malloc(sizeof(double) * g.cell_count()));
    if (data_ == nullptr) throw std::bad_alloc();
    for (bool forward : {true, false}) {
      for (const auto& c : planes_) plane_plans_[forward].push_back(plan_planes(c, forward));
      for (const auto& c : rows_) line_plans_[forward].push_back(plan_lines(c, forward));
    }
  }
  ~FftPressure3d() override { release(); }
  FftPressure3d(const FftPressure3d&) = delete;
  FftPressure3d& operator=(const FftPressure3d&) = delete;

  std::string_view name() const override { return "fft"; }
  bool uses_initial_guess() const override { return false; }

  PressureReport3d solve(const Field3d& b, Field3d& p) override {
    copy_in(b);
    run_chunks(plane_plans_[1]);
    run_chunks(line_plans_[1]);
    divide_by_eigenvalues();
    run_chunks(line_plans_[0]);
    run_chunks(plane_plans_[0]);
    copy_out(p);
    apply_pressure_boundaries(g_, b_, p);
    return {1, 0.0};
  }

 private:
  // FFTW's arrays are row-major (last index fastest): a plane is (ny, nx).
  fftw_plan plan_planes(std::array<int, 2> k, bool forward) {
    const int n[2] = {g_.n(1), g_.n(0)}, plane = n[0] * n[1];
    const fftw_r2r_kind kinds[2] = {forward ? axes_[1].forward : axes_[1].inverse, forward ? axes_[0].forward : axes_[0].inverse};
    double* first = data_ + static_cast<std::ptrdiff_t>(k[0]) * plane;
    return checked(fftw_plan_many_r2r(2, n, k[1] - k[0], first, nullptr, 1, plane, first, nullptr, 1, plane, kinds, FFTW_ESTIMATE));
  }
  fftw_plan plan_lines(std::array<int, 2> j, bool forward) {
    const int n[1] = {g_.n(2)}, plane = g_.n(0) * g_.n(1);
    const fftw_r2r_kind kinds[1] = {forward ? axes_[2].forward : axes_[2].inverse};
    double* first = data_ + static_cast<std::ptrdiff_t>(j[0]) * g_.n(0);
    return checked(fftw_plan_many_r2r(1, n, (j[1] - j[0]) * g_.n(0), first, nullptr, plane, 1, first, nullptr, plane, 1,
                                      kinds, FFTW_ESTIMATE));
  }
  fftw_plan checked(fftw_plan plan) {
    if (plan == nullptr) {
      release();
      throw std::runtime_error("FFTW could not plan the 3D pressure transforms");
    }
    return plan;
  }
  void run_chunks(const std::vector<fftw_plan>& plans) {
    const auto task = [&](std::size_t c) { fftw_execute(plans[c]); };
    if (pool_ != nullptr)
      pool_->run_tasks(plans.size(), task);
    else
      for (std::size_t c = 0; c < plans.size(); ++c) task(c);
  }
  void release() {
    std::lock_guard<std::recursive_mutex> lock(fftw_planner_mutex());
    for (auto* plans : {&plane_plans_[0], &plane_plans_[1], &line_plans_[0], &line_plans_[1]}) {
      for (fftw_plan plan : *plans) fftw_destroy_plan(plan);
      plans->clear();
    }
    if (data_ != nullptr) fftw_free(data_);
    data_ = nullptr;
  }
  // Calls row(j, k, n) for every x-row of cells, n the row's first index in the compact array; the
  // rows split between the pool's threads (element-wise work: the same bits on any thread count).
  template <class Row>
  void for_rows(Row&& row) {
    const std::size_t ny = static_cast<std::size_t>(g_.n(1)), rows = ny * static_cast<std::size_t>(g_.n(2));
    const auto body = [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t r = begin; r < end; ++r)
        row(static_cast<int>(r % ny), static_cast<int>(r / ny), r * static_cast<std::size_t>(g_.n(0)));
    };
    if (pool_ != nullptr)
      pool_->run(rows, body);
    else
      body(0, rows, 0);
  }
  void copy_in(const Field3d& b) {
    for_rows([&](int j, int k, std::size_t n) { std::copy_n(b.data() + g_.index(0, j, k), g_.n(0), data_ + n); });
  }
  void copy_out(Field3d& p) {
    for_rows([&](int j, int k, std::size_t n) { std::copy_n(data_ + n, g_.n(0), p.data() + g_.index(0, j, k)); });
  }
  // p̂ = b̂ / (λx + λy + λz), scaled for the unnormalised round trip; the null mode (the mean, whose
  // eigenvalue is 0) is set to zero, which removes b's mean and makes p mean-free.
  void divide_by_eigenvalues() {
    const double scale = axes_[0].scale * axes_[1].scale * axes_[2].scale;
    for_rows([&](int j, int k, std::size_t n) {
      const double lyz = axes_[1].eigenvalue[static_cast<std::size_t>(j)] + axes_[2].eigenvalue[static_cast<std::size_t>(k)];
      for (int i = 0; i < g_.n(0); ++i, ++n) {
        const double lambda = axes_[0].eigenvalue[static_cast<std::size_t>(i)] + lyz;
        data_[n] = lambda == 0.0 ? 0.0 : data_[n] / (lambda * scale);
      }
    });
  }

  Grid3d g_;
  Boundaries3d b_;
  WorkerPool* pool_;
  std::array<AxisTransform, 3> axes_;
  std::vector<std::array<int, 2>> planes_, rows_;
  double* data_ = nullptr;
  std::array<std::vector<fftw_plan>, 2> plane_plans_, line_plans_;  ///< [0] inverse, [1] forward
};

}  // namespace

std::unique_ptr<PressureSolver3d> make_fft_pressure_3d(const Grid3d& g, const Boundaries3d& b, WorkerPool* pool) {
  return std::make_unique<FftPressure3d>(g, b, pool);
}

}  // namespace jellysim::fluid3d
