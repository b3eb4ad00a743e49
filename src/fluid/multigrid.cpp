#include "fluid/multigrid.hpp"

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

// Averages each block of 2×2 fine residuals into the coarse right-hand side.
void restrict_full_weighting(std::span<const double> fine, int fine_nx, std::span<double> coarse,
                             int coarse_nx, int coarse_ny) {
  for (int J = 0; J < coarse_ny; ++J)
    for (int I = 0; I < coarse_nx; ++I) {
      const std::size_t f = static_cast<std::size_t>(2 * J) * fine_nx + 2 * I;
      coarse[static_cast<std::size_t>(J) * coarse_nx + I] =
          0.25 * (fine[f] + fine[f + 1] + fine[f + fine_nx] + fine[f + fine_nx + 1]);
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

void relax_colour(const PoissonOperator& op, std::span<const double> b, std::span<double> p, int colour) {
  const int nx = op.nx();
  const int ny = op.ny();
  const double cx = 1.0 / (op.dx() * op.dx());
  const double cy = 1.0 / (op.dy() * op.dy());
  const double inv_diag = 1.0 / (2.0 * cx + 2.0 * cy);
  for (int j = 0; j < ny; ++j) {
    const int first = (j + colour) % 2;
    const bool interior_row = j > 0 && j < ny - 1;
    if (!interior_row || nx < 3) {
      for (int i = first; i < nx; i += 2) relax_cell(op, b, p, i, j);
      continue;
    }
    if (first == 0) relax_cell(op, b, p, 0, j);
    double* row = p.data() + static_cast<std::size_t>(j) * nx;
    const double* brow = b.data() + static_cast<std::size_t>(j) * nx;
    for (int i = first == 0 ? 2 : 1; i < nx - 1; i += 2)
      row[i] = (cx * (row[i - 1] + row[i + 1]) + cy * (row[i - nx] + row[i + nx]) - brow[i]) * inv_diag;
    if ((nx - 1 - first) % 2 == 0) relax_cell(op, b, p, nx - 1, j);
  }
}

}  // namespace

void smooth_red_black(const PoissonOperator& op, std::span<const double> b, std::span<double> p, int sweeps) {
  for (int s = 0; s < sweeps; ++s) {
    relax_colour(op, b, p, 0);
    relax_colour(op, b, p, 1);
  }
}

void MultigridSolver::build_levels(const PoissonOperator& op) {
  if (!levels_.empty() && levels_.front().op.same_problem(op)) return;
  levels_.clear();
  PoissonOperator current = op;
  while (true) {
    const std::size_t n = static_cast<std::size_t>(current.size());
    levels_.push_back(Level{current, std::vector<double>(n), std::vector<double>(n), std::vector<double>(n), {}, {}});
    const bool can_coarsen = current.nx() % 2 == 0 && current.ny() % 2 == 0 && current.nx() >= 4 &&
                             current.ny() >= 4 && current.size() > kCoarsestCells;
    if (!can_coarsen) break;
    Level& fine = levels_.back();
    fine.px = make_prolongation_axis(current.nx(), current.sides()[0], current.sides()[1]);
    fine.py = make_prolongation_axis(current.ny(), current.sides()[2], current.sides()[3]);
    current = current.coarsened();
  }
}

void MultigridSolver::v_cycle(std::size_t l) {
  Level& level = levels_[l];
  if (l + 1 == levels_.size()) {
    conjugate_gradient_poisson(level.op, level.b, level.p, 1e-12, 4 * level.op.size() + 50);
    return;
  }
  const int smoothing = std::max(1, settings_.multigrid_smoothing);
  smooth_red_black(level.op, level.b, level.p, smoothing);
  level.op.residual(level.p, level.b, level.r);
  Level& coarse = levels_[l + 1];
  restrict_full_weighting(level.r, level.op.nx(), coarse.b, coarse.op.nx(), coarse.op.ny());
  if (coarse.op.singular()) remove_mean(coarse.b);
  std::fill(coarse.p.begin(), coarse.p.end(), 0.0);
  v_cycle(l + 1);
  prolong_and_add(coarse.p, coarse.op.nx(), level.px, level.py, level.p, level.op.nx(), level.op.ny(), row_);
  smooth_red_black(level.op, level.b, level.p, smoothing);
}

PressureSolveReport MultigridSolver::solve(const PoissonOperator& op, std::span<const double> b,
                                           std::span<double> p) {
  build_levels(op);
  Level& top = levels_.front();
  top.b.assign(b.begin(), b.end());
  if (op.singular()) remove_mean(top.b);
  top.p.assign(p.begin(), p.end());
  PressureSolveReport report;
  report.rhs_max = max_abs(top.b);
  const double target = std::max(settings_.relative_tolerance * report.rhs_max, settings_.absolute_tolerance);
  report.residual_max = op.residual_max(top.p, top.b);
  while (report.residual_max > target && report.iterations < settings_.max_iterations) {
    v_cycle(0);
    ++report.iterations;
    report.residual_max = op.residual_max(top.p, top.b);
  }
  report.converged = report.residual_max <= target;
  if (op.singular()) remove_mean(top.p);
  std::copy(top.p.begin(), top.p.end(), p.begin());
  return report;
}

}  // namespace jellysim::fluid
