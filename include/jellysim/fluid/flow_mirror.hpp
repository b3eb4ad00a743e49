#pragma once
// Mirror symmetry about the tank's vertical centre line (beyond the thesis). A mirror-symmetric
// scene (one centred jellyfish, walls alike on both sides) has a mirror-symmetric solution, the
// 2D analogue of an axisymmetric jellyfish; round-off seeds an asymmetric part that the planar
// jet's wake amplifies about forty-fold per cycle (docs/jellyfish.md). Keeping only the symmetric
// part after every step is what exact arithmetic would give: the same as solving half the tank
// with a symmetry plane on the axis.
//
// With x̄ = 2c − x the mirror image of x about the centre line x = c, the symmetric part is
//   u(x, y) → ½(u(x, y) − u(x̄, y)),   v(x, y) → ½(v(x, y) + v(x̄, y)),   p likewise with +.
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

/// Replaces velocity and pressure by their mirror-symmetric parts, ghost samples included (the
/// ghosts of symmetric boundary conditions are mirror images of each other already).
void keep_mirror_symmetric_part(FlowState& flow);

/// The east half of a symmetric tank: the same cells, spacing and y sides, x from the centre line
/// to the east side, its west side a free-slip wall (the symmetry plane: u odd, v and p even).
/// nx must be even.
MacGrid east_half(const MacGrid& full);
/// The whole tank's flow from its east half (grid: east_half(full.grid)): the west half is the
/// mirror image. Ghosts are filled for the full tank's sides.
void unfold_east_half(const FlowState& half, FlowState& full, const Boundaries& full_sides);

/// Largest |q − M q| over the velocity samples, M the mirror map above (m/s); 0 for a symmetric flow.
double mirror_asymmetry(const Velocity& velocity);

}  // namespace jellysim::fluid
