// The 3D immersed boundary's transfer (issue 40, part 2): the tensor-product kernel, its
// adjointness, moments and exactness, periodic seams, walls, mirror planes, threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "jellysim/ib3d/transfer_3d.hpp"

namespace jellysim::ib3d {
namespace {

using fluid3d::Boundaries3d;
using fluid3d::Grid3d;
using fluid3d::Velocity3d;

/// A box with mirror planes at both x sides, periodic along y, walls along z.
Boundaries3d mixed() {
  Boundaries3d b = Boundaries3d::duct(1);
  b.axis[0].symmetry = {true, true};
  return b;
}

struct Mix {
  const char* name;
  Boundaries3d b;
};
std::vector<Mix> boundary_mixes() {
  return {{"closed box", Boundaries3d::closed_box()},
          {"periodic box", Boundaries3d::periodic_box()},
          {"duct along y", Boundaries3d::duct(1)},
          {"quarter tank", Boundaries3d::closed_box().quarter()},
          {"mirrors at both x sides", mixed()}};
}

/// Markers anywhere in the box, many within the kernel's reach of a side.
std::vector<Vec3> random_markers(const Grid3d& g, std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x(n);
  for (auto& p : x)
    for (int d = 0; d < 3; ++d) p[static_cast<std::size_t>(d)] = g.origin()[static_cast<std::size_t>(d)] + g.size(d) * u(rng);
  return x;
}

std::vector<Vec3> random_vectors(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> f(n);
  for (auto& p : f) p = {u(rng), u(rng), u(rng)};
  return f;
}

// ρ V Σ_samples a·u = Σ_markers F·U on random markers, forces and a random velocity (ghosts
// included: no boundary condition is assumed): spreading and interpolation are adjoint to
// round-off on every boundary mix (measured ≤ 2e-16 relative).
TEST(Transfer3d, SpreadingAndInterpolationAreAdjointOnEveryBoundaryMix) {
  const Grid3d g({10, 12, 9}, {0.05, 0.072, 0.036}, {0.01, -0.02, 0.0});  // anisotropic cells
  const double rho = 1000.0;
  for (const Mix& mix : boundary_mixes()) {
    std::mt19937 rng(7);
    const auto x = random_markers(g, 300, rng);
    const auto f = random_vectors(x.size(), rng);
    Velocity3d u(g), a(g);
    std::uniform_real_distribution<double> uu(-1.0, 1.0);
    for (auto& q : u.c)
      for (double& s : q) s = uu(rng);
    Transfer3d t(g, mix.b);
    t.spread(x, f, rho, a);
    std::vector<Vec3> at(x.size());
    t.interpolate(u, x, at);
    double grid_side = 0.0, marker_side = 0.0, scale = 0.0;
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < u.c[c].size(); ++i) grid_side += a.c[c][i] * u.c[c][i];
    grid_side *= rho * g.cell_volume();
    for (std::size_t m = 0; m < x.size(); ++m)
      for (std::size_t c = 0; c < 3; ++c) {
        marker_side += f[m][c] * at[m][c];
        scale += std::abs(f[m][c] * at[m][c]);
      }
    std::printf("%-24s <S f, u> rho V = %.15g, <f, J u> = %.15g, difference / scale %.2g\n", mix.name, grid_side,
                marker_side, std::abs(grid_side - marker_side) / scale);
    EXPECT_LT(std::abs(grid_side - marker_side), 1e-14 * scale) << mix.name;
  }
}

// In a periodic box every marker's weights sum to 1 (Σ a ρV = F for each component) and have no
// first moment about the marker (Σ a x ρV = F X for a marker away from the seams).
TEST(Transfer3d, WeightsSumToOneAndHaveNoFirstMoment) {
  const Grid3d g({12, 10, 14}, {0.06, 0.04, 0.07});
  Transfer3d t(g, Boundaries3d::periodic_box());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.3, 0.7);  // away from the seams: positions unwrapped
  double worst_sum = 0.0, worst_moment = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 x{0.06 * u(rng), 0.04 * u(rng), 0.07 * u(rng)};
    const std::vector<Vec3> f{{1.0, -2.0, 0.5}};
    Velocity3d a(g);
    t.spread(std::vector<Vec3>{x}, f, 1.0, a);
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      Vec3 moment{};
      for (int k = 0; k < g.n(2); ++k)
        for (int j = 0; j < g.n(1); ++j)
          for (int i = 0; i < g.n(0); ++i) {
            const double v = a.c[static_cast<std::size_t>(c)][g.index(i, j, k)] * g.cell_volume();
            const Vec3 p = g.position(c, i, j, k);
            sum += v;
            for (std::size_t d = 0; d < 3; ++d) moment[d] += v * (p[d] - x[d]);
          }
      worst_sum = std::max(worst_sum, std::abs(sum - f[0][static_cast<std::size_t>(c)]));
      for (double m : moment) worst_moment = std::max(worst_moment, std::abs(m));
    }
  }
  std::printf("largest |sum - F| %.2g N, largest first moment %.2g N m\n", worst_sum, worst_moment);
  EXPECT_LT(worst_sum, 1e-14);
  EXPECT_LT(worst_moment, 1e-16);
}

