#pragma once
// The Lagrangian side of the 3D immersed boundary (issue 40, part 2; docs/three-d.md): markers
// (positions in m, velocities in m/s, the forces in N they last gave the fluid) and the force laws
// that act on them. A force law gives F(t, X) and, for the semi-implicit step, its Jacobian applied
// to an increment, K(t, X)·ΔX (N per m of displacement); an elastic shell (part 3) plugs in here.
// Vectors are fluid3d::Vec3 (std::array<double, 3>, x y z), the type of the grid they live on.
#include <span>
#include <vector>

#include <Eigen/Sparse>

#include "jellysim/fluid3d/grid_3d.hpp"

namespace jellysim::ib3d {

using fluid3d::Vec3;

struct Markers3d {
  std::vector<Vec3> position;  ///< m
  std::vector<Vec3> velocity;  ///< m/s: the fluid's, interpolated at the end of the last step
  std::vector<Vec3> force;     ///< N: what each marker spread into the fluid in the last step
  explicit Markers3d(std::vector<Vec3> x = {})
      : position(std::move(x)), velocity(position.size(), Vec3{}), force(position.size(), Vec3{}) {}
  std::size_t size() const { return position.size(); }
};

/// The forces on the markers (a body's elasticity, tethers, muscles). Forces are those the body
/// exerts on the fluid through the markers (N), i.e. minus the fluid's force on the body.
class ForceModel3d {
 public:
  virtual ~ForceModel3d() = default;
  /// f = F(t, x) (N), one per marker; f is sized like x.
  virtual void forces(double t_s, std::span<const Vec3> x, std::span<Vec3> f) const = 0;
  /// df = K dx with K = ∂F/∂X at (t, x) (N/m): the semi-implicit step's linearisation.
  virtual void jacobian_times(double t_s, std::span<const Vec3> x, std::span<const Vec3> dx,
                              std::span<Vec3> df) const = 0;
  /// K as a 3N × 3N sparse matrix (unknowns x0 y0 z0 x1 …), for preconditioners that factor
  /// I − Δt² r K; false when the model does not assemble it.
  virtual bool stiffness(double t_s, std::span<const Vec3> x, Eigen::SparseMatrix<double>& k) const;
};

/// Each marker tied to a fixed anchor by a zero-length spring of stiffness k_i (N/m): F_i =
/// k_i (A_i − X_i), K = −k_i I. What holds a rigid body in place (the drag tests) or, with stiff
/// springs, a body on a prescribed path (anchors moved between steps).
class Tethers3d final : public ForceModel3d {
 public:
  Tethers3d(std::vector<Vec3> anchors, std::vector<double> stiffness_n_per_m);
  void forces(double t_s, std::span<const Vec3> x, std::span<Vec3> f) const override;
  void jacobian_times(double t_s, std::span<const Vec3> x, std::span<const Vec3> dx, std::span<Vec3> df) const override;
  bool stiffness(double t_s, std::span<const Vec3> x, Eigen::SparseMatrix<double>& k) const override;
  std::vector<Vec3>& anchors() { return anchors_; }
  const std::vector<Vec3>& anchors() const { return anchors_; }
  const std::vector<double>& stiffness() const { return stiffness_; }

 private:
  std::vector<Vec3> anchors_;
  std::vector<double> stiffness_;
};

/// Linear springs between pairs of markers (rest length L, stiffness k in N/m) plus an optional
/// tether model: a net of springs, the simplest elastic surface (for the preconditioner's
/// measurements; the shell of part 3 replaces it).
class SpringNet3d final : public ForceModel3d {
 public:
  struct Spring {
    int a = 0, b = 0;
    double rest_length_m = 0.0, stiffness_n_per_m = 0.0;
  };
  SpringNet3d(std::vector<Spring> springs, const ForceModel3d* also = nullptr);
  void forces(double t_s, std::span<const Vec3> x, std::span<Vec3> f) const override;
  void jacobian_times(double t_s, std::span<const Vec3> x, std::span<const Vec3> dx, std::span<Vec3> df) const override;
  bool stiffness(double t_s, std::span<const Vec3> x, Eigen::SparseMatrix<double>& k) const override;

 private:
  std::vector<Spring> springs_;
  const ForceModel3d* also_;
};

/// Markers on a sphere (tests, benchmarks, rigid bodies): latitude rings θ_i = (i + ½)π/n_θ, each
/// with a multiple of four markers at φ_j = (j + ½)2π/n_φ about the vertical (y) axis, about
/// `spacing` apart; the set is its own mirror image about the planes x = c_x and z = c_z and has no
/// marker on them, so `quarter_only` (x > c_x, z > c_z) gives what a quarter tank holds.
std::vector<Vec3> sphere_surface_markers(const Vec3& centre, double radius_m, double spacing_m, bool quarter_only);
/// Springs (stiffness k, rest length the present distance) between markers closer than max_distance.
std::vector<SpringNet3d::Spring> neighbour_springs(std::span<const Vec3> x, double max_distance_m, double stiffness_n_per_m);

}  // namespace jellysim::ib3d
