#pragma once
// The marker-space form of the semi-implicit coupling (beyond the thesis): the fluid's response to
// marker forces, R = J P S / ρ (spread, project, interpolate), as a dense 2N × 2N "mobility" matrix,
// built from a Green's-function table of the discrete projection instead of 2N projections.
//
// The projection P = I − G L⁻¹ D of a rectangular box whose sides are walls (Neumann pressure),
// outflows (Dirichlet pressure) or periodic equals the projection on a larger periodic domain (a
// torus) of the field extended by its mirror images: per axis, a wall reflects the normal velocity
// component with a minus sign and the tangential one with a plus sign (the pressure is even), an
// outflow the other way round (the pressure is odd); the torus is 2n cells long for two alike
// sides, 4n for one of each, n for a periodic axis. On the torus P is translation invariant, so
// its response to a unit force on one face of each component (two projections, once per grid)
// gives every entry of R as sums of table values: for markers a and b,
//   R_ab = Σ_{f' ∈ J_a} Σ_{f ∈ S_b} Σ_images w_a(f') w_b(f) s T(f' − image(f)) / (ρ Δx Δy),
// where the stencils are exactly those of transfer_kernels.hpp (ghost samples read by the boundary rules of
// fluid/boundary.cpp). With the FFT pressure solver R equals the operator the GMRES iterations
// apply, to round-off.
//
// Kallemov, Bhalla, Griffith & Donev (2016) precondition the rigid-multiblob IB method with a dense
// mobility of the same kind (from an analytic Green's function); this one is the discrete
// projection's own, walls included.
#include <span>
#include <vector>

#include <Eigen/Dense>

#include "jellysim/coupling/transfer_kernels.hpp"
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"

namespace jellysim {
class WorkerPool;
}

namespace jellysim::coupling {

/// A face sample of the box and its weight in a marker's transfer stencil.
struct FaceTerm {
  int i = 0, j = 0;  ///< face index in the box (a real face: interior, on a side, never a ghost)
  double weight = 0.0;
};

/// The terms of one component's stencil: at most 4 × 4 samples (Peskin's kernel), plus the copies
/// an outflow side makes.
struct FaceTerms {
  static constexpr int kCapacity = 32;
  FaceTerm term[kCapacity];
  int count = 0;
  void add(int i, int j, double w) { term[count++] = {i, j, w}; }
  const FaceTerm* begin() const { return term; }
  const FaceTerm* end() const { return term + count; }
};

/// Where the markers meet the fluid: the grid, its sides, the kernel, and whether the west side is
/// a mirror plane (the half tank of a mirror-symmetric scene: samples beyond it, at any depth,
/// read the mirror image, u negated).
struct TransferGeometry {
  fluid::MacGrid grid;
  fluid::Boundaries sides;  ///< the homogeneous sides (no prescribed velocities)
  Kernel kernel = Kernel::bilinear;
  bool west_mirror = false;
};

/// The faces whose values interpolation at p reads, per component (0: u, 1: v), with their
/// weights; ghost samples are replaced by the real faces the boundary rules copy them from.
FaceTerms interpolation_terms(const TransferGeometry& g, Vec2 p, int component);
/// The interior faces that spreading a force at p writes, per component, with their weights
/// (before the division by ρΔxΔy), including the copy an outflow side makes of its first face.
FaceTerms spreading_terms(const TransferGeometry& g, Vec2 p, int component);

/// Velocity at the points by interpolation_terms: the same values as interpolate_velocities (which
/// reads the ghosts), and on a half tank also beyond the mirror side.
void interpolate_velocities(const TransferGeometry& g, const fluid::Velocity& vel, std::span<const Vec2> points,
                            std::span<Vec2> out);

/// Green's-function table of the discrete projection of one box and the dense mobility built on it.
class MobilityMatrix {
 public:
  explicit MobilityMatrix(const TransferGeometry& geometry);
  ~MobilityMatrix();
  MobilityMatrix(const MobilityMatrix&) = delete;
  MobilityMatrix& operator=(const MobilityMatrix&) = delete;

