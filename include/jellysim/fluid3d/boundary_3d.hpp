#pragma once
// Boundary conditions of the 3D fluid: each axis is periodic or closed by two solid walls. A wall
// is no-slip and may slide in its own plane (a lid): the normal velocity on it is zero, the
// tangential components take the wall's velocity through ghosts mirrored about it,
// q_ghost = 2 U_wall − q_inside (the 2D solver's no-slip row, docs/fluids.md). A side may instead be
// a mirror plane (`symmetry`, free-slip): zero normal velocity, tangential ghosts copied,
// q_ghost = q_inside, so a flow symmetric about that plane is computed on one half (the quarter
// tank of issue 40: planes at low x and low z through the bell's axis). The pressure is Neumann
// (∂p/∂n = 0) at walls and mirror planes and periodic across periodic axes.
#include <array>
#include <span>
#include <string>

#include "jellysim/fluid3d/grid_3d.hpp"

namespace jellysim::fluid3d {

struct AxisBoundary3d {
  bool periodic = false;
  /// The velocity (m/s) of the low (index 0) and high wall of this axis; only its tangential
  /// components may be non-zero (checked by validate).
  std::array<Vec3, 2> wall_velocity{};
  /// The low / high side is a mirror plane (free-slip) instead of a no-slip wall; its velocity must be 0.
  std::array<bool, 2> symmetry{};
};

struct Boundaries3d {
  std::array<AxisBoundary3d, 3> axis{};

  /// A closed box: walls at rest on all six sides.
  static Boundaries3d closed_box();
  /// Periodic along every axis (Taylor–Green, Beltrami flows).
  static Boundaries3d periodic_box();
  /// Walls on the four sides parallel to `flow_axis`, periodic along it (a duct).
  static Boundaries3d duct(int flow_axis);
  /// A closed box whose top (high y) wall slides with speed U (m/s) along +x: the lid-driven cavity.
  static Boundaries3d lid_driven_cavity(double lid_speed_m_per_s);

  /// The same box with mirror planes at the low x and low z sides: the quarter of a tank whose flow
  /// is symmetric about the planes x = 0 and z = 0 of the quarter (the vertical axis).
  Boundaries3d quarter() const;

  /// Throws std::invalid_argument if a wall has a normal velocity or a mirror plane a velocity, or
  /// if a periodic axis has a mirror plane.
  void validate() const;
  /// The largest |velocity component| a wall prescribes along axis c (for the time-step limit).
  double largest_wall_speed(int c) const;
};

/// Sets the boundary faces and fills both ghost layers of velocity component c (0, 1, 2) along
/// every axis, from its interior values (x first, then y, then z, over the whole padded range, so
/// edge and corner ghosts are consistent too).
void apply_velocity_boundaries(const Grid3d& g, const Boundaries3d& b, int c, Field3d& q);
/// All three components.
void apply_velocity_boundaries(const Grid3d& g, const Boundaries3d& b, Velocity3d& vel);
/// The pressure's (cell-centred) ghosts: wrapped across periodic axes, copied at walls (Neumann).
void apply_pressure_boundaries(const Grid3d& g, const Boundaries3d& b, Field3d& p);

/// The index range [begin, end) of the faces of component c along axis d that the solver updates:
/// along its own axis [1, n) between walls and [0, n) when periodic; along the others [0, n).
std::array<int, 2> unknown_range(const Grid3d& g, const Boundaries3d& b, int c, int d);

}  // namespace jellysim::fluid3d
