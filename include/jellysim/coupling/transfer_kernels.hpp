#pragma once
// Transfer between Lagrangian points and the staggered grid (thesis §4.3.2): interpolation of
// face velocities to points and spreading of point forces onto faces with the same kernel, so the
// two operations are adjoint. Two kernels: the thesis's nearest-four-samples (bilinear) kernel and
// Peskin's regularised 4-point delta function.
#include <optional>
#include <span>
#include <string_view>

#include "jellysim/fluid/grid.hpp"

namespace jellysim::coupling {

enum class Kernel {
  bilinear,  ///< φ(r) = 1 − |r| on |r| < 1: the four nearest samples (thesis §4.3.2)
  peskin4,   ///< Peskin's 4-point regularised delta, support |r| < 2
};

std::string_view to_string(Kernel k);
/// Parses "bilinear" or "peskin4"; nullopt otherwise.
std::optional<Kernel> kernel_from_string(std::string_view name);

/// One-dimensional kernel φ(r), r in sample spacings; Σ_i φ(r − i) = 1 and Σ_i (r − i) φ(r − i) = 0.
double kernel_weight(Kernel k, double r);
/// Half-width of the kernel's support in samples (1 or 2).
int kernel_radius(Kernel k);

/// Which axes of the tank are periodic: along those the kernel wraps around the seam (a point near
/// one side reaches the samples at the other), elsewhere it stops at the ghost layer.
struct Periodicity {
  bool x = false, y = false;
};

/// The samples of one staggered field that a point touches and their weights w = φ(Δi) φ(Δj).
/// Along a periodic axis sample indices wrap with the period (cells along the axis; a face on the
/// seam is stored twice and the first copy is used); elsewhere samples outside the stored range
/// (interior plus one ghost layer) get weight 0.
struct Stencil {
  int i0 = 0, j0 = 0;  ///< first sample index in x and y (before wrapping)
  int width = 0;       ///< 2 (bilinear) or 4 (peskin4) samples per direction
  int period_x = 0, period_y = 0;  ///< > 0: indices wrap modulo this along the axis
  double wx[4] = {0, 0, 0, 0};
  double wy[4] = {0, 0, 0, 0};
  int index_x(int a) const { return wrap(i0 + a, period_x); }
  int index_y(int b) const { return wrap(j0 + b, period_y); }

 private:
  static int wrap(int i, int period) { return period > 0 ? ((i % period) + period) % period : i; }
};
Stencil make_stencil(const fluid::Field& field, Vec2 p, Kernel k, Periodicity periodic = {});

/// Σ w · field over the stencil (the velocity at a point, eq. 4.20's u(x_i)); ghosts must be set.
double interpolate(const fluid::Field& field, const Stencil& s);
/// field += value · w over the stencil (samples inside the stored range only).
void spread(fluid::Field& field, const Stencil& s, double value);

/// Fluid velocity (m/s) at each point (needs filled ghosts).
void interpolate_velocities(const fluid::Velocity& vel, std::span<const Vec2> points, Kernel k, std::span<Vec2> out,
                            Periodicity periodic = {});

/// Adds the accelerations (m/s²) that point forces F_k (N per metre of depth: 2D forces) give the
/// fluid: a(face) += Σ_k F_k w_k(face) / (ρ ΔxΔy) — the force density divided by ρ (eq. 4.19).
void spread_forces(std::span<const Vec2> points, std::span<const Vec2> forces, Kernel k, double density_kg_per_m3,
                   fluid::FaceAccelerations& acc, Periodicity periodic = {});

// ---- Axisymmetric flow (fluid::Geometry::axisymmetric: x = r from the axis, y = z) ----
// Each point is a ring of radius r around the axis. Its force F (N, the whole ring's) spreads as
// the force density F w / (2π r_face Δr Δz) on the faces its kernel covers (w the kernel weight,
// r_face the face's radius), and its velocity is Σ w u_face: the two are adjoint in the
// volume-weighted inner product Σ_faces 2π r Δr Δz a·u (tests/coupling/test_kernels.cpp). Where the
// kernel reaches across the axis, its samples fold onto their mirror images: u_r is odd across the
// axis (face −i ↔ face i, sign −1), u_z even (cell −1 − i ↔ cell i); the axis face itself carries
// u_r = 0 and takes no force.

/// Fluid velocity (m/s) at each ring (needs filled ghosts); `periodic_z`: the z axis wraps.
void interpolate_velocities_axisymmetric(const fluid::Velocity& vel, std::span<const Vec2> points, Kernel k,
                                         std::span<Vec2> out, bool periodic_z = false);
/// Adds the accelerations that ring forces F (N per ring) give the fluid: a(face) += Σ F w /
/// (ρ 2π r_face Δr Δz).
void spread_forces_axisymmetric(std::span<const Vec2> points, std::span<const Vec2> forces, Kernel k,
                                double density_kg_per_m3, fluid::FaceAccelerations& acc, bool periodic_z = false);

}  // namespace jellysim::coupling
