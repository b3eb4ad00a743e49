#pragma once
// Published reference solutions used to validate the fluid solvers.
#include <array>

#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

/// One tabulated point of a centreline profile: position along the line and velocity component.
struct ProfilePoint {
  double position;
  double velocity;
};

/// Ghia, U., Ghia, K. N. & Shin, C. T. (1982), "High-Re solutions for incompressible flow using
/// the Navier–Stokes equations and a multigrid method", J. Comput. Phys. 48(3), 387–411,
/// Table I (u along the vertical line x = 0.5) and Table II (v along the horizontal line y = 0.5),
/// Re = 100, unit square, lid speed 1 moving in +x on the top side.
inline constexpr std::array<ProfilePoint, 17> kGhiaRe100CentrelineU{{
    {1.0000, 1.00000}, {0.9766, 0.84123}, {0.9688, 0.78871}, {0.9609, 0.73722}, {0.9531, 0.68717},
    {0.8516, 0.23151}, {0.7344, 0.00332}, {0.6172, -0.13641}, {0.5000, -0.20581}, {0.4531, -0.21090},
    {0.2813, -0.15662}, {0.1719, -0.10150}, {0.1016, -0.06434}, {0.0703, -0.04775}, {0.0625, -0.04192},
    {0.0547, -0.03717}, {0.0000, 0.00000},
}};
inline constexpr std::array<ProfilePoint, 17> kGhiaRe100CentrelineV{{
    {1.0000, 0.00000}, {0.9688, -0.05906}, {0.9609, -0.07391}, {0.9531, -0.08864}, {0.9453, -0.10313},
    {0.9063, -0.16914}, {0.8594, -0.22445}, {0.8047, -0.24533}, {0.5000, 0.05454}, {0.2344, 0.17527},
    {0.2266, 0.17507}, {0.1563, 0.16077}, {0.0938, 0.12317}, {0.0781, 0.10890}, {0.0703, 0.10091},
    {0.0625, 0.09233}, {0.0000, 0.00000},
}};

/// Taylor–Green vortex on the periodic square [0, 2π]²·(L/2π): u = U sin(kx) cos(ky) e^{−2νk²t},
/// v = −U cos(kx) sin(ky) e^{−2νk²t}, p = ρU²/4 (cos 2kx + cos 2ky) e^{−4νk²t}, k = 2π/L.
struct TaylorGreen {
  double length_m = 6.283185307179586;
  double speed_m_per_s = 1.0;
  double viscosity_m2_per_s = 0.1;

  double wavenumber() const;
  double decay(double t_s) const;
  Vec2 velocity(Vec2 x, double t_s) const;
  double pressure(Vec2 x, double t_s, double density) const;
  /// Samples the exact velocity onto the faces of a grid (discretely divergence-free).
  Velocity sample(const MacGrid& g, double t_s) const;
};

}  // namespace jellysim::fluid
