#include "jellysim/fluid/direct_poisson.hpp"

#include <stdexcept>

namespace jellysim::fluid {

namespace {

/// The volume weight of cell (i, j): r_i on an axisymmetric operator's radial axis, else 1.
double volume(const PoissonOperator& op, int i, int j) {
  const auto& x = op.x_axis().volume;
  const auto& y = op.y_axis().volume;
  return (x.empty() ? 1.0 : x[static_cast<std::size_t>(i)]) * (y.empty() ? 1.0 : y[static_cast<std::size_t>(j)]);
}

}  // namespace

void DirectPoissonSolver::factor(const PoissonOperator& op) {
  if (factored_ && factored_->same_problem(op)) return;
  const int n = op.size();
  // Columns of ∇² from unit vectors: five-point stencils, so this is cheap and exactly the
  // operator the iterative solvers use (edge coefficients of eq. 4.10 included).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(5 * n));
  std::vector<double> unit(static_cast<std::size_t>(n), 0.0), column(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    unit[static_cast<std::size_t>(k)] = 1.0;
    op.apply(unit, column);
    unit[static_cast<std::size_t>(k)] = 0.0;
    // Only the stencil's rows can be non-zero.
    const int i = k % op.nx(), j = k / op.nx();
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        if (di != 0 && dj != 0) continue;
        const int ii = (i + di + op.nx()) % op.nx(), jj = (j + dj + op.ny()) % op.ny();  // periodic wrap included
        const int r = jj * op.nx() + ii;
        // Rows scaled by the cell's volume weight (1 on a planar operator), which makes the
        // axisymmetric operator symmetric: W(−∇²) is, for the weights r_i (poisson.hpp).
        const double value = -column[static_cast<std::size_t>(r)] * volume(op, ii, jj);
        if (value != 0.0 && r >= k) entries.emplace_back(r, k, value);  // lower triangle
        column[static_cast<std::size_t>(r)] = 0.0;
      }
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  if (op.singular()) a.coeffRef(0, 0) += a.coeff(0, 0);
  cholesky_.compute(a);
  if (cholesky_.info() != Eigen::Success)
    throw std::runtime_error("direct pressure solver: the Poisson matrix could not be factored");
  factored_ = std::make_unique<PoissonOperator>(op);
}

PressureSolveReport DirectPoissonSolver::solve(const PoissonOperator& op, std::span<const double> b,
                                               std::span<double> p) {
  factor(op);
  std::span<const double> rhs = b;
  if (op.singular()) {
    compatible_.assign(b.begin(), b.end());
    op.remove_weighted_mean(compatible_);
    rhs = compatible_;
  }
  const auto n = static_cast<Eigen::Index>(p.size());
  rhs_.resize(n);
  for (Eigen::Index k = 0; k < n; ++k)  // W A p = −W b
    rhs_[k] = -rhs[static_cast<std::size_t>(k)] * volume(op, static_cast<int>(k % op.nx()), static_cast<int>(k / op.nx()));
  solution_ = cholesky_.solve(rhs_);
  for (Eigen::Index k = 0; k < n; ++k) p[static_cast<std::size_t>(k)] = solution_[k];
  if (op.singular()) op.remove_weighted_mean(p);
  PressureSolveReport report;
  report.iterations = 1;
  report.rhs_max = max_abs(rhs);
  report.residual_max = op.residual_max(p, rhs);
  report.converged = true;
  return report;
}

}  // namespace jellysim::fluid