// A constant velocity is interpolated exactly: anywhere in a periodic box, near the walls of a
// closed box (the field constant in the ghosts too), and, for the component tangential to both
// mirror planes, anywhere in the quarter tank (folded samples of an even component keep their sign).
TEST(Transfer3d, AConstantVelocityIsInterpolatedExactly) {
  const Grid3d g({8, 10, 9}, {0.04, 0.05, 0.045});
  std::mt19937 rng(11);
  const auto x = random_markers(g, 200, rng);
  struct Case {
    Boundaries3d b;
    Vec3 value;
  };
  for (const Case& c : {Case{Boundaries3d::periodic_box(), {0.3, -0.2, 0.1}},
                        Case{Boundaries3d::closed_box(), {0.3, -0.2, 0.1}},
                        Case{Boundaries3d::closed_box().quarter(), {0.0, -0.2, 0.0}}}) {
    Velocity3d u(g);
    for (std::size_t k = 0; k < 3; ++k) std::fill(u.c[k].begin(), u.c[k].end(), c.value[k]);
    Transfer3d t(g, c.b);
    std::vector<Vec3> at(x.size());
    t.interpolate(u, x, at);
    double worst = 0.0;
    for (const Vec3& v : at)
      for (std::size_t k = 0; k < 3; ++k) worst = std::max(worst, std::abs(v[k] - c.value[k]));
    EXPECT_LT(worst, 1e-15);
  }
}

// A marker near a mirror plane acts with its image: in the quarter tank, its spread force equals
// the full box's (the marker and its image spread there), restricted to the quarter.
TEST(Transfer3d, TheQuarterTankSeesTheMarkersImages) {
  const double h = 0.005;
  const Grid3d full({16, 8, 16}, {16 * h, 8 * h, 16 * h}, {-8 * h, 0.0, -8 * h});
  const Grid3d quarter({8, 8, 8}, {8 * h, 8 * h, 8 * h});
  const Vec3 x{0.3 * h, 3.7 * h, 1.2 * h};
  const Vec3 f{0.7, -0.4, 0.9};
  // The full box: the marker and its three images (x → −x, z → −z, both), force components odd
  // in the mirrored coordinate.
  std::vector<Vec3> xs, fs;
  for (int sx : {1, -1})
    for (int sz : {1, -1}) {
      xs.push_back({sx * x[0], x[1], sz * x[2]});
      fs.push_back({sx * f[0], f[1], sz * f[2]});
    }
  Velocity3d a_full(full), a_quarter(quarter);
  Transfer3d(full, Boundaries3d::closed_box()).spread(xs, fs, 1000.0, a_full);
  Transfer3d(quarter, Boundaries3d::closed_box().quarter()).spread(std::vector<Vec3>{x}, std::vector<Vec3>{f}, 1000.0,
                                                                 a_quarter);
  double worst = 0.0, largest = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 8; ++k)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
          const double q = a_quarter.c[static_cast<std::size_t>(c)][quarter.index(i, j, k)];
          const double w = a_full.c[static_cast<std::size_t>(c)][full.index(i + 8, j, k + 8)];
          worst = std::max(worst, std::abs(q - w));
          largest = std::max(largest, std::abs(w));
        }
  std::printf("quarter vs full box: largest %.3g m/s^2, difference %.2g\n", largest, worst);
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(worst, 1e-15 * largest);
}

// Spreading (slabs of z-planes per thread) and interpolation (markers per thread) give the same
// bits on one and two threads.
TEST(Transfer3dThreads, OneAndTwoThreadsGiveTheSameBits) {
  const Grid3d g({12, 16, 14}, {0.06, 0.08, 0.07});
  std::mt19937 rng(5);
  const auto x = random_markers(g, 2000, rng);
  const auto f = random_vectors(x.size(), rng);
  Velocity3d u(g);
  std::uniform_real_distribution<double> uu(-1.0, 1.0);
  for (auto& q : u.c)
    for (double& s : q) s = uu(rng);
  std::vector<Velocity3d> spread;
  std::vector<std::vector<Vec3>> interpolated;
  for (int threads : {1, 2}) {
    WorkerPool pool(threads);
    Transfer3d t(g, Boundaries3d::closed_box().quarter(), coupling::Kernel::peskin4, &pool);
    spread.emplace_back(g);
    t.spread(x, f, 1000.0, spread.back());
    interpolated.emplace_back(x.size());
    t.interpolate(u, x, interpolated.back());
  }
  for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(spread[0].c[c], spread[1].c[c]) << "component " << c;
  EXPECT_EQ(interpolated[0], interpolated[1]);
}

}  // namespace
}  // namespace jellysim::ib3d
