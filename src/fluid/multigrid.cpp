#include "jellysim/fluid/multigrid.hpp"

#include <stdexcept>

#include <algorithm>
#include <cmath>

namespace jellysim::fluid {
namespace {

constexpr int kCoarsestCells = 64;  // stop coarsening at or below this many cells

ProlongationAxis make_prolongation_axis(int fine_n, PressureBoundary lower, PressureBoundary upper) {
  const int coarse_n = fine_n / 2;
  ProlongationAxis a;
  a.near.resize(fine_n);
  a.far.resize(fine_n);
  a.far_weight.resize(fine_n);
  for (int k = 0; k < fine_n; ++k) {
    const int K = k / 2;
    const bool lower_half = (k % 2) == 0;
    const int other = lower_half ? K - 1 : K + 1;
    const PressureBoundary side = lower_half ? lower : upper;
    a.near[k] = K;
    if (other >= 0 && other < coarse_n) {
      a.far[k] = other;
      a.far_weight[k] = 0.25;
    } else if (side == PressureBoundary::periodic) {
      a.far[k] = (other + coarse_n) % coarse_n;
      a.far_weight[k] = 0.25;
    } else {  // ghost across a side: +value (Neumann) or −value (p = 0 on the side)
      a.far[k] = K;
      a.far_weight[k] = side == PressureBoundary::dirichlet ? -0.25 : 0.25;
    }
  }
  return a;
}

// The fine residual b − ∇²p averaged over each block of 2×2 cells into the coarse right-hand
// side, two fine rows at a time (the fine residual is never stored as a whole).
void restrict_residual(const PoissonOperator& op, std::span<const double> p, std::span<const double> b,
                       std::span<double> coarse, int coarse_nx, int coarse_ny, std::vector<double>& rows) {
  const std::size_t fine_nx = static_cast<std::size_t>(op.nx());
  rows.resize(2 * fine_nx);
  double* r0 = rows.data();
  double* r1 = rows.data() + fine_nx;
  for (int J = 0; J < coarse_ny; ++J) {
    op.residual_row(p, b, 2 * J, r0);
    op.residual_row(p, b, 2 * J + 1, r1);
    double* c = coarse.data() + static_cast<std::size_t>(J) * coarse_nx;
    for (int I = 0; I < coarse_nx; ++I) c[I] = 0.25 * (r0[2 * I] + r0[2 * I + 1] + r1[2 * I] + r1[2 * I + 1]);
  }
}

// Bilinear cell-centred prolongation, first along y into a padded row (with the ghost values of
// the sides at both ends), then along x: fine 2I takes ¾ of coarse I and ¼ of I−1, 2I+1 ¼ of I+1.
void prolong_and_add(std::span<const double> coarse, int coarse_nx, const ProlongationAxis& px,
                     const ProlongationAxis& py, std::span<double> fine, int fine_nx, int fine_ny,
                     std::vector<double>& row) {
  row.resize(static_cast<std::size_t>(coarse_nx) + 2);
  double* t = row.data() + 1;
  const double lower_sign = px.far[0] == px.near[0] ? (px.far_weight[0] < 0.0 ? -1.0 : 1.0) : 0.0;
  const double upper_sign =
      px.far[fine_nx - 1] == px.near[fine_nx - 1] ? (px.far_weight[fine_nx - 1] < 0.0 ? -1.0 : 1.0) : 0.0;
  for (int j = 0; j < fine_ny; ++j) {
    const double* near_row = coarse.data() + static_cast<std::size_t>(py.near[j]) * coarse_nx;
    const double* far_row = coarse.data() + static_cast<std::size_t>(py.far[j]) * coarse_nx;
    const double wy_far = py.far_weight[j];
    for (int I = 0; I < coarse_nx; ++I) t[I] = 0.75 * near_row[I] + wy_far * far_row[I];
    t[-1] = lower_sign != 0.0 ? lower_sign * t[0] : t[coarse_nx - 1];             // periodic: wrap
    t[coarse_nx] = upper_sign != 0.0 ? upper_sign * t[coarse_nx - 1] : t[0];
    double* f = fine.data() + static_cast<std::size_t>(j) * fine_nx;
    for (int I = 0; I < coarse_nx; ++I) {
      f[2 * I] += 0.75 * t[I] + 0.25 * t[I - 1];
      f[2 * I + 1] += 0.75 * t[I] + 0.25 * t[I + 1];
    }
  }
}

// Gauss–Seidel update of one cell with the general (boundary-aware) stencil.
inline void relax_cell(const PoissonOperator& op, std::span<const double> b, std::span<double> p, int i, int j) {
  const double diag = op.diagonal(i, j);
  if (diag == 0.0) return;
  const std::size_t k = static_cast<std::size_t>(j) * op.nx() + i;
  p[k] = (op.neighbour_sum(p, i, j) - b[k]) / diag;
}

// Gauss–Seidel update of the cells of one colour ((i + j + colour) even) in row j.
void relax_row(const PoissonOperator& op, std::span<const double> b, std::span<double> p, int j, int colour,
               double cx, double cy, double inv_diag) {
  const int nx = op.nx();
  const int ny = op.ny();
  const int first = (j + colour) % 2;
  if (!(j > 0 && j < ny - 1) || nx < 3) {
    for (int i = first; i < nx; i += 2) relax_cell(op, b, p, i, j);
    return;
  }
  if (first == 0) relax_cell(op, b, p, 0, j);
  double* row = p.data() + static_cast<std::size_t>(j) * nx;
  const double* below = row - nx;
  const double* above = row + nx;
  const double* brow = b.data() + static_cast<std::size_t>(j) * nx;
  for (int i = first == 0 ? 2 : 1; i < nx - 1; i += 2)
    row[i] = (cx * (row[i - 1] + row[i + 1]) + cy * (below[i] + above[i]) - brow[i]) * inv_diag;
  if ((nx - 1 - first) % 2 == 0) relax_cell(op, b, p, nx - 1, j);
}

}  // namespace

void smooth_red_black(const PoissonOperator& op, std::span<const double> b, std::span<double> p, int sweeps) {
  const int ny = op.ny();
  const double cx = 1.0 / (op.dx() * op.dx());
  const double cy = 1.0 / (op.dy() * op.dy());
  const double inv_diag = 1.0 / (2.0 * cx + 2.0 * cy);
  const bool periodic_y = op.sides()[2] == PressureBoundary::periodic;
  for (int s = 0; s < sweeps; ++s) {
    // Plain order for tiny grids, and for an odd periodic y, where rows ny − 1 and 0 touch with
    // the same colour, so the order inside a colour matters and must stay the plain one.
    if (ny < 3 || (periodic_y && ny % 2 != 0)) {
      for (int colour = 0; colour < 2; ++colour)
        for (int j = 0; j < ny; ++j) relax_row(op, b, p, j, colour, cx, cy, inv_diag);
      continue;
    }
    // Both half-sweeps in one pass over the rows: red row j, then black row j − 1, whose red
    // neighbours (rows j − 2, j − 1, j) are all new by then. A red row only reads black rows that
    // are still old, so this is exactly the red half-sweep followed by the black one. With
    // periodic y, black row 0 reads red row ny − 1 and so comes last.
    relax_row(op, b, p, 0, 0, cx, cy, inv_diag);
    for (int j = 1; j < ny; ++j) {
      relax_row(op, b, p, j, 0, cx, cy, inv_diag);
      if (j > 1 || !periodic_y) relax_row(op, b, p, j - 1, 1, cx, cy, inv_diag);
    }
    relax_row(op, b, p, ny - 1, 1, cx, cy, inv_diag);
    if (periodic_y) relax_row(op, b, p, 0, 1, cx, cy, inv_diag);
  }
}

void MultigridSolver::build_levels(const PoissonOperator& op) {
  if (!levels_.empty() && levels_.front().op.same_problem(op)) return;
  levels_.clear();
  PoissonOperator current = op;
  while (true) {
    const std::size_t n = static_cast<std::size_t>(current.size());
    // The finest level's p is the caller's; its b is used only for singular problems.
    const std::size_t np = levels_.empty() ? 0 : n;
    levels_.push_back(Level{current, std::vector<double>(np), std::vector<double>(n), {}, {}});
    const bool can_coarsen = current.nx() % 2 == 0 && current.ny() % 2 == 0 && current.nx() >= 4 &&
                             current.ny() >= 4 && current.size() > kCoarsestCells;
    if (!can_coarsen) break;
    Level& fine = levels_.back();
    fine.px = make_prolongation_axis(current.nx(), current.sides()[0], current.sides()[1]);
    fine.py = make_prolongation_axis(current.ny(), current.sides()[2], current.sides()[3]);
    current = current.coarsened();
  }
  factor_coarsest();
}

// The coarsest operator as a dense SPD matrix A = −∇² (columns from unit vectors); for the
// singular (pure Neumann or periodic) problem A + 11ᵀ/n, whose solution for a mean-free right-hand
// side is the mean-free solution of A p = c.
void MultigridSolver::factor_coarsest() {
  const PoissonOperator& op = levels_.back().op;
  const int n = op.size();
  coarsest_direct_ = n <= kDirectCoarsestCells;
  if (!coarsest_direct_) return;
  Eigen::MatrixXd a(n, n);
  std::vector<double> unit(static_cast<std::size_t>(n), 0.0), column(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    unit[static_cast<std::size_t>(k)] = 1.0;
    op.apply(unit, column);
    for (int r = 0; r < n; ++r) a(r, k) = -column[static_cast<std::size_t>(r)];
    unit[static_cast<std::size_t>(k)] = 0.0;
  }
  if (op.singular()) a.array() += 1.0 / n;
  coarsest_.compute(a);
  coarsest_direct_ = coarsest_.info() == Eigen::Success;
}

void MultigridSolver::solve_coarsest(const Level& level, std::span<double> p, std::span<const double> b) {
  if (!coarsest_direct_) {
    conjugate_gradient_poisson(level.op, b, p, 1e-12, 4 * level.op.size() + 50);
    return;
  }
  const auto n = static_cast<Eigen::Index>(p.size());
  coarse_rhs_.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) coarse_rhs_[k] = -b[static_cast<std::size_t>(k)];  // A p = −b
  if (level.op.singular()) coarse_rhs_.array() -= coarse_rhs_.mean();
  coarse_solution_ = coarsest_.solve(coarse_rhs_);
  for (Eigen::Index k = 0; k < n; ++k) p[static_cast<std::size_t>(k)] = coarse_solution_[k];
}

