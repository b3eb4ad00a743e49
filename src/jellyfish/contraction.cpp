#include "jellysim/jellyfish/contraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace jellysim::jellyfish {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double wrap_phase(double phase) { return phase - std::floor(phase); }

/// The Hermite curve of Fig. 7.3: from relaxed (1) down to contracted (0) over the contraction
/// part with zero end slopes, then back up along u^p with zero end slopes.
double hermite_contraction(const ContractionProfile& p, double s) {
  const double c = p.contract_fraction;
  if (s < c) return hermite(s / c, 1.0, 0.0, 0.0, 0.0);
  const double u = (s - c) / (1.0 - c);
  return hermite(std::pow(u, p.expansion_exponent), 0.0, 1.0, 0.0, 0.0);
}

/// Triangle wave: linear down over the contraction part, linear up over the rest.
double triangle_contraction(const ContractionProfile& p, double s) {
  const double c = p.contract_fraction;
  return s < c ? 1.0 - s / c : (s - c) / (1.0 - c);
}

/// A short Fourier series skewed toward a fast contraction: three harmonics of a sawtooth-like
/// wave, smoothed, shifted so that Q(0) = 1 and normalised to [0, 1] numerically.
double fourier_raw(double s) {
  double sum = 0.0;
  for (int n = 1; n <= 3; ++n) sum += std::cos(kTwoPi * n * s + 0.9 * (n - 1)) / (n * n);
  return sum;
}

struct Range {
  double lo, hi, at_zero;
};

Range fourier_range() {
  static const Range r = [] {
    Range out{INFINITY, -INFINITY, fourier_raw(0.0)};
    for (int k = 0; k < 4096; ++k) {
      const double v = fourier_raw(k / 4096.0);
      out.lo = std::min(out.lo, v);
      out.hi = std::max(out.hi, v);
    }
    return out;
  }();
  return r;
}

double fourier_contraction(double s) {
  // Shift the phase so that the maximum (relaxed) sits at s = 0.
  static const double shift = [] {
    double best = 0.0, best_value = -INFINITY;
    for (int k = 0; k < 4096; ++k) {
      const double v = fourier_raw(k / 4096.0);
      if (v > best_value) {
        best_value = v;
        best = k / 4096.0;
      }
    }
    return best;
  }();
  const Range r = fourier_range();
  return std::clamp((fourier_raw(wrap_phase(s + shift)) - r.lo) / (r.hi - r.lo), 0.0, 1.0);
}

/// Trochoid (Fournier & Reeves' ocean-wave curve): along θ ∈ [0, 2π) the point (θ − λ sin θ, cos θ)
/// traces a skewed wave; solve θ − λ sin θ = 2π s by Newton's method and map cos θ to [0, 1].
double trochoid_contraction(const ContractionProfile& p, double s) {
  const double target = kTwoPi * s;
  const double lambda = p.trochoid_skew;
  double theta = target;
  for (int it = 0; it < 50; ++it) {
    const double f = theta - lambda * std::sin(theta) - target;
    const double step = f / (1.0 - lambda * std::cos(theta));
    theta -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return 0.5 * (1.0 + std::cos(theta));
}

}  // namespace

std::string_view to_string(ContractionShape s) {
  switch (s) {
    case ContractionShape::hermite: return "hermite";
    case ContractionShape::sine: return "sine";
    case ContractionShape::triangle: return "triangle";
    case ContractionShape::fourier: return "fourier";
    case ContractionShape::trochoid: return "trochoid";
  }
  return "hermite";
}

std::vector<std::string> contraction_shape_names() { return {"hermite", "sine", "triangle", "fourier", "trochoid"}; }

std::optional<ContractionShape> contraction_shape_from_string(std::string_view name) {
  for (ContractionShape s : {ContractionShape::hermite, ContractionShape::sine, ContractionShape::triangle,
                             ContractionShape::fourier, ContractionShape::trochoid})
    if (to_string(s) == name) return s;
  return std::nullopt;
}

double hermite(double s, double x_b, double x_e, double v_b, double v_e) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * x_b + (-2 * s3 + 3 * s2) * x_e + (s3 - 2 * s2 + s) * v_b + (s3 - s2) * v_e;
}

/// Q of one cycle's phase s ∈ [0, 1) without a pause.
double active_contraction_value(const ContractionProfile& p, double s) {
  switch (p.shape) {
    case ContractionShape::hermite: return hermite_contraction(p, s);
    case ContractionShape::sine: return 0.5 * (1.0 + std::cos(kTwoPi * s));
    case ContractionShape::triangle: return triangle_contraction(p, s);
    case ContractionShape::fourier: return fourier_contraction(s);
    case ContractionShape::trochoid: return trochoid_contraction(p, s);
  }
  return 1.0;
}

double contraction_value(const ContractionProfile& p, double phase) {
  const double s = wrap_phase(phase);
  if (p.pause_fraction <= 0.0) return active_contraction_value(p, s);
  // The pause (Gemmell et al. 2013): contraction and expansion in the first 1 − pause of the cycle,
  // contract_fraction still a part of the whole cycle; relaxed (Q = 1) for the rest.
  const double active = 1.0 - p.pause_fraction;
  if (s >= active) return 1.0;
  ContractionProfile within = p;
  within.contract_fraction = p.contract_fraction / active;
  return active_contraction_value(within, s / active);
}

double RestLengthController::update(double t, double current_length, double uncontracted_length, double rest_length,
                                    double gamma, double frequency_hz, double contract_fraction) {
  const double ratio = current_length / uncontracted_length;  // γ_c
  if (!started || t <= previous_time) {
    started = true;
    previous_ratio = ratio;
    previous_time = t;
    return rest_length;
  }
  const double dt = t - previous_time;
  const double rate = (ratio - previous_ratio) / dt;  // dγ_c/dt
  // Goal of the current phase: contracted (γ) by the end of the contraction part, relaxed (1) by
  // the end of the cycle.
  const double cycles = t * frequency_hz;
  const double cycle_start = std::floor(cycles);
  const bool contracting = cycles - cycle_start < contract_fraction;
  const double goal = contracting ? gamma : 1.0;
  const double goal_time = (cycle_start + (contracting ? contract_fraction : 1.0)) / frequency_hz;
  const double required_rate = (goal - ratio) / std::max(goal_time - t, 1e-3 / frequency_hz);
  const double new_rest =
      rest_length - alpha * uncontracted_length * (rate - required_rate) * dt;  // eq. 7.2, rate form
  previous_ratio = ratio;
  previous_time = t;
  return std::clamp(new_rest, 0.2 * uncontracted_length, 1.2 * uncontracted_length);
}

}  // namespace jellysim::jellyfish
