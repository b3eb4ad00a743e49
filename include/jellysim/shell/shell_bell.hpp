#pragma once
// The jellyfish bell as an elastic shell (issue 40 part 3, docs/three-d.md "Part 3"): the slice's
// subumbrellar profile (jellyfish::bell_profile, the JellyfishSpec's diameter and height) revolved
// into a triangulated surface, with
//  * the slice's continuum material as a shell (shell_material_from_continuum: h = √(12B/S),
//    E = S(1 − ν²)/h, ρh = the line density), membrane and bending as ShellBody builds them;
//  * coronal (ring) muscles: a fibre along the azimuth on every face that does not touch the apex
//    (the slice's muscles run from the aperture to the points next to the apex), tension per unit
//    width per unit strain k_m (the slice's muscle_stiffness: the ring muscle of the axisymmetric
//    bell carries the planar spring's tension k_m·band·strain over its band, i.e. k_m per unit width);
//    and optional radial muscles along the meridian (the slice has none: 0 by default);
//  * the contraction of the slice: each fibre's rest stretch is γ + (1 − γ) Q (eq. 7.5) with the
//    slice's profile, frequency and phase, the expansion exponent running from the aperture's to 1
//    at the apex (Fig. 7.5), and a delay (§6.2) = margin delay + ½ τ s, s the meridional arc
//    fraction from the margin (0) to the apex (1), τ the slice's neural_delay: the slice's delay
//    ½ τ k/m on every meridian. Without a pacemaker the whole margin fires at once (a symmetric
//    stroke, the slice revolved); with one, the impulse runs around the margin from the pacemaker's
//    azimuth at the conduction speed c, margin delay = R |Δφ| / c, so that side fires first. c
//    defaults to L / τ (L the meridian's arc): the speed at which the slice's impulse crosses the bell;
//  * tentacles as rods hanging from margin vertices, continuing the margin's meridian: the slice's
//    tentacles are a curtain around the margin (as in axisymmetric water), so each of n rods carries
//    the curtain's EA = S_t w, EI = B_t w and mass ρ_t w over its share w = 2πR / n of the margin.
// The bell's axis is +y, the aperture centre at the origin, azimuth 0 along +x (the slice's plane
// is z = 0). Fluidless for now: no water, no scene keys.
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/shell/shell_body.hpp"
#include "jellysim/shell/triangle_mesh.hpp"

namespace jellysim::shell {

struct ShellBellSpec {
  /// Shape (diameter_m, height_m, tentacle_length_m), material (ContinuumMaterial) and contraction
  /// (frequency_hz, gamma, profile, aperture_expansion_exponent, neural_delay_s, phase_cycles) of
  /// the slice. thickness_m is the slice's rendering thickness ϑ and does not enter the mechanics.
  jellyfish::JellyfishSpec slice{};
  double target_edge_m = 0.004;            ///< mesh edge length (the meridian's rows are √3/2 of it apart)
  double poisson_ratio = 0.5;              ///< mesoglea: nearly incompressible
  BendingModel bending = BendingModel::midedge;
  double radial_muscle_n_per_m = 0.0;      ///< radial muscle layer, tension per unit width per unit strain
  bool pacemaker = false;                  ///< false: the margin fires at once (symmetric stroke)
  double pacemaker_azimuth_rad = 0.0;      ///< where on the margin the impulse starts
  double conduction_speed_m_per_s = 0.0;   ///< around the margin; 0: L / neural_delay (∞ without a delay)
  int tentacle_count = 12;                 ///< rods around the margin (0: none)
};

/// Throws std::invalid_argument naming the field when out of range (and validates the slice).
void validate(const ShellBellSpec& spec);

class ShellBell {
 public:
  explicit ShellBell(const ShellBellSpec& spec);

  const ShellBellSpec& spec() const { return spec_; }
  const ShellMaterial& material() const { return material_; }
  ShellBody& body() { return body_; }
  const ShellBody& body() const { return body_; }
  /// The bell's surface (its vertices come first in the body) and its rings (apex, then ring by
  /// ring to the margin).
  const RevolvedMesh& surface() const { return surface_; }
  /// Rest positions of every point: the surface's vertices, then the tentacles' nodes.
  const Vector& rest_positions() const { return rest_; }
  /// Each tentacle's points from its root on the margin outward.
  const std::vector<std::vector<int>>& tentacles() const { return tentacles_; }
  /// Indices into body().fibres of the coronal and the radial muscles.
  const std::vector<std::size_t>& coronal_fibres() const { return coronal_; }
  const std::vector<std::size_t>& radial_fibres() const { return radial_; }
  double conduction_speed_m_per_s() const { return conduction_speed_; }
  /// The meridian's arc from the margin to the apex (m).
  double meridian_arc_m() const { return meridian_arc_; }

  /// Sets every muscle fibre's rest stretch for time t (eq. 7.5 with its profile and delay).
  void actuate(double t);
  /// Q ∈ [0, 1] of fibre k at time t (1 relaxed).
  double activation(std::size_t fibre, double t) const;
  /// The delay (s) with which fibre k follows the pacemaker.
  double delay_s(std::size_t fibre) const { return delay_[fibre]; }

  /// The cavity's volume at positions x: the surface closed by its aperture (m³).
  double cavity_volume(const Vector& x) const;

 private:
  void build_muscles();
  void add_muscle(std::size_t face, const Vec3& direction, double stiffness, std::vector<std::size_t>& into);
  void build_tentacles();
  double margin_delay_s(double azimuth) const;

  ShellBellSpec spec_;
  ShellMaterial material_;
  RevolvedMesh surface_;
  ShellBody body_;
  Vector rest_;
  std::vector<double> arc_fraction_;   ///< per surface vertex: 0 at the margin, 1 at the apex
  std::vector<std::size_t> coronal_, radial_;
  std::vector<jellyfish::ContractionProfile> profile_;  ///< per fibre
  std::vector<double> delay_;                           ///< per fibre
  std::vector<std::vector<int>> tentacles_;
  double conduction_speed_ = 0.0;
  double meridian_arc_ = 0.0;
};

/// Radial distance from the bell's axis (the y axis) of point i.
inline double axial_radius(const Vector& x, int i) { return std::hypot(x(3 * i), x(3 * i + 2)); }

/// The mean radial displacement (m, outward positive) at positions x of the margin's vertices
/// within `half_width_rad` of azimuth φ: how far that side of the margin has moved in or out.
double margin_displacement(const ShellBell& bell, const Vector& x, double azimuth_rad,
                           double half_width_rad = std::numbers::pi / 6);

}  // namespace jellysim::shell
