#pragma once
// Derived fields and integral quantities of a flow on the MAC grid.
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

/// Vorticity ω = ∂v/∂x − ∂u/∂y (1/s) at the cell corners (ghosts of the velocity must be set).
Field vorticity_at_nodes(const Velocity& vel);
/// Vorticity averaged from the four corners onto each cell centre.
Field vorticity_at_centres(const Velocity& vel);
/// |u| (m/s) at the cell centres from face averages.
Field speed_at_centres(const Velocity& vel);
/// Velocity interpolated to the centre of cell (i, j).
Vec2 velocity_at_centre(const Velocity& vel, int i, int j);

/// Σ u ΔxΔy over the distinct faces (m³/s per unit depth): the total momentum / ρ.
Vec2 total_momentum(const Velocity& vel, bool periodic_x, bool periodic_y);
/// ½ Σ |u|² ΔxΔy over the distinct faces (m⁴/s² per unit depth): kinetic energy / ρ.
double kinetic_energy(const Velocity& vel, bool periodic_x, bool periodic_y);

}  // namespace jellysim::fluid
