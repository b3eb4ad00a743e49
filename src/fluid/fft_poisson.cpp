#include "jellysim/fluid/fft_poisson.hpp"
#include "jellysim/fluid/fftw_planner.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <fftw3.h>

#include "double2.hpp"

namespace jellysim::fluid {

std::recursive_mutex& fftw_planner_mutex() {
  static std::recursive_mutex m;
  return m;
}

namespace {

std::recursive_mutex& planner_mutex() { return fftw_planner_mutex(); }

using PB = PressureBoundary;

/// An fftw_malloc'ed array: aligned as FFTW likes, and always the same array for a plan, so that
/// every execution takes the code path chosen at plan time.
template <class T>
class FftwArray {
 public:
  explicit FftwArray(std::size_t n) {
    std::lock_guard<std::recursive_mutex> lock(planner_mutex());
    data_ = static_cast<T*>(fftw_malloc(sizeof(T) * std::max<std::size_t>(n, 1)));
    if (data_ == nullptr) throw std::bad_alloc();
  }
  ~FftwArray() {
    std::lock_guard<std::recursive_mutex> lock(planner_mutex());
    fftw_free(data_);
  }
  FftwArray(const FftwArray&) = delete;
  FftwArray& operator=(const FftwArray&) = delete;
  T* data() const { return data_; }

 private:
  T* data_ = nullptr;
};

class Plan {
 public:
  explicit Plan(fftw_plan p) : plan_(p) {
    if (plan_ == nullptr) throw std::runtime_error("fft pressure solver: FFTW could not plan a transform");
  }
  ~Plan() {
    std::lock_guard<std::recursive_mutex> lock(planner_mutex());
    fftw_destroy_plan(plan_);
  }
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;
  void execute() const { fftw_execute(plan_); }

