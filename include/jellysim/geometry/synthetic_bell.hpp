#pragma once
// A synthetic, analytically shaped jellyfish slice for developing and testing the rendering
// pipeline without the simulation: a symmetric hemi-ellipse bell that contracts toward a cone.
#include <vector>

#include "jellysim/geometry/surface_geometry.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::geometry {

struct SyntheticBell {
  double diameter_m = 0.04;          ///< aperture diameter when expanded (Fig. 8.21: 4 cm)
  double height_m = 0.028;           ///< apex height above the aperture when expanded (2.8 cm)
  double contraction = 0.0;          ///< 0 expanded … 1 fully contracted
  double max_contraction = 0.56;     ///< γ: radius ratio at the aperture when fully contracted (§7.1)
  int umbrella_points = 21;          ///< odd ≥ 5
  int tentacle_points = 8;           ///< per tentacle (0: no tentacles, else ≥ 2)
  double tentacle_length_m = 0.014;  ///< Fig. 8.21: 1.4 cm
  double thickness_m = 0.0015;       ///< ϑ; §7.2: 5.4 % of the height
  double time_s = 0.0;
  Vec2 aperture_centre_m{0.0, 0.0};  ///< where the aperture chord's midpoint lies
};

/// Subumbrellar points on x = R' sin θ, y = H' cos θ for θ uniform in [−π/2, π/2] (left tip, apex,
/// right tip), with the radius shrunk toward the aperture by contraction·(1 − γ)·|sin θ| and the
/// height raised by 20 % at full contraction; one muscle per opposing pair (rest length = the
/// expanded pair distance); two tentacles hanging from the tips, swept inward as it contracts.
/// Throws InputError for out-of-range fields.
jellyfish::SliceFrame synthetic_bell(const SyntheticBell& spec);

/// Shorthand for the common fields.
jellyfish::SliceFrame synthetic_bell(double diameter_m, double height_m, double contraction, int umbrella_points,
                                     int tentacle_points);

/// The synthetic bell as a simulated 3D bell would record it (surface_geometry.hpp), for tests and
/// development of the surface path: one frame per spec, its slice's right half (apex to margin: the
/// subumbrella's meridian) revolved about the axis through the aperture centre, `ring_points`
/// vertices per ring at σ_j = 2πj / ring_points (x = c + r (cos σ ê − sin σ ẑ), the extrapolation's
/// eq. 7.12) and one at the apex; `strands` copies of the right tentacle at even azimuths from 0.
/// The triangles' normals point out of the cavity. ϑ is the first spec's thickness.
SurfaceFrames revolved_synthetic_bell(const std::vector<SyntheticBell>& frames, int ring_points, int strands);

}  // namespace jellysim::geometry
