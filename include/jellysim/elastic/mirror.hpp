#pragma once
// Mirror symmetry of a spring body about a vertical line x = c (see fluid/mirror.hpp for why).
#include <vector>

#include "jellysim/elastic/body.hpp"

namespace jellysim::elastic {

/// For every point, the index of the point at its mirror image (2c − x, y) within tolerance_m,
/// of the same kind and mass (itself for points on the line); empty if some point has no partner.
std::vector<int> mirror_partners(const Body& body, double axis_x_m, double tolerance_m);

/// True when every linear and angular spring has a mirror-image spring (partners' points) with the
/// same stiffness and rest length, and the same stiffness and opposite rest angle.
bool springs_mirror_symmetric(const Body& body, const std::vector<int>& partners);

/// Replaces the free points' positions and velocities by the mirror-symmetric part: each pair
/// gets the average of one point and the mirror image of its partner. Pinned and prescribed points
/// are left alone.
void keep_mirror_symmetric_part(Body& body, const std::vector<int>& partners, double axis_x_m);

}  // namespace jellysim::elastic
