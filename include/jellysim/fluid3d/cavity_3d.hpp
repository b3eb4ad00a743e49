#pragma once
// The 3D lid-driven cavity (issue 40): a box of side 1 m (span `span` along z), the top (high y) wall
// sliding at 1 m/s along +x, ν = 1/Re, run to a steady state. Physics only: the centrelines are
// returned, the caller writes them (bench/cavity_3d_main.cpp).
#include <array>
#include <vector>

#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid3d/fluid_solver_3d.hpp"

namespace jellysim::fluid3d {

struct CavitySettings3d {
  int cells = 32;                 ///< cells along x and y (even)
  double span = 1.0;              ///< depth along z (m); cells along z = round(cells · span), even
  bool periodic_span = false;     ///< periodic along z: the 2D cavity, extruded (a check against Ghia et al.)
  double reynolds = 100.0;        ///< U L / ν with U = L = 1
  double steady_tolerance = 1e-5; ///< stop when max|Δu|/Δt · L/U² falls below this
  double max_time_s = 100.0;
  double safety_factor = 0.9;
  fluid::ConvectionScheme convection = fluid::ConvectionScheme::koren;
  int threads = 1;
};

struct CavityResult3d {
  std::vector<fluid::ProfilePoint> centreline_u;  ///< u(y) on x = ½, z = span/2 (walls included)
  std::vector<fluid::ProfilePoint> centreline_v;  ///< v(x) on y = ½, z = span/2 (walls included)
  double time_s = 0.0;
  long steps = 0;
  double change_rate = 0.0;  ///< the last step's max|Δu|/Δt · L/U²
  bool steady = false;
  double symmetry_error = 0.0;  ///< max |u(x, y, z) − u(x, y, span − z)| (the flow is symmetric about mid-span)
  double max_divergence = 0.0;  ///< 1/s
};

/// Albensoeder, S. & Kuhlmann, H. C. (2005), "Accurate three-dimensional lid-driven cavity flow",
/// J. Comput. Phys. 206, 536–558, Tables 5 and 6: the cube at Re 1000 (Chebyshev collocation), the
/// centrelines through the centre, at Ghia et al.'s positions. Their cube is [−½, ½]³ with the lid
/// at x = −½ sliding along +y; in ours (lid at y = 1 sliding along +x) their v(x) on the line
/// through the centre is our u(y) with y = ½ − x, and their u(y) is our −v(x) with x = y + ½
/// (the same 17 positions as Ghia's 2D tables confirm the mapping). Values as tabulated, taken from
/// the transcription in tum-pbs/PICT, tests/validations.py (commit a95d7f9d), and mapped here.
inline constexpr std::array<fluid::ProfilePoint, 17> kAlbensoederKuhlmannRe1000CentrelineU{{
    {1.0000, 1.00000}, {0.9766, 0.58964}, {0.9688, 0.48443}, {0.9609, 0.39821}, {0.9531, 0.33171},
    {0.8516, 0.12183}, {0.7344, 0.07334}, {0.6172, 0.03905}, {0.5000, 0.00802}, {0.4531, -0.00612},
    {0.2813, -0.10999}, {0.1719, -0.25160}, {0.1016, -0.27293}, {0.0703, -0.23696}, {0.0625, -0.22283},
    {0.0547, -0.20623}, {0.0000, 0.00000},
}};
inline constexpr std::array<fluid::ProfilePoint, 17> kAlbensoederKuhlmannRe1000CentrelineV{{
    {1.0000, 0.00000}, {0.9688, -0.18864}, {0.9609, -0.24095}, {0.9531, -0.29032}, {0.9453, -0.33511},
    {0.9063, -0.43423}, {0.8594, -0.31117}, {0.8047, -0.15223}, {0.5000, 0.03674}, {0.2344, 0.16987},
    {0.2266, 0.17580}, {0.1563, 0.22924}, {0.0938, 0.24407}, {0.0781, 0.23503}, {0.0703, 0.22746},
    {0.0625, 0.21738}, {0.0000, 0.00000},
}};

/// Runs the cavity to steady state (or max_time_s).
CavityResult3d run_lid_driven_cavity_3d(const CavitySettings3d& s);

/// The profile's value at `position` by linear interpolation (positions ascending).
double interpolate_profile(const std::vector<fluid::ProfilePoint>& profile, double position);
/// max |profile − reference| over the reference's points.
double largest_profile_difference(const std::vector<fluid::ProfilePoint>& profile,
                                  std::span<const fluid::ProfilePoint> reference);

}  // namespace jellysim::fluid3d
