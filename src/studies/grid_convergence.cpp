#include "jellysim/studies/grid_convergence.hpp"

#include <cmath>
#include <stdexcept>

namespace jellysim::studies {

namespace {

/// Celik et al. (2008), eqs. 3–4: p = |ln|ε₃₂/ε₂₁| + q(p)| / ln r₂₁ with
/// q(p) = ln((r₂₁^p − s)/(r₃₂^p − s)), s = sign(ε₃₂/ε₂₁), by fixed-point iteration (q = 0 when
/// the two ratios are equal, and p follows at once).
std::optional<double> observed_order(double r21, double r32, double e21, double e32) {
  const double s = (e32 / e21) >= 0 ? 1.0 : -1.0;
  const double log_ratio = std::log(std::abs(e32 / e21));
  double p = std::abs(log_ratio) / std::log(r21);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double num = std::pow(r21, p) - s, den = std::pow(r32, p) - s;
    if (!(num > 0 && den > 0)) return std::nullopt;
    const double next = std::abs(log_ratio + std::log(num / den)) / std::log(r21);
    if (!std::isfinite(next)) return std::nullopt;
    if (std::abs(next - p) <= 1e-12 * std::max(1.0, p)) return next;
    p = next;
  }
  return std::nullopt;
}

}  // namespace

GridConvergence grid_convergence(std::span<const double> spacing, std::span<const double> value, double safety_factor) {
  if (spacing.size() != value.size()) throw std::invalid_argument("grid_convergence: one value per grid");
  for (std::size_t k = 0; k < spacing.size(); ++k) {
    if (!(spacing[k] > 0 && std::isfinite(spacing[k]))) throw std::invalid_argument("grid_convergence: spacings must be positive");
    if (k > 0 && !(spacing[k] < spacing[k - 1]))
      throw std::invalid_argument("grid_convergence: spacings must decrease from the coarsest grid to the finest");
  }
  GridConvergence g;
  const std::size_t n = value.size();
  if (n < 2) return g;
  const double f1 = value[n - 1], f2 = value[n - 2];  // finest, medium
  if (f1 != 0) g.relative_change_finest = std::abs(f1 - f2) / std::abs(f1);
  if (n < 3) return g;
  const double f3 = value[n - 3];
  const double r21 = spacing[n - 2] / spacing[n - 1], r32 = spacing[n - 3] / spacing[n - 2];
  const double e21 = f2 - f1, e32 = f3 - f2;
  if (e21 == 0 || e32 == 0) return g;
  g.oscillatory = (e32 / e21) < 0;
  g.observed_order = observed_order(r21, r32, e21, e32);
  if (!g.observed_order) return g;
  const double rp = std::pow(r21, *g.observed_order);
  if (!(rp > 1)) return g;
  g.extrapolated = (rp * f1 - f2) / (rp - 1.0);
  if (f1 != 0) g.gci_fine = safety_factor * std::abs(e21 / f1) / (rp - 1.0);
  return g;
}

}  // namespace jellysim::studies