 private:
  fftw_plan plan_;
};

struct AxisKinds {
  fftw_r2r_kind forward, inverse;
  double normalisation;  ///< inverse(forward(x)) = normalisation · x
};

AxisKinds axis_kinds(int n, PB low, PB high) {
  if (low == PB::periodic) return {FFTW_R2HC, FFTW_HC2R, static_cast<double>(n)};
  if (low == PB::neumann && high == PB::neumann) return {FFTW_REDFT10, FFTW_REDFT01, 2.0 * n};
  if (low == PB::dirichlet && high == PB::dirichlet) return {FFTW_RODFT10, FFTW_RODFT01, 2.0 * n};
  if (low == PB::neumann) return {FFTW_REDFT11, FFTW_REDFT11, 2.0 * n};
  return {FFTW_RODFT11, FFTW_RODFT11, 2.0 * n};
}

std::size_t cells(int nx, int ny) { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }

/// A mode with eigenvalue 0 (the constants, of a singular problem); `scale` is the largest |λ|.
bool is_null_mode(double lambda, double scale) { return std::abs(lambda) <= 1e-12 * scale; }

double largest_magnitude(const std::vector<double>& lambda) {
  double m = 0.0;
  for (double l : lambda) m = std::max(m, std::abs(l));
  return m;
}

}  // namespace

std::vector<double> axis_eigenvalues(int n, double h, PressureBoundary low, PressureBoundary high) {
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

// ---------------------------------------------------------------------------------------------
// Row transforms: modes ← T(b) and p ← T⁻¹(modes) · normalisation, row-major, row j of `modes`
// holding the x modes of row j (or, for the 2D transform, all modes).

class FftPoissonSolver::RowTransform {
 public:
  RowTransform(int nx, int ny) : nx_(nx), ny_(ny), modes_(cells(nx, ny)) {}
  virtual ~RowTransform() = default;
  virtual void forward(std::span<const double> b) = 0;
  virtual void inverse(std::span<double> p) = 0;
  /// inverse(forward(x)) = normalisation · x.
  virtual double normalisation() const = 0;
  double* modes() const { return modes_.data(); }

 protected:
  int nx_, ny_;
  FftwArray<double> modes_;
};

namespace {

/// FFTW r2r kinds in place on the mode array: every row (batched 1D) or the whole grid (2D).
class R2rTransform final : public FftPoissonSolver::RowTransform {
 public:
  enum class Rank { rows, both_axes };
  R2rTransform(const PoissonOperator& op, Rank rank) : RowTransform(op.nx(), op.ny()) {
    const auto& s = op.sides();  // west, east, south, north
    const AxisKinds x = axis_kinds(nx_, s[0], s[1]);
    std::lock_guard<std::recursive_mutex> lock(planner_mutex());
    if (rank == Rank::rows) {
      normalisation_ = x.normalisation;
      auto rows = [&](fftw_r2r_kind kind) {
        return fftw_plan_many_r2r(1, &nx_, ny_, modes(), nullptr, 1, nx_, modes(), nullptr, 1, nx_, &kind, FFTW_ESTIMATE);
      };
      forward_.emplace(rows(x.forward));
      inverse_.emplace(rows(x.inverse));
    } else {
      const AxisKinds y = axis_kinds(ny_, s[2], s[3]);
      normalisation_ = x.normalisation * y.normalisation;
      // Row-major, index j·nx + i: the slow dimension is y.
      forward_.emplace(fftw_plan_r2r_2d(ny_, nx_, modes(), modes(), y.forward, x.forward, FFTW_ESTIMATE));
      inverse_.emplace(fftw_plan_r2r_2d(ny_, nx_, modes(), modes(), y.inverse, x.inverse, FFTW_ESTIMATE));
    }
  }
  void forward(std::span<const double> b) override {
    std::copy(b.begin(), b.end(), modes());
    forward_->execute();
  }
  void inverse(std::span<double> p) override {
    inverse_->execute();
    std::copy(modes(), modes() + p.size(), p.begin());
  }
  double normalisation() const override { return normalisation_; }

 private:
  std::optional<Plan> forward_, inverse_;
  double normalisation_ = 1.0;
};

/// DCT-II of every row (FFTW's REDFT10, X_k = 2 Σ_i x_i cos(πk(i+½)/n)) by a DFT of the same
/// length (Makhoul 1980): with v = (x_0, x_2, x_4, …, x_5, x_3, x_1) and V = DFT(v),
///   X_k = w^k V_k + w^{−k} V_{n−k}  (= 2 Re(w^k V_k) for real x),  w = e^{−iπ/(2n)}.
/// The DCT is real-linear, so two rows a, b go through one complex DFT: Z = DFT(v_a + i v_b)
/// gives Y = X_a + i X_b by the same formula (half the work of two real DFTs).
/// The inverse undoes each step: Z_k = w^{−k} (Y_k − i Y_{n−k}) / 2 (Y_n = 0), v = IDFT(Z),
/// un-reorder; it returns x exactly (normalisation 1: the 1/n of the IDFT is in the twiddle).
/// An odd row count is padded with a zero row (the mode array has the extra row).
class DctRowsByComplexDft final : public FftPoissonSolver::RowTransform {
 public:
  explicit DctRowsByComplexDft(const PoissonOperator& op)
      : RowTransform(op.nx(), op.ny() + op.ny() % 2),
        rows_(op.ny()),
        pairs_(ny_ / 2),
        packed_(cells(nx_, pairs_)),
        transformed_(cells(nx_, pairs_)),
        zeros_(static_cast<std::size_t>(nx_), 0.0),
        discard_(static_cast<std::size_t>(nx_)) {
    for (int k = 0; k < nx_; ++k) {
      const double phi = std::numbers::pi * k / (2.0 * nx_);
      cos_.push_back(std::cos(phi));
      sin_.push_back(std::sin(phi));
      inverse_cos_.push_back(cos_.back() / (2.0 * nx_));
      inverse_sin_.push_back(sin_.back() / (2.0 * nx_));
    }
    std::lock_guard<std::recursive_mutex> lock(planner_mutex());
    auto pair_dfts = [&](int sign) {
      return fftw_plan_many_dft(1, &nx_, pairs_, packed_.data(), nullptr, 1, nx_, transformed_.data(), nullptr, 1, nx_, sign,
                                FFTW_ESTIMATE);
    };
    forward_dft_.emplace(pair_dfts(FFTW_FORWARD));
    inverse_dft_.emplace(pair_dfts(FFTW_BACKWARD));
  }

  void forward(std::span<const double> b) override {
    for (int q = 0; q < pairs_; ++q) pack(b.data() + row(2 * q), has_second(q) ? b.data() + row(2 * q + 1) : zeros_.data(), packed(q));
    forward_dft_->execute();
    for (int q = 0; q < pairs_; ++q) separate_to_dct(transformed(q), modes() + row(2 * q), modes() + row(2 * q + 1));
    if (rows_ % 2 != 0) std::fill(modes() + row(rows_), modes() + row(rows_ + 1), 0.0);  // the padding row
  }

  void inverse(std::span<double> p) override {
    for (int q = 0; q < pairs_; ++q) combine_from_dct(modes() + row(2 * q), modes() + row(2 * q + 1), packed(q));
    inverse_dft_->execute();
    for (int q = 0; q < pairs_; ++q) unpack(transformed(q), p.data() + row(2 * q), has_second(q) ? p.data() + row(2 * q + 1) : discard_.data());
  }

  double normalisation() const override { return 1.0; }

 private:
  std::size_t row(int j) const { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_); }
  bool has_second(int q) const { return 2 * q + 1 < rows_; }
  // DFT input and output of pair q (out of place: FFTW_ESTIMATE's in-place plans copy for n = 60).
  fftw_complex* packed(int q) const { return packed_.data() + row(q); }
  fftw_complex* transformed(int q) const { return transformed_.data() + row(q); }

  /// z_k = v_a,k + i v_b,k with v_k = x_{2k}, v_{n−1−k} = x_{2k+1}: per pair of cells
  /// (x_{2k}, x_{2k+1}) of both rows, z_k = (a_{2k}, b_{2k}) and z_{n−1−k} = (a_{2k+1}, b_{2k+1}).
  void pack(const double* a, const double* b, fftw_complex* z) const {
    using simd::Double2;
    const int n = nx_;
    for (int k = 0; 2 * k + 1 < n; ++k) {
      const Double2 a2 = simd::load2(a + 2 * k), b2 = simd::load2(b + 2 * k);
      simd::store2(z[k], Double2{a2[0], b2[0]});
      simd::store2(z[n - 1 - k], Double2{a2[1], b2[1]});
    }
    if (n % 2 != 0) simd::store2(z[n / 2], Double2{a[n - 1], b[n - 1]});
  }
  void unpack(const fftw_complex* z, double* a, double* b) const {
    using simd::Double2;
    const int n = nx_;
    for (int k = 0; 2 * k + 1 < n; ++k) {
      const Double2 even = simd::load2(z[k]), odd = simd::load2(z[n - 1 - k]);
      simd::store2(a + 2 * k, Double2{even[0], odd[0]});
      simd::store2(b + 2 * k, Double2{even[1], odd[1]});
    }
    if (n % 2 != 0) {
      a[n - 1] = z[n / 2][0];
      b[n - 1] = z[n / 2][1];
    }
  }

  /// Y_k = X_a,k + i X_b,k = w^k A + w^{−k} B with A = Z_k, B = Z_{n−k} (Z_n = Z_0) and
  /// w^k = c − is:  X_a,k = c(A_r + B_r) + s(A_i − B_i),  X_b,k = c(A_i + B_i) − s(A_r − B_r).
  void separate_to_dct(const fftw_complex* Z, double* Xa, double* Xb) const {
    const int n = nx_;
    Xa[0] = 2.0 * Z[0][0];
    Xb[0] = 2.0 * Z[0][1];
    for (int k = 1; k < n; ++k) {
      const double ar = Z[k][0], ai = Z[k][1], br = Z[n - k][0], bi = Z[n - k][1];
      const double c = cos_[static_cast<std::size_t>(k)], s = sin_[static_cast<std::size_t>(k)];
      Xa[k] = c * (ar + br) + s * (ai - bi);
      Xb[k] = c * (ai + bi) - s * (ar - br);
    }
  }
  /// Z_k = w^{−k} (P + iQ) / (2n) with P + iQ = Y_k − i Y_{n−k}: P = X_a,k + X_b,n−k,
  /// Q = X_b,k − X_a,n−k (X_n = 0).
  void combine_from_dct(const double* Xa, const double* Xb, fftw_complex* Z) const {
    const int n = nx_;
    const double scale = 1.0 / (2.0 * n);
    Z[0][0] = Xa[0] * scale;
    Z[0][1] = Xb[0] * scale;
    for (int k = 1; k < n; ++k) {
      const double P = Xa[k] + Xb[n - k], Q = Xb[k] - Xa[n - k];  // before any store to Z
      const double c = inverse_cos_[static_cast<std::size_t>(k)], s = inverse_sin_[static_cast<std::size_t>(k)];
      Z[k][0] = c * P - s * Q;
      Z[k][1] = s * P + c * Q;
    }
  }

  int rows_;   ///< ny (the mode array has ny rounded up to even)
  int pairs_;  ///< complex DFTs: ⌈ny/2⌉
  FftwArray<fftw_complex> packed_, transformed_;
  std::vector<double> cos_, sin_;                  ///< cos φ_k, sin φ_k, φ_k = πk/(2n), k = 0 … n−1
  std::vector<double> inverse_cos_, inverse_sin_;  ///< the same divided by 2n
  std::vector<double> zeros_, discard_;            ///< the missing row of the last pair (odd ny)
  std::optional<Plan> forward_dft_, inverse_dft_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Solves in mode space: modes ← (normalisation · M)⁻¹ modes, M the operator restricted to the
// x modes (tridiagonal along y) or fully diagonal.

class FftPoissonSolver::ColumnSolve {
 public:
  virtual ~ColumnSolve() = default;
  virtual void solve(double* modes) const = 0;
};

namespace {

/// For every x mode k the tridiagonal system along y
///   c (a_j p̂_{j−1} − d_j p̂_j + u_j p̂_{j+1} + λx_k p̂_j) = b̂_j
/// (a, d, u: the y stencil of the five-point operator, cell-centred, its Neumann/Dirichlet ends
/// included; c the transform's normalisation), by the Thomas algorithm. The elimination is done
/// here, once; a solve is forward and back substitution, vectorised across the modes.
/// The null mode of a singular problem (λx_k = 0, Neumann at both y ends; its x mode is the
/// constant): its right-hand side is made compatible by removing its mean over j (that is
/// removing the mean of b), it is pinned by −c/h_y² on its first diagonal entry (one solution of
/// the compatible system) and its solution's mean over j is removed (that is the mean of p).
class ThomasColumns final : public FftPoissonSolver::ColumnSolve {
 public:
  ThomasColumns(const PoissonOperator& op, const std::vector<double>& lambda_x, double c)
      : nx_(op.nx()), ny_(op.ny()), volume_(op.y_axis().volume),
        lower_(static_cast<std::size_t>(ny_)),
        inverse_pivot_(cells(nx_, ny_)),
        upper_ratio_(cells(nx_, ny_)) {
    const StencilAxis& y = op.y_axis();
    const double scale = largest_magnitude(lambda_x) + 4.0 / (op.dy() * op.dy());
    for (int k = 0; k < nx_; ++k) {
      const double lambda = lambda_x[static_cast<std::size_t>(k)];
      const bool pin = op.singular() && is_null_mode(lambda, scale);
      if (pin) null_modes_.push_back(k);
      double previous_ratio = 0.0;  // u_{j−1} / pivot_{j−1}
      for (int j = 0; j < ny_; ++j) {
        const double a = j > 0 ? c * y.lower_weight[static_cast<std::size_t>(j)] : 0.0;
        const double u = j < ny_ - 1 ? c * y.upper_weight[static_cast<std::size_t>(j)] : 0.0;
        double d = c * (lambda - y.diagonal[static_cast<std::size_t>(j)]);
        if (pin && j == 0) d -= c / (op.dy() * op.dy());
        const double pivot = d - a * previous_ratio;
        const std::size_t jk = static_cast<std::size_t>(j) * nx_ + k;
        inverse_pivot_[jk] = 1.0 / pivot;
        upper_ratio_[jk] = u / pivot;
        lower_[static_cast<std::size_t>(j)] = a;
        previous_ratio = upper_ratio_[jk];
      }
    }
  }

  void solve(double* modes) const override {
    for (int k : null_modes_) remove_column_mean(modes, k);
    substitute(modes);
    for (int k : null_modes_) remove_column_mean(modes, k);
  }

 private:
  void substitute(double* modes) const {
    const std::size_t nx = static_cast<std::size_t>(nx_);
    // Forward: y_j = (b̂_j − a_j y_{j−1}) / pivot_j.
    for (std::size_t k = 0; k < nx; ++k) modes[k] *= inverse_pivot_[k];
    for (int j = 1; j < ny_; ++j) {
      double* row = modes + j * nx;
      const double* below = row - nx;
      const double* inverse_pivot = inverse_pivot_.data() + j * nx;
      const double a = lower_[static_cast<std::size_t>(j)];
      for (std::size_t k = 0; k < nx; ++k) row[k] = (row[k] - a * below[k]) * inverse_pivot[k];
    }
    // Back: p̂_j = y_j − (u_j / pivot_j) p̂_{j+1}.
    for (int j = ny_ - 2; j >= 0; --j) {
      double* row = modes + j * nx;
      const double* above = row + nx;
      const double* ratio = upper_ratio_.data() + j * nx;
      for (std::size_t k = 0; k < nx; ++k) row[k] -= ratio[k] * above[k];
    }
  }

  /// The column's mean, volume-weighted along a radial y axis (the compatibility condition and
  /// normalisation of the axisymmetric operator, poisson.hpp).
  void remove_column_mean(double* modes, int k) const {
    double sum = 0.0, total = 0.0;
    if (volume_.empty()) {
      for (int j = 0; j < ny_; ++j) sum += modes[row(j) + k];
      total = ny_;
    } else {
      for (int j = 0; j < ny_; ++j) {
        sum += volume_[static_cast<std::size_t>(j)] * modes[row(j) + k];
        total += volume_[static_cast<std::size_t>(j)];
      }
    }
    const double mean = sum / total;
    for (int j = 0; j < ny_; ++j) modes[row(j) + k] -= mean;
  }
  std::size_t row(int j) const { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_); }

  int nx_, ny_;
  std::vector<double> volume_;                       ///< the y axis' volume weights (empty: uniform)
  std::vector<int> null_modes_;                      ///< pinned x modes (at most one)
  std::vector<double> lower_;                        ///< c · a_j (0 for j = 0)
  std::vector<double> inverse_pivot_, upper_ratio_;  ///< per (j, k), row-major like the modes
};

/// Fully diagonal: p̂ = b̂ / (c (λx_k + λy_m)), 0 for the null mode (the mean-free solution).
/// Optionally the columns (y) are transformed first and back afterwards (a periodic y axis).
class DiagonalModes final : public FftPoissonSolver::ColumnSolve {
 public:
  enum class Columns { already_transformed, transform };
  DiagonalModes(const PoissonOperator& op, double* modes, const std::vector<double>& lambda_x, double c, Columns columns) {
    const int nx = op.nx(), ny = op.ny();
    const auto& s = op.sides();
    if (columns == Columns::transform) {
      const AxisKinds y = axis_kinds(ny, s[2], s[3]);
      c *= y.normalisation;
      std::lock_guard<std::recursive_mutex> lock(planner_mutex());
      auto column_plan = [&](fftw_r2r_kind kind) {
        return fftw_plan_many_r2r(1, &ny, nx, modes, nullptr, nx, 1, modes, nullptr, nx, 1, &kind, FFTW_ESTIMATE);
      };
      forward_.emplace(column_plan(y.forward));
      inverse_.emplace(column_plan(y.inverse));
    }
    const std::vector<double> lambda_y = axis_eigenvalues(ny, op.dy(), s[2], s[3]);
    const double scale = largest_magnitude(lambda_x) + largest_magnitude(lambda_y);
    inverse_eigenvalue_.resize(cells(nx, ny));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double lambda = lambda_x[static_cast<std::size_t>(i)] + lambda_y[static_cast<std::size_t>(j)];
        inverse_eigenvalue_[static_cast<std::size_t>(j) * nx + i] = is_null_mode(lambda, scale) ? 0.0 : 1.0 / (lambda * c);
      }
  }

  void solve(double* modes) const override {
    if (forward_) forward_->execute();
    for (std::size_t k = 0; k < inverse_eigenvalue_.size(); ++k) modes[k] *= inverse_eigenvalue_[k];
    if (inverse_) inverse_->execute();
  }

 private:
  std::optional<Plan> forward_, inverse_;
  std::vector<double> inverse_eigenvalue_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------

FftPoissonSolver::FftPoissonSolver(FftPoissonMethod method) : method_(method) {}
FftPoissonSolver::~FftPoissonSolver() = default;

void FftPoissonSolver::plan(const PoissonOperator& op) {
  if (planned_ && planned_->same_problem(op)) return;
  planned_.reset();
  columns_.reset();
  rows_.reset();
  const auto& s = op.sides();  // west, east, south, north
  const std::vector<double> lambda_x = axis_eigenvalues(op.nx(), op.dx(), s[0], s[1]);
  if (method_ == FftPoissonMethod::r2r_2d) {
    rows_ = std::make_unique<R2rTransform>(op, R2rTransform::Rank::both_axes);
    columns_ = std::make_unique<DiagonalModes>(op, rows_->modes(), lambda_x, rows_->normalisation(),
                                               DiagonalModes::Columns::already_transformed);
  } else {
    const bool dct_by_dft = method_ == FftPoissonMethod::rows_then_tridiagonal && s[0] == PB::neumann && s[1] == PB::neumann;
    if (dct_by_dft)
      rows_ = std::make_unique<DctRowsByComplexDft>(op);
    else
      rows_ = std::make_unique<R2rTransform>(op, R2rTransform::Rank::rows);
    if (s[2] == PB::periodic)
      columns_ = std::make_unique<DiagonalModes>(op, rows_->modes(), lambda_x, rows_->normalisation(),
                                                 DiagonalModes::Columns::transform);
    else
      columns_ = std::make_unique<ThomasColumns>(op, lambda_x, rows_->normalisation());
  }
  planned_ = std::make_unique<PoissonOperator>(op);
}

PressureSolveReport FftPoissonSolver::solve(const PoissonOperator& op, std::span<const double> b,
                                            std::span<double> p) {
  if (op.geometry() == Geometry::axisymmetric) return solve_axisymmetric(op, b, p);
  plan(op);
  // Singular problems: the mean of b and of p live in the null mode alone, which the column
  // solve makes compatible and mean-free (no passes over the grid for them).
  rows_->forward(b);
  columns_->solve(rows_->modes());
  rows_->inverse(p);
  PressureSolveReport report;
  report.iterations = 1;
  report.converged = true;
  return report;
}

// The radial axis has r-dependent coefficients, so it cannot be transformed: the problem is solved
// transposed, z along the rows (transformed) and r along the columns (a tridiagonal solve per z mode,
// the radial operator's own three-point rows).
PressureSolveReport FftPoissonSolver::solve_axisymmetric(const PoissonOperator& op, std::span<const double> b,
                                                         std::span<double> p) {
  if (op.x_axis().volume.empty() || method_ == FftPoissonMethod::r2r_2d)
    throw std::invalid_argument("fft pressure solver: an axisymmetric operator needs its radial axis along x "
                                "and a row-transform method");
  const int nx = op.nx(), ny = op.ny();
  if (!transposed_ || !transposed_source_->same_problem(op)) {
    transposed_ = std::make_unique<PoissonOperator>(op.transposed());
    transposed_source_ = std::make_unique<PoissonOperator>(op);
  }
  b_transposed_.resize(b.size());
  p_transposed_.resize(p.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      b_transposed_[static_cast<std::size_t>(i) * ny + j] = b[static_cast<std::size_t>(j) * nx + i];
  plan(*transposed_);
  rows_->forward(b_transposed_);
  columns_->solve(rows_->modes());
  rows_->inverse(p_transposed_);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      p[static_cast<std::size_t>(j) * nx + i] = p_transposed_[static_cast<std::size_t>(i) * ny + j];
  PressureSolveReport report;
  report.iterations = 1;
  report.converged = true;
  return report;
}

}  // namespace jellysim::fluid
