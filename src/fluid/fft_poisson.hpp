#pragma once
// A fast Poisson solver (beyond the thesis, which names faster pressure solvers as future work):
// on a uniform grid the five-point Laplacian of eq. 4.10 with Neumann, Dirichlet or periodic
// sides is diagonalised by discrete cosine, sine or Fourier transforms along each axis. A solve is
// one forward transform, a division by the eigenvalues and one inverse transform: exact to
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
#include <memory>
#include <vector>

#include "fluid/poisson.hpp"

namespace jellysim::fluid {

class FftPoissonSolver final : public PressureSolver {
 public:
  FftPoissonSolver();
  ~FftPoissonSolver() override;
  FftPoissonSolver(const FftPoissonSolver&) = delete;
  FftPoissonSolver& operator=(const FftPoissonSolver&) = delete;

  std::string_view name() const override { return "fft"; }
  PressureSolveReport solve(const PoissonOperator& op, std::span<const double> b, std::span<double> p) override;

 private:
  void plan(const PoissonOperator& op);

  struct Plans;
  std::unique_ptr<Plans> plans_;
  std::unique_ptr<PoissonOperator> planned_;
  std::vector<double> inverse_eigenvalue_;  ///< 1/(λx + λy) per mode, 0 for the null mode
  double normalisation_ = 1.0;
};

/// The 1D eigenvalues −(2 − 2cos θ_k)/h² of the cell-centred Laplacian with the given sides, in
/// the order of the transform's output (for tests).
std::vector<double> axis_eigenvalues(int n, double h, PressureBoundary low, PressureBoundary high);

}  // namespace jellysim::fluid
