#pragma once
// The 3D lid-driven cavity (issue 40): a box of side 1 m (span `span` along z), the top (high y) wall
// sliding at 1 m/s along +x, ν = 1/Re, run to a steady state. Physics only: the centrelines are
// returned, the caller writes them (bench/cavity_3d_main.cpp).
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

/// Runs the cavity to steady state (or max_time_s).
CavityResult3d run_lid_driven_cavity_3d(const CavitySettings3d& s);

/// The profile's value at `position` by linear interpolation (positions ascending).
double interpolate_profile(const std::vector<fluid::ProfilePoint>& profile, double position);
/// max |profile − reference| over the reference's points.
double largest_profile_difference(const std::vector<fluid::ProfilePoint>& profile,
                                  std::span<const fluid::ProfilePoint> reference);

}  // namespace jellysim::fluid3d
