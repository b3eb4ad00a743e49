// Spreading and interpolation (thesis §4.3.2): conservation, exactness and adjointness.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "jellysim/coupling/transfer_kernels.hpp"

namespace jellysim::coupling {
namespace {

const fluid::MacGrid kGrid(24, 20, 1.2, 1.0, Vec2{-0.1, 0.2});

std::vector<Vec2> random_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  // Keep away from the sides so the 4-point stencil stays on stored samples.
  std::uniform_real_distribution<double> ux(0.1, 0.9), uy(0.45, 1.0);
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) p.push_back({ux(rng), uy(rng)});
  return p;
}

class KernelTest : public ::testing::TestWithParam<Kernel> {};

TEST_P(KernelTest, WeightsSumToOneAndHaveZeroFirstMoment) {
  for (double r : {0.0, 0.13, 0.5, 0.77, 0.999}) {
    double sum = 0.0, moment = 0.0;
    for (int i = -3; i <= 3; ++i) {
      sum += kernel_weight(GetParam(), r - i);
      moment += (r - i) * kernel_weight(GetParam(), r - i);
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << r;
    EXPECT_NEAR(moment, 0.0, 1e-14) << r;
  }
}

TEST_P(KernelTest, SpreadingConservesTotalForceAndTorque) {
  const auto points = random_points(17, 1);
  std::vector<Vec2> forces;
  std::mt19937 rng(2);
  std::normal_distribution<double> n01;
  for (std::size_t k = 0; k < points.size(); ++k) forces.push_back({n01(rng), n01(rng)});
  const double rho = 1000.0;
  fluid::FaceAccelerations acc(kGrid);
  spread_forces(points, forces, GetParam(), rho, acc);
  Vec2 f_lagrangian{};
  double torque_lagrangian = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    f_lagrangian += forces[k];
    torque_lagrangian += cross(points[k], forces[k]);
  }
  const double cell_mass = rho * kGrid.dx() * kGrid.dy();
  Vec2 f_grid{};
  double torque_grid = 0.0;
  for (int j = -1; j <= acc.u.count_y(); ++j)
    for (int i = -1; i <= acc.u.count_x(); ++i) {
      f_grid.x += cell_mass * acc.u(i, j);
      torque_grid -= acc.u.position(i, j).y * cell_mass * acc.u(i, j);
    }
  for (int j = -1; j <= acc.v.count_y(); ++j)
    for (int i = -1; i <= acc.v.count_x(); ++i) {
      f_grid.y += cell_mass * acc.v(i, j);
      torque_grid += acc.v.position(i, j).x * cell_mass * acc.v(i, j);
    }
  EXPECT_NEAR(f_grid.x, f_lagrangian.x, 1e-12);
  EXPECT_NEAR(f_grid.y, f_lagrangian.y, 1e-12);
  EXPECT_NEAR(torque_grid, torque_lagrangian, 1e-12);
}

TEST_P(KernelTest, InterpolationReproducesLinearFieldsExactly) {
  fluid::Velocity vel(kGrid);
  auto u_exact = [](Vec2 p) { return 0.3 + 1.7 * p.x - 0.4 * p.y; };
  auto v_exact = [](Vec2 p) { return -1.1 + 0.25 * p.x + 2.5 * p.y; };
  for (int j = -1; j <= vel.u.count_y(); ++j)
    for (int i = -1; i <= vel.u.count_x(); ++i) vel.u(i, j) = u_exact(vel.u.position(i, j));
  for (int j = -1; j <= vel.v.count_y(); ++j)
    for (int i = -1; i <= vel.v.count_x(); ++i) vel.v(i, j) = v_exact(vel.v.position(i, j));
  const auto points = random_points(40, 3);
  std::vector<Vec2> out(points.size());
  interpolate_velocities(vel, points, GetParam(), out);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR(out[k].x, u_exact(points[k]), 1e-13);
    EXPECT_NEAR(out[k].y, v_exact(points[k]), 1e-13);
  }
}

