#pragma once
// Derived fields and integral quantities of a flow on the MAC grid.
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

/// Vorticity ω = ∂v/∂x − ∂u/∂y (1/s) at the cell corners (ghosts of the velocity must be set).
Field vorticity_at_nodes(const Velocity& vel);
/// Stream function ψ (m²/s) at the cell corners, u = ∂ψ/∂y, v = −∂ψ/∂x (the sign of Ghia et al.
/// 1982: a clockwise vortex has ψ < 0). ψ = 0 at the origin corner; integrated exactly for the
/// staggered faces, ψ(i+1, 0) = ψ(i, 0) − v(i, 0)Δx along the bottom row, then
/// ψ(i, j+1) = ψ(i, j) + u(i, j)Δy up each column (u(i, j) is the flux between those corners).
/// For a discretely divergence-free field the path does not matter, and in a closed box
/// (no flow through the walls) ψ = 0 on all four walls. Interior samples only; ghosts are 0.
Field stream_function_at_nodes(const Velocity& vel);
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
