#pragma once
// Geometric multigrid for the cell-centred pressure equation: V-cycles with red-black
// Gauss–Seidel smoothing, full-weighting (four-cell average) restriction, bilinear prolongation
// and conjugate gradients on the coarsest level. Each V-cycle costs O(N) in the number of cells N
// and reduces the residual by a grid-independent factor, so the whole solve is about linear in N.
// Grids are coarsened while both cell counts are even; odd counts end the hierarchy early. The
// coarsest level is solved directly (dense Cholesky factorisation, computed once per problem) when
// it has at most kDirectCoarsestCells cells, else by CG.
#include <vector>

#include <Eigen/Dense>

#include "jellysim/fluid/poisson.hpp"

namespace jellysim::fluid {

/// Cell-centred bilinear prolongation along one axis: fine cell k takes 3/4 of its own coarse
/// cell and 1/4 of the nearer coarse neighbour (a ghost across a side: ±itself or wrapped).
struct ProlongationAxis {
  std::vector<int> near, far;
  std::vector<double> far_weight;
};

class MultigridSolver final : public PressureSolver {
 public:
  explicit MultigridSolver(const PressureSolverSettings& settings) : settings_(settings) {}
  std::string_view name() const override { return "multigrid"; }
  PressureSolveReport solve(const PoissonOperator& op, std::span<const double> b,
                            std::span<double> p) override;
  /// Number of grid levels used for the last problem.
  int level_count() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {
    PoissonOperator op;
    std::vector<double> p, b;  // coarse levels; the finest uses the caller's arrays
    ProlongationAxis px, py;  // from the next coarser level onto this one
  };
  void build_levels(const PoissonOperator& op);
  void v_cycle(std::size_t level, std::span<double> p, std::span<const double> b);
  void factor_coarsest();
  void solve_coarsest(const Level& level, std::span<double> p, std::span<const double> b);

  PressureSolverSettings settings_;
  Eigen::LLT<Eigen::MatrixXd> coarsest_;  // of −∇² (+ 11ᵀ/n when singular) on the coarsest level
  bool coarsest_direct_ = false;
  Eigen::VectorXd coarse_rhs_, coarse_solution_;
  std::vector<Level> levels_;
  std::vector<double> row_;  // prolongation and restriction scratch
};

/// Largest coarsest level (cells) solved by a dense factorisation rather than CG.
inline constexpr int kDirectCoarsestCells = 1024;

/// Red-black Gauss–Seidel sweeps on ∇²p = b.
void smooth_red_black(const PoissonOperator& op, std::span<const double> b, std::span<double> p, int sweeps);

}  // namespace jellysim::fluid
