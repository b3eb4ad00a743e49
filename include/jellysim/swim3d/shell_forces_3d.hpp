#pragma once
// The bell as an elastic shell in 3D water (issue 40 part 4, docs/three-d.md): the shell's points
// (its surface's vertices, then its tentacles' nodes) are the immersed boundary's markers, and the
// forces they give the fluid are the shell's: the muscles set for the time (ShellBell::actuate),
// then the elastic forces −∂W/∂x (N). The semi-implicit step's linearisation is K = ∂F/∂X =
// −∂²W/∂x², the negative of the shell's stiffness. The shell's mass does not enter: the markers are
// massless and the body neutrally buoyant (§4.3.2), as in the slice.
#include "jellysim/ib3d/markers_3d.hpp"
#include "jellysim/shell/shell_bell.hpp"

namespace jellysim::swim3d {

class ShellForces3d final : public ib3d::ForceModel3d {
 public:
  /// `bell` is referenced: forces() actuates its muscles for the time asked.
  explicit ShellForces3d(shell::ShellBell& bell) : bell_(&bell) {}
  void forces(double t_s, std::span<const ib3d::Vec3> x, std::span<ib3d::Vec3> f) const override;
  void jacobian_times(double t_s, std::span<const ib3d::Vec3> x, std::span<const ib3d::Vec3> dx,
                      std::span<ib3d::Vec3> df) const override;
  bool stiffness(double t_s, std::span<const ib3d::Vec3> x, Eigen::SparseMatrix<double>& k) const override;

 private:
  shell::ShellBell* bell_;
};

/// The shell's rest points as markers moved by `offset` (m): the bell's aperture centre there.
std::vector<ib3d::Vec3> shell_markers(const shell::ShellBell& bell, const ib3d::Vec3& offset);

}  // namespace jellysim::swim3d
