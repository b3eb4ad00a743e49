#pragma once
// Each element's energy and forces from its own vertices' positions (docs/three-d.md, "Part 3").
// Private to the shell module; shell_body.cpp sums them and takes their Hessians.
#include <array>
#include <cstddef>

#include "jellysim/shell/shell_body.hpp"

namespace jellysim::shell::detail {

template <std::size_t N>
using Points = std::array<Vec3, N>;

/// Energy (J) of the element and its forces −∂W/∂x_i (N) added to f.
double membrane(const MembraneElement& e, const Points<3>& x, Points<3>& f);
double hinge(const HingeElement& e, const Points<4>& x, Points<4>& f);
/// x = the face's three vertices, then the three across its edges.
double bending_triangle(const BendingTriangle& e, const Points<6>& x, Points<6>& f);
/// θ at the edge x0 → x1 (dihedral_angle) and its gradient with respect to the four points.
double hinge_angle_gradient(const Points<4>& x, Points<4>& gradient);
double fibre(const FibreElement& e, const Points<3>& x, Points<3>& f);
double rod_segment(const RodSegment& e, const Points<2>& x, Points<2>& f);
/// x = {a0, a1, b, c}.
double rod_joint(const RodJoint& e, const Points<4>& x, Points<4>& f);

}  // namespace jellysim::shell::detail
