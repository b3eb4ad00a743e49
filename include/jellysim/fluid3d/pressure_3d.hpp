#pragma once
// Pressure solvers of the 3D fluid: ∇²p = b with the seven-point Laplacian at cell centres,
// Neumann (∂p/∂n = 0) at walls, periodic across periodic axes. Walls and periodic sides only, so
// the problem is singular: b is made compatible by removing its mean and p is returned mean-free.
//  * "fft": exact to round-off. Each axis is diagonalised by its own transform (FFTW r2r, one
//    plan for the 3D array): DCT-II/DCT-III (REDFT10/REDFT01) between walls, the real DFT
//    (R2HC/HC2R) across periodic axes; eigenvalues λ_d(k) = −(4/h_d²) sin²(πk/(2n_d)) (walls) and
//    −(4/h_d²) sin²(πk/n_d) (periodic; k the frequency of a half-complex slot). Plans use
//    FFTW_ESTIMATE, so every run takes the same code path (deterministic bytes). The 2D (x, y)
//    transforms of slabs of z-planes and the z transforms of bands of y-rows are fixed chunks (8 or
//    fewer), run as the pool's tasks when one is given.
//  * "multigrid": geometric multigrid V(2,2) cycles, red-black Gauss–Seidel, eight-cell-average
//    restriction, trilinear cell-centred prolongation, CG on the coarsest grid (reached when a
//    count is odd or below 4, or at ≤ 64 cells); to a relative max-norm residual. For general cases
//    (a later immersed boundary with non-uniform coefficients); serial.
//  * "cg": conjugate gradients on −∇², to a relative max-norm residual (a reference for the tests
//    and the coarsest multigrid level; serial, fixed summation order).
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "jellysim/core/parallel.hpp"
#include "jellysim/fluid3d/boundary_3d.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"

namespace jellysim::fluid3d {

struct PressureReport3d {
  int iterations = 0;           ///< 1 for the exact (FFT) solve
  double residual_max = 0.0;    ///< max|b − ∇²p| (iterative solvers; 0 when not computed)
};

struct PressureSettings3d {
  double relative_tolerance = 1e-10;  ///< iterative solvers: stop when max|r| ≤ tol · max|b|
  int max_iterations = 10000;
};

class PressureSolver3d {
 public:
  virtual ~PressureSolver3d() = default;
  virtual std::string_view name() const = 0;
  /// Solves ∇²p = b on the interior cells. b and p are padded cell-centred fields (only their
  /// interior is read / written, p's ghosts are then filled); b's mean is removed first.
  virtual PressureReport3d solve(const Field3d& b, Field3d& p) = 0;
  /// Whether the solve uses p's value on entry (an initial guess).
  virtual bool uses_initial_guess() const { return true; }
};

/// "fft", "multigrid", "cg".
const std::vector<std::string>& pressure_solver_3d_names();
/// Throws std::invalid_argument for other names. `pool` (optional, kept by the solver) runs the FFT's
/// transforms: fixed chunks of planes and lines as its tasks, the same bits on any thread count.
std::unique_ptr<PressureSolver3d> make_pressure_solver_3d(std::string_view name, const Grid3d& g, const Boundaries3d& b,
                                                          const PressureSettings3d& settings = {},
                                                          WorkerPool* pool = nullptr);

/// The seven-point Laplacian of a cell-centred field p at interior cell (i, j, k); p's ghosts
/// must be filled (apply_pressure_boundaries).
double centre_laplacian(const Grid3d& g, const Field3d& p, int i, int j, int k);
/// The mean of a padded cell-centred field over the interior cells (summed in index order).
double interior_mean(const Grid3d& g, const Field3d& f);

}  // namespace jellysim::fluid3d