TEST_P(KernelTest, SpreadAndInterpolateAreAdjoint) {
  // Σ_k F_k · (J u)_k = Σ_faces (S F)(face) u(face) ρΔxΔy for any u and F.
  const auto points = random_points(11, 4);
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  std::vector<Vec2> forces;
  for (std::size_t k = 0; k < points.size(); ++k) forces.push_back({n01(rng), n01(rng)});
  fluid::Velocity vel(kGrid);
  for (double& x : vel.u.raw()) x = n01(rng);
  for (double& x : vel.v.raw()) x = n01(rng);
  std::vector<Vec2> at_points(points.size());
  interpolate_velocities(vel, points, GetParam(), at_points);
  double lagrangian = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) lagrangian += dot(forces[k], at_points[k]);
  const double rho = 2.0;
  fluid::FaceAccelerations acc(kGrid);
  spread_forces(points, forces, GetParam(), rho, acc);
  double eulerian = 0.0;
  for (std::size_t k = 0; k < acc.u.raw().size(); ++k) eulerian += acc.u.raw()[k] * vel.u.raw()[k];
  for (std::size_t k = 0; k < acc.v.raw().size(); ++k) eulerian += acc.v.raw()[k] * vel.v.raw()[k];
  eulerian *= rho * kGrid.dx() * kGrid.dy();
  EXPECT_NEAR(eulerian, lagrangian, 1e-12 * std::max(1.0, std::abs(lagrangian)));
}

INSTANTIATE_TEST_SUITE_P(Kernels, KernelTest, ::testing::Values(Kernel::bilinear, Kernel::peskin4),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(Kernel, PeskinFourPointHasItsDefiningSumOfSquares) {
  // Σ_i φ(r − i)² = 3/8 for every r (Peskin 2002, eq. 6.24).
  for (double r : {0.0, 0.2, 0.5, 0.9}) {
    double s = 0.0;
    for (int i = -3; i <= 3; ++i) s += std::pow(kernel_weight(Kernel::peskin4, r - i), 2);
    EXPECT_NEAR(s, 3.0 / 8.0, 1e-14);
  }
}

// A periodic tank: a point within two cells of a seam reaches the samples beyond it on the other
// side. Spreading keeps the whole force on the independent samples (before the fix the samples
// beyond the ghost layer were dropped: 6 % of the force for a point half a cell from the seam),
// and interpolation of a field that is periodic reads the same value on both sides of the seam.
TEST(Kernel, WrapsAroundPeriodicSeams) {
  const fluid::MacGrid g(16, 12, 1.6, 1.2);
  const Periodicity both{true, true};
  for (Vec2 p : {Vec2{0.05, 0.6}, Vec2{1.58, 0.6}, Vec2{0.8, 0.02}, Vec2{0.01, 1.19}}) {
    fluid::FaceAccelerations acc(g);
    const std::vector<Vec2> at{p}, force{{0.3, -0.7}};
    spread_forces(at, force, Kernel::peskin4, 1.0, acc, both);
    double fx = 0.0, fy = 0.0;  // independent samples: faces 0 … n − 1 along the periodic axis
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) fx += acc.u(i, j), fy += acc.v(i, j);
    EXPECT_NEAR(fx * g.dx() * g.dy(), 0.3, 1e-14) << p.x << ", " << p.y;
    EXPECT_NEAR(fy * g.dx() * g.dy(), -0.7, 1e-14) << p.x << ", " << p.y;
  }
  // Interpolation on the seam of a periodic field reads what it reads in the interior of the
  // field shifted by whole cells: u = sin(2π(x − s_x)/L_x) at x = s_x (s_x = 6 cells) equals
  // u = sin(2πx/L_x) at x = 0 and at x = L_x; likewise v along y.
  auto periodic_field = [&](Vec2 shift) {
    fluid::Velocity vel(g);
    for (int j = -1; j <= vel.u.count_y(); ++j)
      for (int i = -1; i <= vel.u.count_x(); ++i)
        vel.u(i, j) = std::sin(2 * M_PI * (vel.u.position(i, j).x - shift.x) / 1.6);
    for (int j = -1; j <= vel.v.count_y(); ++j)
      for (int i = -1; i <= vel.v.count_x(); ++i)
        vel.v(i, j) = std::cos(2 * M_PI * (vel.v.position(i, j).y - shift.y) / 1.2);
    return vel;
  };
  const Vec2 shift{0.6, 0.6};
  const std::vector<Vec2> seam{{0.0, 0.3}, {1.6, 0.3}, {0.7, 0.0}, {0.7, 1.2}}, inside{{0.6, 0.3}, {0.7, 0.6}};
  std::vector<Vec2> on_seam(seam.size()), in_interior(inside.size());
  interpolate_velocities(periodic_field({}), seam, Kernel::peskin4, on_seam, both);
  interpolate_velocities(periodic_field(shift), inside, Kernel::peskin4, in_interior, both);
  EXPECT_NEAR(on_seam[0].x, in_interior[0].x, 1e-14);
  EXPECT_NEAR(on_seam[1].x, in_interior[0].x, 1e-14);
  EXPECT_NEAR(on_seam[2].y, in_interior[1].y, 1e-14);
  EXPECT_NEAR(on_seam[3].y, in_interior[1].y, 1e-14);
}

