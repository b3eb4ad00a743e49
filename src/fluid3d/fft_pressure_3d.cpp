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

// The transform as three passes of contiguous 1D transforms, one per axis, with the data transposed
// between them so that every pass reads its lines with unit stride: FFTW then needs no buffered
// (strided) plans, whose buffers it allocates on every execution (about a third of the solve's time
// before). Layouts of the compact arrays: `x_` holds x-fastest (k, j, i) before the x pass and
// z-fastest (i, j, k) for the z pass; `y_` holds y-fastest (k, i, j). Each pass is cut into at most
// 8 **fixed** chunks of lines with a plan of their own, run as the pool's tasks; the transposes are
// copies. Neither depends on the thread count, so neither do the bits.
class FftPressure3d final : public PressureSolver3d {
 public:
  FftPressure3d(const Grid3d& g, const Boundaries3d& b, WorkerPool* pool) : g_(g), b_(b), pool_(pool) {
    for (int d = 0; d < 3; ++d)
      axes_[static_cast<std::size_t>(d)] = axis_transform(g.n(d), g.h(d), b.axis[static_cast<std::size_t>(d)].periodic);
    std::lock_guard<std::recursive_mutex> lock(fftw_planner_mutex());
    x_ = allocate(g.cell_count());
    y_ = allocate(g.cell_count());
    const std::array<double*, 3> on{x_, y_, x_};  // the array each axis's lines lie in
    for (int d = 0; d < 3; ++d)
      for (bool forward : {true, false}) {
        const int n = g.n(d), lines = static_cast<int>(g.cell_count()) / n;
        for (const auto& c : fixed_chunks(lines))
          plans_[static_cast<std::size_t>(d)][forward].push_back(plan_lines(d, forward, on[static_cast<std::size_t>(d)], c));
      }
  }
  ~FftPressure3d() override { release(); }
  FftPressure3d(const FftPressure3d&) = delete;
  FftPressure3d& operator=(const FftPressure3d&) = delete;

  std::string_view name() const override { return "fft"; }
  bool uses_initial_guess() const override { return false; }

  PressureReport3d solve(const Field3d& b, Field3d& p) override {
    copy_in(b);
    run_chunks(plans_[0][1]);
    transpose(Layout::x_fastest, Layout::y_fastest);
    run_chunks(plans_[1][1]);
    transpose(Layout::y_fastest, Layout::z_fastest);
    run_chunks(plans_[2][1]);
    divide_by_eigenvalues();
    run_chunks(plans_[2][0]);
    transpose(Layout::z_fastest, Layout::y_fastest);
    run_chunks(plans_[1][0]);
    transpose(Layout::y_fastest, Layout::x_fastest);
    run_chunks(plans_[0][0]);
    copy_out(p);
    apply_pressure_boundaries(g_, b_, p);
    return {1, 0.0};
  }

 private:
  enum class Layout { x_fastest, y_fastest, z_fastest };