void MultigridSolver::v_cycle(std::size_t l, std::span<double> p, std::span<const double> b) {
  Level& level = levels_[l];
  if (l + 1 == levels_.size()) {
    solve_coarsest(level, p, b);
    return;
  }
  const int smoothing = std::max(1, settings_.multigrid_smoothing);
  smooth_red_black(level.op, b, p, smoothing);
  Level& coarse = levels_[l + 1];
  restrict_residual(level.op, p, b, coarse.b, coarse.op.nx(), coarse.op.ny(), row_);
  if (coarse.op.singular()) remove_mean(coarse.b);
  std::fill(coarse.p.begin(), coarse.p.end(), 0.0);
  v_cycle(l + 1, coarse.p, coarse.b);
  prolong_and_add(coarse.p, coarse.op.nx(), level.px, level.py, p, level.op.nx(), level.op.ny(), row_);
  smooth_red_black(level.op, b, p, smoothing);
}

PressureSolveReport MultigridSolver::solve(const PoissonOperator& op, std::span<const double> b,
                                           std::span<double> p) {
  if (op.geometry() != Geometry::planar)
    throw std::invalid_argument("the multigrid pressure solver is planar only; the axisymmetric operator "
                                "needs fft, direct or sor");
  build_levels(op);
  // The finest level works on the caller's p in place, and on b itself unless the problem is
  // singular (then on a copy with the mean removed).
  std::span<const double> rhs = b;
  if (op.singular()) {
    Level& top = levels_.front();
    top.b.assign(b.begin(), b.end());
    remove_mean(top.b);
    rhs = top.b;
  }
  PressureSolveReport report;
  report.rhs_max = max_abs(rhs);
  const double target = std::max(settings_.relative_tolerance * report.rhs_max, settings_.absolute_tolerance);
  report.residual_max = op.residual_max(p, rhs);
  while (report.residual_max > target && report.iterations < settings_.max_iterations) {
    v_cycle(0, p, rhs);
    ++report.iterations;
    report.residual_max = op.residual_max(p, rhs);
  }
  report.converged = report.residual_max <= target;
  if (op.singular()) remove_mean(p);
  return report;
}

}  // namespace jellysim::fluid
