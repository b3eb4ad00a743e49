#include "multigrid_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace jellysim::fluid3d {

namespace {

// One grid of the hierarchy: its unknowns, right-hand side and residual (padded, cell-centred).
struct Level {
  Grid3d g;
  Field3d p, rhs, r;
  explicit Level(const Grid3d& grid) : g(grid), p(g.padded_size(), 0.0), rhs(g.padded_size(), 0.0), r(g.padded_size(), 0.0) {}
};

bool can_coarsen(const Grid3d& g) {
  for (int d = 0; d < 3; ++d)
    if (g.n(d) % 2 != 0 || g.n(d) < 4) return false;
  return g.cell_count() > 64;
}

class MultigridPressure3d final : public PressureSolver3d {
 public:
  MultigridPressure3d(const Grid3d& g, const Boundaries3d& b, const PressureSettings3d& s) : b_(b), s_(s) {
    levels_.emplace_back(g);
    while (can_coarsen(levels_.back().g)) {
      const Grid3d& f = levels_.back().g;
      levels_.emplace_back(Grid3d({f.n(0) / 2, f.n(1) / 2, f.n(2) / 2}, {f.size(0), f.size(1), f.size(2)}, f.origin()));
    }
    PressureSettings3d coarse = s;
    coarse.relative_tolerance = 1e-12;
    coarsest_ = make_pressure_solver_3d("cg", levels_.back().g, b, coarse);
  }
  std::string_view name() const override { return "multigrid"; }
  PressureReport3d solve(const Field3d& b, Field3d& p) override;

 private:
  void smooth(Level& l, int sweeps) const;
  void compute_residual(Level& l) const;
  void restrict_residual(const Level& fine, Level& coarse) const;
  void correct_from(const Level& coarse, Level& fine) const;
  void v_cycle(std::size_t level);

  Boundaries3d b_;
  PressureSettings3d s_;
  std::vector<Level> levels_;
  std::unique_ptr<PressureSolver3d> coarsest_;
};

// Red-black Gauss–Seidel on ∇²p = rhs: p = (Σ_d (p₊ + p₋)/h_d² − rhs) / Σ_d 2/h_d², red cells
// (i + j + k even) first.
void MultigridPressure3d::smooth(Level& l, int sweeps) const {
  const Grid3d& g = l.g;
  const double inv[3] = {1.0 / (g.h(0) * g.h(0)), 1.0 / (g.h(1) * g.h(1)), 1.0 / (g.h(2) * g.h(2))};
  const double diagonal = 2.0 * (inv[0] + inv[1] + inv[2]);
  for (int sweep = 0; sweep < 2 * sweeps; ++sweep) {
    apply_pressure_boundaries(g, b_, l.p);
    for (int k = 0; k < g.n(2); ++k)
      for (int j = 0; j < g.n(1); ++j)
        for (int i = (j + k + sweep) % 2; i < g.n(0); i += 2) {
          const std::size_t I = g.index(i, j, k);
          double sum = -l.rhs[I];
          for (int d = 0; d < 3; ++d) sum += (l.p[I + g.stride(d)] + l.p[I - g.stride(d)]) * inv[d];
          l.p[I] = sum / diagonal;
        }
  }
  apply_pressure_boundaries(g, b_, l.p);
}

void MultigridPressure3d::compute_residual(Level& l) const {
  for_each_interior_cell(l.g, [&](std::size_t I, int i, int j, int k) { l.r[I] = l.rhs[I] - centre_laplacian(l.g, l.p, i, j, k); });
}

// The coarse right-hand side: the average of the eight fine residuals of each coarse cell.
void MultigridPressure3d::restrict_residual(const Level& fine, Level& coarse) const {
  for_each_interior_cell(coarse.g, [&](std::size_t I, int i, int j, int k) {
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) sum += fine.r[fine.g.index(2 * i + (c & 1), 2 * j + ((c >> 1) & 1), 2 * k + (c >> 2))];
    coarse.rhs[I] = sum / 8.0;
    coarse.p[I] = 0.0;
  });
}

// fine p += the coarse correction interpolated trilinearly between cell centres (weights ¾, ¼ per
// axis toward the fine cell's side); the coarse ghosts carry the boundaries.
void MultigridPressure3d::correct_from(const Level& coarse, Level& fine) const {
  for_each_interior_cell(fine.g, [&](std::size_t I, int i, int j, int k) {
    const int ci[3] = {i / 2, j / 2, k / 2}, side[3] = {i % 2 == 0 ? -1 : 1, j % 2 == 0 ? -1 : 1, k % 2 == 0 ? -1 : 1};
    double e = 0.0;
    for (int c = 0; c < 8; ++c) {
      const int o[3] = {c & 1, (c >> 1) & 1, c >> 2};
      const double w = (o[0] ? 0.25 : 0.75) * (o[1] ? 0.25 : 0.75) * (o[2] ? 0.25 : 0.75);
      e += w * coarse.p[coarse.g.index(ci[0] + o[0] * side[0], ci[1] + o[1] * side[1], ci[2] + o[2] * side[2])];
    }
    fine.p[I] += e;
  });
}

void MultigridPressure3d::v_cycle(std::size_t level) {
  Level& l = levels_[level];
  if (level + 1 == levels_.size()) {
    coarsest_->solve(l.rhs, l.p);
    return;
  }
  smooth(l, 2);
  compute_residual(l);
  restrict_residual(l, levels_[level + 1]);
  v_cycle(level + 1);
  apply_pressure_boundaries(levels_[level + 1].g, b_, levels_[level + 1].p);
  correct_from(levels_[level + 1], l);
  smooth(l, 2);
}

PressureReport3d MultigridPressure3d::solve(const Field3d& b, Field3d& p) {
  Level& top = levels_.front();
  const double mean = interior_mean(top.g, b);
  double bmax = 0.0;
  for_each_interior_cell(top.g, [&](std::size_t I, int, int, int) {
    top.rhs[I] = b[I] - mean;
    top.p[I] = p[I];
    bmax = std::max(bmax, std::abs(top.rhs[I]));
  });
  PressureReport3d report;
  for (double previous = std::numeric_limits<double>::infinity();; ++report.iterations) {
    apply_pressure_boundaries(top.g, b_, top.p);
    compute_residual(top);
    report.residual_max = 0.0;
    for_each_interior_cell(top.g, [&](std::size_t I, int, int, int) { report.residual_max = std::max(report.residual_max, std::abs(top.r[I])); });
    // Stops at the tolerance, at max_iterations, or where round-off stalls the cycles (a tolerance
    // below what the arithmetic can reach): less than a tenth gained by the last cycle.
    if (report.residual_max <= s_.relative_tolerance * bmax || report.iterations >= s_.max_iterations ||
        report.residual_max > 0.9 * previous)
      break;
    previous = report.residual_max;
    v_cycle(0);
  }
  const double pmean = interior_mean(top.g, top.p);
  for_each_interior_cell(top.g, [&](std::size_t I, int, int, int) { p[I] = top.p[I] - pmean; });
  apply_pressure_boundaries(top.g, b_, p);
  return report;
}

}  // namespace

std::unique_ptr<PressureSolver3d> make_multigrid_pressure_3d(const Grid3d& g, const Boundaries3d& b,
                                                             const PressureSettings3d& settings) {
  return std::make_unique<MultigridPressure3d>(g, b, settings);
}

}  // namespace jellysim::fluid3d
