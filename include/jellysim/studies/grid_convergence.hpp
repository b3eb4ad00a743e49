#pragma once
// Grid convergence of a figure computed on a sequence of grids: the observed order of accuracy,
// Richardson extrapolation and Roache's grid convergence index (GCI), by the procedure of Celik et
// al. (2008, ASME J. Fluids Eng. 130, 078001), which also allows refinement ratios that differ
// between the grid pairs. Pure numerics: it knows nothing of what the figure is.
#include <optional>
#include <span>

namespace jellysim::studies {

struct GridConvergence {
  /// p from the three finest grids; empty with fewer than three grids, when the two finest agree
  /// exactly or the medium and coarse ones do, or when the iteration for p does not settle.
  std::optional<double> observed_order;
  /// f₁ + (f₁ − f₂)/(r₂₁^p − 1), Richardson's estimate of the grid-independent value (with p).
  std::optional<double> extrapolated;
  /// Roache's GCI of the finest grid: F_s |(f₁ − f₂)/f₁| / (r₂₁^p − 1), a relative uncertainty.
  std::optional<double> gci_fine;
  /// |f₁ − f₂| / |f₁| (two grids or more; empty when f₁ = 0).
  std::optional<double> relative_change_finest;
  /// The differences f₁ − f₂ and f₂ − f₃ have opposite signs (oscillatory convergence: p is
  /// then computed from their magnitudes, as Celik et al. do, and is less trustworthy).
  bool oscillatory = false;
};

/// `spacing` holds the grids' representative cell sizes (any unit), coarsest first, each smaller
/// than the one before; `value` the figure on each grid. Uses the last three (the finest).
/// `safety_factor` F_s is Roache's 1.25 for three or more grids. Throws std::invalid_argument for
/// mismatched sizes or spacings that do not decrease.
GridConvergence grid_convergence(std::span<const double> spacing, std::span<const double> value,
                                 double safety_factor = 1.25);

}  // namespace jellysim::studies