  double* allocate(std::size_t n) {
    auto* p = static_cast<double*>(fftw_malloc(sizeof(double) * n));
    if (p == nullptr) {
      release();
      throw std::bad_alloc();
    }
    return p;
  }
  // Lines [c[0], c[1]) of axis d, each g.n(d) contiguous values. FFTW_NO_BUFFERING keeps the
  // planner off the buffered solvers (the lines are contiguous: they gain nothing); a size it
  // cannot plan so falls back to the planner's free choice.
  fftw_plan plan_lines(int d, bool forward, double* data, std::array<int, 2> c) {
    const auto& a = axes_[static_cast<std::size_t>(d)];
    const int n[1] = {g_.n(d)};
    const fftw_r2r_kind kinds[1] = {forward ? a.forward : a.inverse};
    double* first = data + static_cast<std::ptrdiff_t>(c[0]) * n[0];
    fftw_plan plan = nullptr;
    for (unsigned flags : {FFTW_ESTIMATE | FFTW_NO_BUFFERING, unsigned{FFTW_ESTIMATE}})
      if (plan == nullptr)
        plan = fftw_plan_many_r2r(1, n, c[1] - c[0], first, nullptr, 1, n[0], first, nullptr, 1, n[0], kinds, flags);
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
    for (auto& axis : plans_)
      for (auto& plans : axis) {
        for (fftw_plan plan : plans) fftw_destroy_plan(plan);
        plans.clear();
      }
    for (double** p : {&x_, &y_}) {
      if (*p != nullptr) fftw_free(*p);
      *p = nullptr;
    }
  }
  // The strides of i, j and k in a layout's compact array.
  std::array<std::size_t, 3> strides(Layout l) const {
    const auto nx = static_cast<std::size_t>(g_.n(0)), ny = static_cast<std::size_t>(g_.n(1)),
               nz = static_cast<std::size_t>(g_.n(2));
    switch (l) {
      case Layout::x_fastest: return {1, nx, nx * ny};
      case Layout::y_fastest: return {ny, 1, nx * ny};
      case Layout::z_fastest: return {ny * nz, nz, 1};
    }
    return {};
  }
  // Copies between the layouts (x_fastest and z_fastest live in x_, y_fastest in y_), split by the
  // destination's outermost index between the pool's threads.
  void transpose(Layout from, Layout to) {
    const double* src = from == Layout::y_fastest ? y_ : x_;
    double* dst = to == Layout::y_fastest ? y_ : x_;
    const auto nx = static_cast<std::size_t>(g_.n(0)), ny = static_cast<std::size_t>(g_.n(1)),
               nz = static_cast<std::size_t>(g_.n(2));
    const std::size_t outer = to == Layout::z_fastest ? nx : nz;
    const std::array<std::size_t, 3> s = strides(from);
    const auto body = [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t o = begin; o < end; ++o)
        for_cells_of(to, o, nx, ny, nz, [&](std::size_t i, std::size_t j, std::size_t k, std::size_t n) {
          dst[n] = src[i * s[0] + j * s[1] + k * s[2]];
        });
    };
    if (pool_ != nullptr)
      pool_->run(outer, body);
    else
      body(0, outer, 0);
  }
  // Visits the cells of one outermost slice o of layout `to` in its own storage order.
  template <class Cell>
  void for_cells_of(Layout to, std::size_t o, std::size_t nx, std::size_t ny, std::size_t nz, Cell&& cell) const {
    std::size_t n = 0;
    switch (to) {
      case Layout::x_fastest:
        n = o * ny * nx;
        for (std::size_t j = 0; j < ny; ++j)
          for (std::size_t i = 0; i < nx; ++i) cell(i, j, o, n++);
        return;
      case Layout::y_fastest:
        n = o * nx * ny;
        for (std::size_t i = 0; i < nx; ++i)
          for (std::size_t j = 0; j < ny; ++j) cell(i, j, o, n++);
        return;
      case Layout::z_fastest:
        n = o * ny * nz;
        for (std::size_t j = 0; j < ny; ++j)
          for (std::size_t k = 0; k < nz; ++k) cell(o, j, k, n++);
        return;
    }
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
    for_rows([&](int j, int k, std::size_t n) { std::copy_n(b.data() + g_.index(0, j, k), g_.n(0), x_ + n); });
  }
  void copy_out(Field3d& p) {
    for_rows([&](int j, int k, std::size_t n) { std::copy_n(x_ + n, g_.n(0), p.data() + g_.index(0, j, k)); });
  }
  // p̂ = b̂ / (λx + λy + λz) in the z-fastest layout, scaled for the unnormalised round trip; the null
  // mode (the mean, whose eigenvalue is 0) is set to zero, which removes b's mean and makes p mean-free.
  void divide_by_eigenvalues() {
    const double scale = axes_[0].scale * axes_[1].scale * axes_[2].scale;
    const auto ny = static_cast<std::size_t>(g_.n(1)), nz = static_cast<std::size_t>(g_.n(2));
    const auto body = [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t i = begin; i < end; ++i)
        for (std::size_t j = 0; j < ny; ++j) {
          const double lxy = axes_[0].eigenvalue[i] + axes_[1].eigenvalue[j];
          double* line = x_ + (i * ny + j) * nz;  // the z-fastest layout's line (i, j)
          for (std::size_t k = 0; k < nz; ++k) {
            const double lambda = lxy + axes_[2].eigenvalue[k];
            line[k] = lambda == 0.0 ? 0.0 : line[k] / (lambda * scale);
          }
        }
    };
    if (pool_ != nullptr)
      pool_->run(static_cast<std::size_t>(g_.n(0)), body);
    else
      body(0, static_cast<std::size_t>(g_.n(0)), 0);
  }

  Grid3d g_;
  Boundaries3d b_;
  WorkerPool* pool_;
  std::array<AxisTransform, 3> axes_;
  double* x_ = nullptr;  ///< x-fastest, then z-fastest
  double* y_ = nullptr;  ///< y-fastest
  std::array<std::array<std::vector<fftw_plan>, 2>, 3> plans_;  ///< [axis][0] inverse, [axis][1] forward
};

}  // namespace

std::unique_ptr<PressureSolver3d> make_fft_pressure_3d(const Grid3d& g, const Boundaries3d& b, WorkerPool* pool) {
  return std::make_unique<FftPressure3d>(g, b, pool);
}

}  // namespace jellysim::fluid3d
