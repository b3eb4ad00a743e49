#pragma once
// A fast Poisson solver (beyond the thesis, which names faster pressure solvers as future work):
// on a uniform grid the five-point Laplacian of eq. 4.10 with Neumann, Dirichlet or periodic
// sides is diagonalised by discrete cosine, sine or Fourier transforms along each axis. Exact to
// round-off, O(N log N), with no tolerance and no iteration. Transforms by FFTW, planned with
// FFTW_ESTIMATE on fftw_malloc'ed buffers so that every run takes the same code path (deterministic).
//
// Per axis, with the cell-centred unknowns x_j = (j + ½)h, j = 0 … n−1:
//   Neumann–Neumann     cos(πk(j+½)/n)       DCT-II  / DCT-III     θ_k = πk/n
//   Dirichlet–Dirichlet sin(π(k+1)(j+½)/n)   DST-II  / DST-III     θ_k = π(k+1)/n
//   Neumann–Dirichlet   cos(π(k+½)(j+½)/n)   DCT-IV  (self-inverse) θ_k = π(k+½)/n
//   Dirichlet–Neumann   sin(π(k+½)(j+½)/n)   DST-IV  (self-inverse) θ_k = π(k+½)/n
//   periodic            e^{2πikj/n}          real DFT (halfcomplex) θ_k = 2πk/n
// with eigenvalue −(2 − 2cos θ_k)/h² of the 1D operator.
//
// The default method transforms only the rows (x): mode k of every row then obeys the 1D problem
//   (d²/dy² + λx_k) p̂_k = b̂_k
// along y, a tridiagonal system per mode solved by the Thomas algorithm (factored once per operator,
// vectorised across the modes). A periodic y axis is transformed too (real DFT of the columns).
// The Neumann–Neumann DCT-II/III is computed by a DFT of the same length (Makhoul's reordering
// and a twiddle), two rows per complex DFT: much faster than FFTW's REDFT10/REDFT01 for lengths
// such as 60. A singular problem's null mode (constants) is handled in mode space: b's mean is
// removed and p is returned mean-free.
//
// An axisymmetric operator (poisson.hpp) is solved transposed: a transform along z and, per z mode,
// a tridiagonal solve along r with the radial coefficients; its null mode's mean is volume-weighted.
#include <memory>
#include <vector>

#include "jellysim/fluid/poisson.hpp"

namespace jellysim::fluid {

/// How FftPoissonSolver diagonalises the operator. All give the same solution to round-off; the
/// default is the fastest, the others are kept for tests and benchmarks.
enum class FftPoissonMethod {
  /// Row transforms (DCT-II by a complex DFT of two rows where both x sides are Neumann, FFTW
  /// r2r otherwise), then a tridiagonal solve per mode along y (a column transform where y is
  /// periodic).
  rows_then_tridiagonal,
  /// The same with FFTW's r2r kinds along x for every side type.
  r2r_rows_then_tridiagonal,
  /// One 2D FFTW r2r transform each way (fftw_plan_r2r_2d) and a division by λx + λy: the
  /// original method, kept to measure against.
  r2r_2d,
};

class FftPoissonSolver final : public PressureSolver {
 public:
  explicit FftPoissonSolver(FftPoissonMethod method = FftPoissonMethod::rows_then_tridiagonal);
  ~FftPoissonSolver() override;
  FftPoissonSolver(const FftPoissonSolver&) = delete;
  FftPoissonSolver& operator=(const FftPoissonSolver&) = delete;

  std::string_view name() const override { return "fft"; }
  bool uses_initial_guess() const override { return false; }
  PressureSolveReport solve(const PoissonOperator& op, std::span<const double> b, std::span<double> p) override;

  /// Implementation parts (defined in fft_poisson.cpp).
  class RowTransform;
  class ColumnSolve;

 private:
  void plan(const PoissonOperator& op);
  PressureSolveReport solve_axisymmetric(const PoissonOperator& op, std::span<const double> b, std::span<double> p);

  FftPoissonMethod method_;
  std::unique_ptr<PoissonOperator> planned_;
  std::unique_ptr<RowTransform> rows_;
  std::unique_ptr<ColumnSolve> columns_;
  std::unique_ptr<PoissonOperator> transposed_, transposed_source_;  ///< the axisymmetric problem, transposed
  std::vector<double> b_transposed_, p_transposed_;
};

/// The 1D eigenvalues −(2 − 2cos θ_k)/h² of the cell-centred Laplacian with the given sides, in
/// the order of the transform's output (for tests).
std::vector<double> axis_eigenvalues(int n, double h, PressureBoundary low, PressureBoundary high);

}  // namespace jellysim::fluid