TEST(Kernel, NamesRoundTrip) {
  EXPECT_EQ(kernel_from_string("peskin4"), Kernel::peskin4);
  EXPECT_EQ(kernel_from_string("bilinear"), Kernel::bilinear);
  EXPECT_FALSE(kernel_from_string("gauss").has_value());
}

}  // namespace
}  // namespace jellysim::coupling

namespace jellysim::coupling {
namespace {

// Axisymmetric rings (issue 22): random rings, some within two cells of the axis.
std::vector<Vec2> rings(const fluid::MacGrid& g, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> r(0.0, 0.8 * g.width_m), z(0.25 * g.height_m, 0.75 * g.height_m);
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) p.push_back({k < n / 2 ? r(rng) * 0.05 : r(rng), z(rng)});  // half of them near the axis
  return p;
}

// Σ_faces 2π r ΔrΔz ρ a·u = Σ_rings F·U(X): spreading and interpolation are adjoint in the
// volume-weighted inner product, with the kernel folded across the axis.
TEST(AxisymmetricKernel, SpreadAndInterpolateAreAdjointInTheVolumeWeightedProduct) {
  const fluid::MacGrid g(20, 24, 1.0, 1.2);
  for (Kernel k : {Kernel::bilinear, Kernel::peskin4}) {
    const std::vector<Vec2> points = rings(g, 16, 3);
    std::mt19937 rng(4);
    std::normal_distribution<double> normal;
    std::vector<Vec2> forces;
    for (std::size_t m = 0; m < points.size(); ++m) forces.push_back({normal(rng), normal(rng)});
    fluid::Velocity vel(g);
    for (double& x : vel.u.raw()) x = normal(rng);
    for (double& x : vel.v.raw()) x = normal(rng);
    for (int j = -1; j <= g.ny; ++j) vel.u(0, j) = 0.0;  // u_r = 0 on the axis
    std::vector<Vec2> at(points.size());
    interpolate_velocities_axisymmetric(vel, points, k, at);
    double lagrangian = 0.0;
    for (std::size_t m = 0; m < points.size(); ++m) lagrangian += dot(forces[m], at[m]);
    const double rho = 3.0;
    fluid::FaceAccelerations acc(g);
    spread_forces_axisymmetric(points, forces, k, rho, acc);
    double eulerian = 0.0;
    const double cell = 2.0 * M_PI * g.dx() * g.dy() * rho;
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) eulerian += cell * i * g.dx() * acc.u(i, j) * vel.u(i, j);
      for (int i = 0; i < g.nx; ++i) eulerian += cell * (i + 0.5) * g.dx() * acc.v(i, j) * vel.v(i, j);
    }
    EXPECT_NEAR(eulerian, lagrangian, 1e-12 * std::abs(lagrangian)) << to_string(k);
  }
}

// The axial force of every ring reaches the fluid whole (Σ 2π r ΔrΔz ρ a_z = Σ F_z), near the axis
// too; and interpolation is exact for u_r = c r (odd across the axis) and u_z = const (even).
TEST(AxisymmetricKernel, ConservesAxialForceAndIsExactForLinearFields) {
  const fluid::MacGrid g(20, 24, 1.0, 1.2);
  for (Kernel k : {Kernel::bilinear, Kernel::peskin4}) {
    const std::vector<Vec2> points = rings(g, 10, 9);
    std::vector<Vec2> forces(points.size(), Vec2{0.3, -1.7});
    fluid::FaceAccelerations acc(g);
    spread_forces_axisymmetric(points, forces, k, 1.0, acc);
    double fz = 0.0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) fz += 2.0 * M_PI * (i + 0.5) * g.dx() * g.dx() * g.dy() * acc.v(i, j);
    EXPECT_NEAR(fz, -1.7 * static_cast<double>(points.size()), 1e-12) << to_string(k);
    fluid::Velocity vel(g);
    for (int j = -1; j <= g.ny; ++j) {
      for (int i = -1; i <= g.nx + 1; ++i) vel.u(i, j) = 0.7 * i * g.dx();
      for (int i = -1; i <= g.nx; ++i) vel.v(i, j) = -0.4;
    }
    std::vector<Vec2> at(points.size());
    interpolate_velocities_axisymmetric(vel, points, k, at);
    for (std::size_t m = 0; m < points.size(); ++m) {
      EXPECT_NEAR(at[m].x, 0.7 * points[m].x, 1e-12) << to_string(k) << " r = " << points[m].x;
      EXPECT_NEAR(at[m].y, -0.4, 1e-12);
    }
  }
}

}  // namespace
}  // namespace jellysim::coupling
