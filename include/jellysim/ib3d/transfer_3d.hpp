#pragma once
// Transfer between the markers and the 3D staggered grid (issue 40, part 2; thesis §4.3.2 in 3D):
// interpolation of face velocities to markers, U = Σ w u, and spreading of marker forces onto the
// faces as accelerations, a += F w / (ρ hx hy hz), with the same weights
// w = φ(Δx/hx) φ(Δy/hy) φ(Δz/hz) — the 1D kernel of the 2D coupling (coupling::kernel_weight,
// Peskin's 4-point function by default) as a tensor product — so that the two are adjoint:
// ρ V Σ_faces a·u = Σ_markers F·U to round-off (V the cell volume).
// Boundaries, axis by axis (fluid3d::Boundaries3d):
//  * periodic: sample indices wrap with the period (faces 0 … n − 1 are the unknowns);
//  * a wall: samples in the padded range (two ghost layers) are kept as they are: interpolation
//    reads the ghosts (the wall's images, filled by the fluid), spreading writes forces there that
//    the fluid does not apply (it updates its unknown faces only) — as the 2D coupling does;
//  * a mirror plane (the quarter tank): a sample beyond the plane is folded onto its mirror image,
//    with sign −1 for the velocity component normal to the plane (which is odd) and +1 for the
//    others (even); the normal component's sample on the plane itself carries nothing (its image
//    cancels it). A marker near a mirror plane so acts with its image: the quarter sees the whole
//    body, and interpolation does not depend on the ghosts.
// Threads: interpolation splits the markers; spreading splits the grid into slabs of z-planes, each
// thread adding, in marker order, the contributions that land in its slab, so every face receives
// the same sums in the same order whatever the thread count (bitwise equal results).
#include <array>
#include <span>
#include <vector>

#include "jellysim/core/parallel.hpp"
#include "jellysim/coupling/transfer_kernels.hpp"
#include "jellysim/fluid3d/boundary_3d.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"
#include "jellysim/ib3d/markers_3d.hpp"

namespace jellysim::ib3d {

/// The samples of one velocity component a marker touches, axis by axis: up to four (index,
/// weight) pairs each, already wrapped or folded; the 3D weight is the product.
struct Stencil3d {
  std::array<int, 3> count{};
  std::array<std::array<int, 4>, 3> index{};
  std::array<std::array<double, 4>, 3> weight{};
};

class Transfer3d {
 public:
  /// `pool` (optional, not owned) runs the threaded loops.
  Transfer3d(const fluid3d::Grid3d& grid, const fluid3d::Boundaries3d& boundaries,
             coupling::Kernel kernel = coupling::Kernel::peskin4, WorkerPool* pool = nullptr);

  const fluid3d::Grid3d& grid() const { return grid_; }
  const fluid3d::Boundaries3d& boundaries() const { return boundaries_; }
  coupling::Kernel kernel() const { return kernel_; }
  /// The samples of component c (0 u, 1 v, 2 w) that a marker at x touches.
  Stencil3d stencil(int c, const Vec3& x) const;

  /// out[m] = Σ w u at marker m (m/s); the velocity's ghosts are read only at walls.
  void interpolate(const fluid3d::Velocity3d& vel, std::span<const Vec3> x, std::span<Vec3> out);
  /// acc += Σ_m F_m w / (ρ V) on every sample the markers touch (m/s²).
  void spread(std::span<const Vec3> x, std::span<const Vec3> force_n, double density_kg_per_m3,
              fluid3d::Velocity3d& acc);

 private:
  /// The 1D samples of component c along axis d for a marker at x (wrapped, folded or kept).
  void axis_samples(int c, int d, double x, Stencil3d& s) const;
  void compute_stencils(std::span<const Vec3> x);
  /// compute_stencils unless the stencils were made for these very positions.
  void ensure_stencils(std::span<const Vec3> x);
  void spread_slab(std::span<const Vec3> force_n, double scale, int k_begin, int k_end, fluid3d::Velocity3d& acc) const;

  fluid3d::Grid3d grid_;
  fluid3d::Boundaries3d boundaries_;
  coupling::Kernel kernel_;
  WorkerPool* pool_;
  std::vector<Stencil3d> stencils_;  ///< 3 per marker (u, v, w), for stencil_positions_
  std::vector<Vec3> stencil_positions_;
};

}  // namespace jellysim::ib3d
