// The bell as an elastic shell in 3D water (issue 40 part 4, first piece): the shell's forces as
// the immersed boundary's force model, and one contraction of the symmetric bell in a periodic box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "jellysim/ib3d/immersed_boundary_3d.hpp"
#include "jellysim/swim3d/shell_forces_3d.hpp"

namespace jellysim::swim3d {
namespace {

using ib3d::Vec3;

shell::ShellBellSpec coarse_bell(double edge_m) {
  shell::ShellBellSpec spec;
  spec.target_edge_m = edge_m;
  spec.tentacle_count = 6;
  return spec;
}

// The adapter's forces are the shell's −∂W/∂x, internal (they sum to zero: no net force on the
// water), and its Jacobian is their derivative: central differences of the forces agree with
// jacobian_times, and the assembled stiffness with the product, on a contracted, deformed bell.
TEST(ShellForces3d, AreTheShellsInternalForcesWithTheirDerivative) {
  shell::ShellBell bell(coarse_bell(0.006));
  ShellForces3d model(bell);
  std::vector<Vec3> x = shell_markers(bell, {0.0, 0.0, 0.0});
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (Vec3& p : x)
    for (double& c : p) c += 2e-4 * n(rng);
  std::vector<Vec3> f(x.size()), dx(x.size()), kdx(x.size()), plus(x.size()), minus(x.size());
  const double t = 0.3;  // in the contraction
  model.forces(t, x, f);
  Vec3 sum{};
  double largest = 0.0;
  for (const Vec3& fi : f)
    for (std::size_t c = 0; c < 3; ++c) sum[c] += fi[c], largest = std::max(largest, std::abs(fi[c]));
  EXPECT_GT(largest, 0.0);
  const double net = std::hypot(sum[0], sum[1], sum[2]);
  std::printf("  largest force %.3e N, |net force| %.1e of it\n", largest, net / largest);
  EXPECT_LT(net, 1e-14 * largest);  // measured 1.5e-15
  for (Vec3& d : dx)
    for (double& c : d) c = n(rng);
  const double eps = 1e-8;
  std::vector<Vec3> xp = x, xm = x;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) xp[i][c] += eps * dx[i][c], xm[i][c] -= eps * dx[i][c];
  model.forces(t, xp, plus);
  model.forces(t, xm, minus);
  model.jacobian_times(t, x, dx, kdx);
  Eigen::SparseMatrix<double> k;
  ASSERT_TRUE(model.stiffness(t, x, k));
  Eigen::VectorXd d(3 * static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) d(static_cast<Eigen::Index>(3 * i + c)) = dx[i][c];
  const Eigen::VectorXd kd = k * d;
  double scale = 0.0, fd_error = 0.0, matrix_error = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      const double fd = (plus[i][c] - minus[i][c]) / (2 * eps);
      scale = std::max(scale, std::abs(kdx[i][c]));
      fd_error = std::max(fd_error, std::abs(fd - kdx[i][c]));
      matrix_error = std::max(matrix_error, std::abs(kd(static_cast<Eigen::Index>(3 * i + c)) - kdx[i][c]));
    }
  std::printf("  max|K dx| %.3e N/m; central differences off by %.1e, the matrix by %.1e (relative)\n", scale,
              fd_error / scale, matrix_error / scale);
  EXPECT_LT(fd_error, 2e-9 * scale);  // measured 4.6e-10
  EXPECT_LT(matrix_error, 2e-9 * scale);  // measured 4.6e-10: both are central differences of the forces
}

/// The fluid's momentum Σ ρ u V over every face of a periodic box (kg m/s).
Vec3 momentum(const fluid3d::FluidSolver3d& f) {
  const fluid3d::Grid3d& g = f.state().grid;
  Vec3 p{};
  for (std::size_t c = 0; c < 3; ++c)
    fluid3d::for_each_interior_cell(g, [&](std::size_t I, int, int, int) { p[c] += f.state().velocity.c[c][I]; });
  for (double& q : p) q *= f.settings().density_kg_per_m3 * g.cell_volume();
  return p;
}

Vec3 centroid(const std::vector<Vec3>& x, std::size_t count) {
  Vec3 c{};
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t d = 0; d < 3; ++d) c[d] += x[i][d] / static_cast<double>(count);
  return c;
}

// The symmetric bell (the slice's material, muscles and stroke, revolved) in a periodic box of
// water, semi-implicit coupling: through the first contraction the water's momentum stays zero to
// round-off (the shell's forces are internal, and spreading, convection, viscosity and the
// projection conserve momentum: the swimmer and its wake balance), the bell's cavity empties and
// the bell moves up, along its axis, and not sideways (the stroke is symmetric).
TEST(ShellInWater3d, TheContractingBellPushesOffItsWakeAndTheWatersMomentumStaysZero) {
  shell::ShellBell bell(coarse_bell(0.004));
  ShellForces3d model(bell);
  const fluid3d::Grid3d g({16, 20, 16}, {0.08, 0.10, 0.08});
  fluid3d::FluidSettings3d fs;
  fs.boundaries = fluid3d::Boundaries3d::periodic_box();
  fs.viscosity_m2_per_s = 1e-6;
  auto fluid = fluid3d::make_fluid_solver_3d(g, fs);
  ib3d::Markers3d markers(shell_markers(bell, {0.04, 0.04, 0.04}));
  const std::size_t surface = static_cast<std::size_t>(bell.surface().mesh.vertices.size());
  const Vec3 start = centroid(markers.position, surface);
  ib3d::ImmersedBoundary3d ib(*fluid, markers, model);
  double largest_momentum = 0.0, largest_speed = 0.0;
  const double dt = 0.005;
  for (int n = 0; n < 60; ++n) {  // 0.3 s: the contraction
    const ib3d::CoupledStepReport3d r = ib.step(dt);
    ASSERT_TRUE(r.converged) << "step " << n;
    const Vec3 p = momentum(*fluid);
    for (double q : p) largest_momentum = std::max(largest_momentum, std::abs(q));
    for (const Vec3& v : markers.velocity) largest_speed = std::max(largest_speed, std::hypot(v[0], v[1], v[2]));
  }
  const Vec3 moved = centroid(markers.position, surface);
  const double rise = moved[1] - start[1], sideways = std::hypot(moved[0] - start[0], moved[2] - start[2]);
  // The momentum scale: the water a bell volume of, moving at the bell's largest speed.
  const double scale = 1000.0 * 0.02 * 0.02 * 0.028 * largest_speed;
  std::printf("  rise %.3f mm, sideways %.1e mm, largest marker speed %.1f mm/s, |water momentum| <= %.1e of %.1e\n",
              1e3 * rise, 1e3 * sideways, 1e3 * largest_speed, largest_momentum, scale);
  EXPECT_LT(largest_momentum, 1e-10 * scale);  // measured 3.0e-14 of 7.9e-4 (4e-11)
  EXPECT_GT(rise, 0.005);                       // measured 6.48 mm in 0.3 s
  EXPECT_LT(sideways, 1e-10 * rise);            // measured 1.6e-10 mm (2.5e-11 of the rise)
}

}  // namespace
}  // namespace jellysim::swim3d
