#pragma once
// The discretisations of the convective term the fluid solvers offer (issue 20): the thesis's
// schemes and the second-order ones beside them.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace jellysim::fluid {

/// Convective differences of the Eulerian solver (thesis §4.1 and issue 20).
enum class ConvectionScheme {
  donor_cell,  ///< the thesis's central/donor-cell blend γ (Griebel et al. eq. 3.19): first order where it upwinds
  van_leer,    ///< second-order upwind-biased face values with van Leer's limiter (TVD)
  koren,       ///< third-order upwind-biased (κ = 1/3, QUICK-like) face values with Koren's limiter (TVD)
};
/// Velocity advection of the semi-Lagrangian solver (§4.2 and issue 20).
enum class AdvectionScheme {
  linear,      ///< one back-traced bilinear sample (Stam; the thesis's)
  maccormack,  ///< Selle et al. (2008): forward and reverse traces, error compensation, clamped
  bfecc,       ///< Kim et al. (2005): back-and-forth error compensation, clamped (three traces)
  cubic,       ///< one trace, monotone cubic interpolation (Fedkiw, Stam & Jensen 2001)
};
/// "donor-cell", "van-leer", "koren" / "linear", "maccormack", "bfecc", "cubic" (and the inverse lookups;
/// nullopt for other names).
std::string_view to_string(ConvectionScheme s);
std::string_view to_string(AdvectionScheme s);
std::optional<ConvectionScheme> convection_scheme_from_string(std::string_view name);
std::optional<AdvectionScheme> advection_scheme_from_string(std::string_view name);
const std::vector<std::string>& convection_scheme_names();
const std::vector<std::string>& advection_scheme_names();

}  // namespace jellysim::fluid
