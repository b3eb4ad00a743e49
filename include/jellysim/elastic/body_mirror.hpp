#pragma once
// Mirror symmetry of a spring body about a vertical line x = c (see fluid/flow_mirror.hpp for why).
#include <vector>

#include "jellysim/elastic/body.hpp"

namespace jellysim::elastic {

/// For every point, the index of the point at its mirror image (2c − x, y) within tolerance_m,
/// of the same kind and mass (itself for points on the line); empty if some point has no partner.
std::vector<int> mirror_partners(const Body& body, double axis_x_m, double tolerance_m);

/// True when every spring, beam and dashpot has a mirror image (on the partners' points) in the body:
/// linear and power springs and dashpots with the same parameters; angular springs with the same
/// stiffness and opposite rest angle (or the same one, walked the other way round); torsional beams
/// with curvature −C (or C with the ends swapped); non-invariant beams with curvature (−C_x, C_y)
/// (either end order).
bool springs_mirror_symmetric(const Body& body, const std::vector<int>& partners);

/// Replaces the free points' positions and velocities by the mirror-symmetric part: each pair
/// gets the average of one point and the mirror image of its partner. Pinned and prescribed points
/// are left alone.
void keep_mirror_symmetric_part(Body& body, const std::vector<int>& partners, double axis_x_m);

}  // namespace jellysim::elastic