  const TransferGeometry& geometry() const { return geometry_; }
  /// The rows of R for the markers `rows` (all markers when empty): a 2|rows| × 2N matrix, R being
  /// the velocity at the markers per unit force (m/s per N/m), unknowns interleaved x0, y0, x1, …
  /// Rows and columns of masked points (targets) are zero. With a pool the rows are shared among
  /// its threads (each entry is computed alike: the same R whatever the number of threads).
  void assemble(std::span<const Vec2> points, std::span<const char> masked, double density_kg_per_m3,
                std::span<const int> rows, Eigen::MatrixXd& r, WorkerPool* pool = nullptr) const;

  /// Response of the box's projection at face (c_to, i_to, j_to) to a unit value on interior face
  /// (c_from, i_from, j_from) (for tests).
  double response(int c_to, int i_to, int j_to, int c_from, int i_from, int j_from) const;

  /// One marker's transfer for one component, prepared for assemble() (defined in mobility.cpp).
  struct Transfer;

 private:
  /// A source face's images on the torus: (i, j, sign).
  struct Image {
    int i, j;
    double sign;
  };
  void images_of(int component, int i, int j, std::vector<Image>& out) const;
  double table(int c_to, int c_from, int di, int dj) const;
  void prepare(Vec2 p, int component, Transfer& t) const;
  double entry(const Transfer& to, int c_to, const Transfer& from, int c_from) const;

  TransferGeometry geometry_;
  int period_x_ = 0, period_y_ = 0;
  /// T for the four component pairs interleaved (index 4·(j·period_x + i) + 2·to + from), so that
  /// one cache line serves all four: the table is larger than the caches on fine grids.
  std::vector<double> table_;
  mutable std::vector<Transfer> transfer_;  ///< assemble()'s per-marker scratch
};

/// The mobility of rings in axisymmetric water (fluid::Geometry::axisymmetric; the axis is the
/// grid's west side): R = J P S / ρ with ring spreading (transfer_kernels.hpp: the stencil folded across
/// the axis, a force F on face f an acceleration F w / (ρ 2π r_f Δr Δz)). Without translation
/// invariance in r, the table holds per source face column i and component the box's response
/// to a unit value on face (i, 0); along z the box is a torus with the sides' mirror images, as in
/// MobilityMatrix. A column is one axisymmetric projection, made when a marker first spreads
/// onto it. With the FFT pressure solver R equals the fluid's own response (test).
class AxisymmetricMobility {
 public:
  /// geometry.west_mirror must be false (the axis folds the stencils by itself).
  explicit AxisymmetricMobility(const TransferGeometry& geometry);
  ~AxisymmetricMobility();
  AxisymmetricMobility(const AxisymmetricMobility&) = delete;
  AxisymmetricMobility& operator=(const AxisymmetricMobility&) = delete;

  /// R among `points` (rings): 2M × 2M for M points, unknowns interleaved r0, z0, r1, …, in m/s
  /// per N. Column b is scaled by column_scale[b] (empty: 1), e.g. ½ for a point on the axis of a
  /// whole slice, which spreads half its force. Rows and columns of masked points are zero.
  void assemble(std::span<const Vec2> points, std::span<const char> masked, std::span<const double> column_scale,
                double density_kg_per_m3, Eigen::MatrixXd& r) const;
  /// Projections made so far for the table (one per source column and component).
  int columns_built() const { return columns_built_; }

  struct Transfer;  ///< one marker's transfer for one component (mobility.cpp)

 private:
  /// The response table of source column i_from of component c_from: [c_to][i_to][dj].
  const std::vector<double>& column(int c_from, int i_from) const;
  void prepare(Vec2 p, int component, Transfer& t) const;
  double entry(const Transfer& to, int c_to, const Transfer& from, int c_from) const;

  TransferGeometry geometry_;
  int period_z_ = 0;
  mutable std::vector<std::vector<double>> columns_;  ///< [2 · i_from + c_from], empty until needed
  mutable int columns_built_ = 0;
  mutable std::vector<Transfer> transfer_;
};

}  // namespace jellysim::coupling
