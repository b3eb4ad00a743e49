#include "fluid/fft_poisson.hpp"

#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include <fftw3.h>

namespace jellysim::fluid {

namespace {

// FFTW's planner is not thread-safe; execution of distinct plans is.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

struct AxisTransform {
  fftw_r2r_kind forward, inverse;
  double normalisation;  ///< inverse(forward(x)) = normalisation · x
};

AxisTransform axis_transform(int n, PressureBoundary low, PressureBoundary high) {
  using PB = PressureBoundary;
  if (low == PB::periodic) return {FFTW_R2HC, FFTW_HC2R, static_cast<double>(n)};
  if (low == PB::neumann && high == PB::neumann) return {FFTW_REDFT10, FFTW_REDFT01, 2.0 * n};
  if (low == PB::dirichlet && high == PB::dirichlet) return {FFTW_RODFT10, FFTW_RODFT01, 2.0 * n};
  if (low == PB::neumann) return {FFTW_REDFT11, FFTW_REDFT11, 2.0 * n};
  return {FFTW_RODFT11, FFTW_RODFT11, 2.0 * n};
}

}  // namespace

std::vector<double> axis_eigenvalues(int n, double h, PressureBoundary low, PressureBoundary high) {
  using PB = PressureBoundary;
  std::vector<double> lambda(static_cast<std::size_t>(n));
  for (int m = 0; m < n; ++m) {
    double theta = 0.0;
    if (low == PB::periodic) {
      const int k = m <= n / 2 ? m : n - m;  // halfcomplex order: r0, r1 … r_{n/2}, i_{(n−1)/2} … i1
      theta = 2.0 * std::numbers::pi * k / n;
    } else if (low == PB::neumann && high == PB::neumann) {
      theta = std::numbers::pi * m / n;
    } else if (low == PB::dirichlet && high == PB::dirichlet) {
      theta = std::numbers::pi * (m + 1) / n;
    } else {
      theta = std::numbers::pi * (m + 0.5) / n;
    }
    lambda[static_cast<std::size_t>(m)] = -(2.0 - 2.0 * std::cos(theta)) / (h * h);
  }
  return lambda;
}

struct FftPoissonSolver::Plans {
  double* data = nullptr;
  fftw_plan forward = nullptr, inverse = nullptr;
  ~Plans() {
    std::lock_guard<std::mutex> lock(planner_mutex());
    if (forward) fftw_destroy_plan(forward);
    if (inverse) fftw_destroy_plan(inverse);
    if (data) fftw_free(data);
  }
};

FftPoissonSolver::FftPoissonSolver() = default;
FftPoissonSolver::~FftPoissonSolver() = default;

void FftPoissonSolver::plan(const PoissonOperator& op) {
  if (planned_ && planned_->same_problem(op)) return;
  const int nx = op.nx(), ny = op.ny();
  const auto& s = op.sides();  // west, east, south, north
  const AxisTransform tx = axis_transform(nx, s[0], s[1]), ty = axis_transform(ny, s[2], s[3]);
  plans_.reset();
  auto plans = std::make_unique<Plans>();
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
    plans->data = fftw_alloc_real(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
    if (plans->data == nullptr) throw std::bad_alloc();
    // Row-major, index j·nx + i: the slow dimension is y.
    plans->forward = fftw_plan_r2r_2d(ny, nx, plans->data, plans->data, ty.forward, tx.forward, FFTW_ESTIMATE);
    plans->inverse = fftw_plan_r2r_2d(ny, nx, plans->data, plans->data, ty.inverse, tx.inverse, FFTW_ESTIMATE);
  }
  if (!plans->forward || !plans->inverse) throw std::runtime_error("fft pressure solver: FFTW could not plan the transforms");
  plans_ = std::move(plans);
  normalisation_ = tx.normalisation * ty.normalisation;
  const std::vector<double> lx = axis_eigenvalues(nx, op.dx(), s[0], s[1]);
  const std::vector<double> ly = axis_eigenvalues(ny, op.dy(), s[2], s[3]);
  inverse_eigenvalue_.resize(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  const double scale = std::max(std::abs(lx.back()), std::abs(ly.back()));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double lambda = lx[static_cast<std::size_t>(i)] + ly[static_cast<std::size_t>(j)];
      // The null mode (constants, only for singular problems) gets 0: the mean-free solution.
      inverse_eigenvalue_[static_cast<std::size_t>(j * nx + i)] =
          std::abs(lambda) > 1e-12 * scale ? 1.0 / (lambda * normalisation_) : 0.0;
    }
  planned_ = std::make_unique<PoissonOperator>(op);
}

PressureSolveReport FftPoissonSolver::solve(const PoissonOperator& op, std::span<const double> b,
                                            std::span<double> p) {
  plan(op);
  double* data = plans_->data;
  const std::size_t n = p.size();
  double mean = 0.0;
  if (op.singular()) {
    for (double v : b) mean += v;
    mean /= static_cast<double>(n);
  }
  for (std::size_t k = 0; k < n; ++k) data[k] = b[k] - mean;
  fftw_execute(plans_->forward);
  for (std::size_t k = 0; k < n; ++k) data[k] *= inverse_eigenvalue_[k];
  fftw_execute(plans_->inverse);
  for (std::size_t k = 0; k < n; ++k) p[k] = data[k];
  if (op.singular()) remove_mean(p);
  PressureSolveReport report;
  report.iterations = 1;
  report.converged = true;
  return report;
}

}  // namespace jellysim::fluid
