#pragma once
// Swimming metrics of a jellyfish slice (thesis §6.4, §8.2.1, Figs 6.10, 8.15–8.18): bell centroid
// along the swimming axis, sub-umbrellar volume as a solid of revolution, aperture area, the
// thrust of eq. 6.4 and Daniel's 1D model (eq. 6.5) driven by the simulated V(t), A(t).
#include <string>
#include <vector>

#include "jellysim/jellyfish/slice_frame.hpp"

namespace jellysim::jellyfish {

/// Shape of the bell at one instant, treated as a body of revolution about its own axis.
struct BellShape {
  Vec2 centroid{};            ///< mean of the umbrella points (m)
  Vec2 axis{0.0, 1.0};        ///< unit vector from the aperture centre to the apex
  double volume_m3 = 0.0;     ///< sub-umbrellar volume: revolved region between bell and aperture plane
  double aperture_area_m2 = 0.0;  ///< π r² with r half the distance between the aperture tips
  double cavity_area_m2 = 0.0;    ///< 2D area enclosed by the umbrella and the aperture chord
};

/// The umbrella runs left tip → apex → right tip with opposing points k and n − 1 − k.
BellShape measure_bell(const std::vector<Vec2>& umbrella);

/// One row of metrics.csv.
struct MetricsRow {
  double t = 0.0;
  double position = 0.0;      ///< centroid displacement along the initial axis (m)
  double lateral = 0.0;       ///< centroid displacement across the initial axis (m)
  double velocity = 0.0;      ///< d position / dt (m/s)
  double acceleration = 0.0;  ///< d velocity / dt (m/s²)
  double volume = 0.0;        ///< m³
  double aperture_area = 0.0; ///< m²
  double volume_ratio = 0.0;  ///< V / V_rest
  double aperture_ratio = 0.0;///< A / A_rest
  double thrust = 0.0;        ///< eq. 6.4 (N), signed: positive while the bell expels water
  double daniel_velocity = 0.0;  ///< u of eq. 6.5 driven by V(t), A(t) (m/s)
  double daniel_position = 0.0;  ///< ∫u dt (m)
};

struct MetricsSettings {
  double density_kg_per_m3 = 1000.0;
  double viscosity_m2_per_s = 1.304e-5;
};

/// Metrics for a series of recorded frames (times increasing). Velocities, accelerations and
/// dV/dt are central differences (one-sided at the ends); the first frame is the rest state.
std::vector<MetricsRow> compute_metrics(const std::vector<SliceFrame>& frames, const MetricsSettings& settings);

/// The first value of `rows` that is not finite, as "the metric 'thrust' is not finite (nan) at
/// t = 0.1 s (frame 3)", or "" when every value is finite: a run whose metrics are not finite
/// diverged even when its state stayed finite (issue 35, item 7).
std::string non_finite_metric(const std::vector<MetricsRow>& rows);

/// Daniel's model (eq. 6.5) in a dimensionally consistent form (docs/jellyfish.md):
///   ρ V (1 + α) du/dt = F_T − ½ ρ C_D A u|u|,  α = (h/r)^1.4 with h/r = (3V/(2A))·√(π/A),
///   C_D = 24 Re^−0.7, Re = 2 r |u| / ν, r = √(A/π).
/// Integrated with RK4 over the frame intervals, V and A linear in between. Returns u per frame.
std::vector<double> daniel_velocity(const std::vector<double>& t, const std::vector<double>& volume,
                                    const std::vector<double>& aperture, const std::vector<double>& thrust,
                                    const MetricsSettings& settings);

/// Number of contraction cycles in [0, t_end] at frequency f.
double cycles(double t_end_s, double frequency_hz);

/// The dominant frequency (Hz) of a uniformly sampled signal, from a discrete Fourier transform
/// of its mean-removed samples (resolution 1/(N Δt)).
double dominant_frequency(const std::vector<double>& values, double sample_interval_s);

}  // namespace jellysim::jellyfish
