#pragma once
// The pressure Poisson equation ∇²p = b on the cell centres (eq. 3.3), discretised with the
// five-point stencil and the edge coefficients of eq. 4.10: a Neumann side removes the neighbour
// from both the sum and the diagonal, a Dirichlet (p = 0 on the side) side adds 2/h² to the
// diagonal (ghost value −p), a periodic side wraps to the opposite cell. Arrays are row-major,
// index j·nx + i, without ghosts.
//
// Axisymmetric geometry (beyond the thesis; issue 22): x is the radius r, from the axis r = 0 at the
// west side, y the axial coordinate z, and the operator is the Laplacian of a body of revolution,
//   (1/r) ∂/∂r (r ∂p/∂r) + ∂²p/∂z²,
// discretised conservatively: (1/r_i) [r_{i+½} (p_{i+1} − p_i) − r_{i−½} (p_i − p_{i−1})] / Δr²,
// r_i = (i + ½)Δr. The axis face has r = 0 and passes no flux (the symmetry condition). The operator
// is symmetric in the volume-weighted inner product Σ r_i p_i q_i; a singular problem's right-hand
// side is compatible when its volume-weighted mean Σ r_i b_i / Σ r_i vanishes.
#include <array>
#include <memory>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "jellysim/fluid/boundary.hpp"

namespace jellysim::fluid {

/// Stencil data along one axis: for every cell, the index of its lower and upper neighbour
/// (itself when there is none, with weight 0) and the axis' share of the diagonal.
struct StencilAxis {
  std::vector<int> lower, upper;
  std::vector<double> lower_weight, upper_weight, diagonal;  // 1/h² units
  /// A radial axis: every cell's volume weight r_i (m); empty for a Cartesian axis (weight 1).
  std::vector<double> volume;
};

/// Planar (Cartesian x, y) or axisymmetric (x = r from the axis, y = z) flow.
enum class Geometry { planar, axisymmetric };
std::string_view to_string(Geometry g);

class PoissonOperator {
 public:
  PoissonOperator(int nx, int ny, double dx, double dy, std::array<PressureBoundary, 4> sides);
  PoissonOperator(const MacGrid& g, const Boundaries& b)
      : PoissonOperator(g.nx, g.ny, g.dx(), g.dy(), pressure_boundaries(b)) {}
  /// The axisymmetric operator on nr × nz cells of Δr × Δz: the axis is the west side, which must be
  /// Neumann (throws std::invalid_argument otherwise, or for a periodic r axis).
  static PoissonOperator axisymmetric(int nr, int nz, double dr, double dz, std::array<PressureBoundary, 4> sides);
  /// The same cells with the axes exchanged (x ↔ y, sides rotated accordingly), for solvers that
  /// transform along x: p^T solves the transposed problem with b^T.
  PoissonOperator transposed() const;

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double dx() const { return dx_; }
  double dy() const { return dy_; }
  int size() const { return nx_ * ny_; }
  const std::array<PressureBoundary, 4>& sides() const { return sides_; }
  const StencilAxis& x_axis() const { return x_; }
  const StencilAxis& y_axis() const { return y_; }
  Geometry geometry() const { return x_.volume.empty() && y_.volume.empty() ? Geometry::planar : Geometry::axisymmetric; }
  /// Makes a singular problem's right-hand side compatible: subtracts its volume-weighted mean (the
  /// plain mean on a planar operator), which is also how a singular solution is normalised.
  void remove_weighted_mean(std::span<double> values) const;
  /// No Dirichlet side: p is defined up to a constant and b must have zero mean.
  bool singular() const;
  bool same_problem(const PoissonOperator& o) const;

  /// out = ∇²p.
  void apply(std::span<const double> p, std::span<double> out) const;
  /// r = b − ∇²p.
  void residual(std::span<const double> p, std::span<const double> b, std::span<double> r) const;
  double residual_max(std::span<const double> p, std::span<const double> b) const;
  /// Row j of r = b − ∇²p into out[0, nx) (same values as residual()).
  void residual_row(std::span<const double> p, std::span<const double> b, int j, double* out) const;
  /// Sum of neighbour terms of eq. 4.11 at (i, j), i.e. ∇²p + diagonal·p.
  double neighbour_sum(std::span<const double> p, int i, int j) const;
  double diagonal(int i, int j) const { return x_.diagonal[i] + y_.diagonal[j]; }
  /// The same problem at half resolution (nx and ny must be even).
  PoissonOperator coarsened() const;

 private:
  /// Calls visit(k, (∇²p)_k) for every cell k.
  template <class Visit>
  void for_each_laplacian(std::span<const double> p, Visit&& visit) const;

  PoissonOperator(int nx, int ny, double dx, double dy, std::array<PressureBoundary, 4> sides, StencilAxis x,
                  StencilAxis y);
  /// Constant interior coefficients (the fast stencil of the interior rows applies).
  bool uniform() const { return x_.volume.empty() && y_.volume.empty(); }

  int nx_, ny_;
  double dx_, dy_;
  std::array<PressureBoundary, 4> sides_;
  StencilAxis x_, y_;
};

/// Subtracts the mean so that a singular (pure Neumann/periodic) problem has a solution.
void remove_mean(std::span<double> values);
double max_abs(std::span<const double> values);

struct PressureSolverSettings {
  double relative_tolerance = 1e-6;  ///< stop when max|r| ≤ tol · max|b| (max-norm, §4.1.4)
  double absolute_tolerance = 0.0;   ///< or when max|r| ≤ this (units of b, 1/s²)
  int max_iterations = 10000;        ///< sweeps (SOR) or V-cycles (multigrid)
  double sor_omega = 1.7;            ///< relaxation ω of eq. 4.11 (Griebel et al. use 1.7)
  int sor_check_interval = 4;        ///< SOR sweeps between residual evaluations
  int multigrid_smoothing = 2;       ///< red-black Gauss–Seidel sweeps before and after
};

struct PressureSolveReport {
  int iterations = 0;
  double residual_max = 0.0;  ///< max-norm of b − ∇²p at exit (after making b compatible)
  double rhs_max = 0.0;
  bool converged = false;
};

/// Solves ∇²p = b for p (initial guess on entry). Singular problems: b is made compatible by
/// removing its mean, and the returned p has zero mean.
class PressureSolver {
 public:
  virtual ~PressureSolver() = default;
  virtual std::string_view name() const = 0;
  virtual PressureSolveReport solve(const PoissonOperator& op, std::span<const double> b,
                                    std::span<double> p) = 0;
  /// False for exact solvers, which ignore what p holds on entry (no initial guess is prepared).
  virtual bool uses_initial_guess() const { return true; }
};

/// The names make_pressure_solver accepts: "sor", "multigrid", "direct", "fft".
const std::vector<std::string>& pressure_solver_names();
/// "sor", "multigrid", "direct" or "fft"; throws std::invalid_argument for other names.
std::unique_ptr<PressureSolver> make_pressure_solver(std::string_view name,
                                                     const PressureSolverSettings& settings = {});

/// Conjugate gradients on −∇² (symmetric positive (semi-)definite); used for the coarsest
/// multigrid level. Returns the iteration count.
int conjugate_gradient_poisson(const PoissonOperator& op, std::span<const double> b,
                               std::span<double> p, double relative_tolerance, int max_iterations);

}  // namespace jellysim::fluid
