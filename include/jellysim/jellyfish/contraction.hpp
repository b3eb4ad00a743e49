#pragma once
// Muscle contraction functions (thesis §7.1): a periodic function Q(phase) ∈ [0, 1] (1 relaxed,
// 0 fully contracted) sets each subumbrellar spring's rest length l_r = l_ru (γ + (1 − γ) Q)
// (eq. 7.5). The thesis's final choice is a Hermite-spline curve (eqs. 7.3–7.4); the functions it
// tried first (sine, triangle, short Fourier series, trochoid) are kept as options.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace jellysim::jellyfish {

enum class ContractionShape { hermite, sine, triangle, fourier, trochoid };
std::string_view to_string(ContractionShape s);
std::optional<ContractionShape> contraction_shape_from_string(std::string_view name);
std::vector<std::string> contraction_shape_names();

/// Eq. 7.3: the cubic Hermite interpolant between x_b and x_e with end derivatives v_b, v_e.
double hermite(double s, double x_b, double x_e, double v_b, double v_e);

struct ContractionProfile {
  ContractionShape shape = ContractionShape::hermite;
  double contract_fraction = 0.3;  ///< part of the cycle spent contracting (Fig. 6.10: about a third)
  /// Expansion exponent p ≥ 1 of this spring: the relaxation runs along u^p (u the relaxation's
  /// progress), so a larger p re-expands more slowly at first (springs near the aperture, Fig. 7.5).
  double expansion_exponent = 1.0;
  double trochoid_skew = 0.6;      ///< λ ∈ [0, 1) of the trochoid (Fournier & Reeves): skew of the wave
  /// Part of the cycle the bell rests relaxed after re-expanding, before the next contraction
  /// (Gemmell et al. 2013's pause): the shape runs over the first 1 − pause of the cycle, Q = 1 after.
  double pause_fraction = 0.0;
};

/// Q(phase) ∈ [0, 1] for a phase in cycles (any real number; the function has period 1);
/// Q(0) = 1 (relaxed) and the minimum 0 is the fully contracted state.
double contraction_value(const ContractionProfile& p, double phase);

/// Eq. 7.5: rest length for the uncontracted length l_ru, contraction amount γ and Q.
inline double contracted_rest_length(double uncontracted_m, double gamma, double q) {
  return uncontracted_m * (gamma + (1.0 - gamma) * q);
}

/// The closed-loop rest-length controller of eq. 7.2 for one spring. The goal alternates between
/// γ (contracted) at the end of the contraction phase and 1 (relaxed) at the end of the cycle.
/// Rate form: dl_r/dt = −α l_ru (dγ_c/dt − (γ_g − γ_c)/(t_g − t_c)); the printed Δl_r has the
/// opposite sign, which would lengthen a spring that lags behind a contraction.
struct RestLengthController {
  double alpha = 2.0;            ///< sensitivity α (1/s per unit error)
  double previous_ratio = 1.0;   ///< γ_c at the previous update
  double previous_time = 0.0;
  bool started = false;
  /// Returns the new rest length after advancing from previous_time to t.
  double update(double t, double current_length, double uncontracted_length, double rest_length, double gamma,
                double frequency_hz, double contract_fraction);
};

}  // namespace jellysim::jellyfish
