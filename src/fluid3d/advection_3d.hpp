#pragma once
// Semi-Lagrangian advection of the 3D fluid (private to the module): trilinear sampling of a face
// field at any point, midpoint traces through the velocity, MacCormack's correction (Selle et al.
// 2008) clamped to the range of the samples the backward trace used.
#include <cstddef>

#include "jellysim/fluid3d/boundary_3d.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"

namespace jellysim::fluid3d {

/// The value of component c's field q (ghosts filled) at world point x by trilinear interpolation;
/// x is wrapped across periodic axes and clamped into the box otherwise. lo / hi (when given)
/// receive the smallest and largest of the eight samples used.
double sample_face_field(const Grid3d& g, const Boundaries3d& b, int c, const Field3d& q, Vec3 x,
                         double* lo = nullptr, double* hi = nullptr);
/// The velocity (all three components) at x.
Vec3 sample_velocity(const Grid3d& g, const Boundaries3d& b, const Velocity3d& vel, const Vec3& x);
/// The midpoint (RK2) trace from x over a time dt (negative: backward): x + dt u(x + ½dt u(x)).
Vec3 trace_midpoint(const Grid3d& g, const Boundaries3d& b, const Velocity3d& vel, const Vec3& x, double dt);

}  // namespace jellysim::fluid3d
