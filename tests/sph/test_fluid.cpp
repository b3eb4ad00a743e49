// SPH forces (eqs. 5.5-5.8), the neighbour grid, walls and initial conditions (§5.1.2-5.1.3).
#include "jellysim/sph/fluid.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/neighbour_grid.hpp"
#include "jellysim/sph/scene.hpp"
#include "sph_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace jellysim::sph {
namespace {

TEST(SphNeighbourGrid, FindsExactlyTheBruteForceNeighbours) {
  test::Random rng(7);
  std::vector<Vec2> x;
  for (int i = 0; i < 1500; ++i) x.push_back(rng.point(1.0));
  for (int i = 0; i < 300; ++i) x.push_back(Vec2{0.3, 0.3} + rng.point(0.02));  // a dense cluster
  x.push_back({25.0, -40.0});                                                   // a far outlier
  for (double radius : {0.05, 0.13}) {
    NeighbourGrid grid;
    grid.build(x, radius);
    for (std::size_t i = 0; i < x.size(); ++i) {
      std::vector<std::size_t> found;
      grid.for_each_candidate(x[i], [&](std::size_t j) {
        if (j != i && norm_squared(x[j] - x[i]) < radius * radius) found.push_back(j);
      });
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, brute_force_neighbours(x, i, radius)) << "point " << i << ", radius " << radius;
    }
  }
}

TEST(SphNeighbourGrid, CellCountStaysLinearForASparseSet) {
  NeighbourGrid grid;
  grid.build({{0.0, 0.0}, {1e6, 1e6}}, 1e-3);
  EXPECT_LE(static_cast<double>(grid.columns()) * grid.rows(), 4.0 * 2 + 16);
}

SphParameters parameters() { return {0.05, 2000.0, 40.0, 8.9e-3}; }

TEST(SphFluid, IsolatedParticleHasItsOwnKernelDensity) {
  SphFluid fluid(parameters(), {});
  fluid.compute_density({{0.2, 0.3}}, {{0.0, 0.0}}, {2.5});
  EXPECT_DOUBLE_EQ(fluid.density()[0], 2.5 * Kernels(0.05).poly6(0.0));
}

TEST(SphFluid, CompressedPairRepelsAndStretchedPairAttracts) {
  SphParameters p = parameters();
  SphFluid fluid(p, {});
  std::vector<Vec2> a;
  const std::vector<Vec2> v(2);
  // Mass so large that each density exceeds ρ0: p > 0 pushes apart (the sign eq. 5.6 lacks).
  fluid.compute_accelerations({{0.0, 0.0}, {0.02, 0.0}}, v, {10.0, 10.0}, a);
  EXPECT_LT(a[0].x, 0.0);
  EXPECT_GT(a[1].x, 0.0);
  fluid.compute_accelerations({{0.0, 0.0}, {0.02, 0.0}}, v, {0.1, 0.1}, a);  // ρ < ρ0: attraction
  EXPECT_GT(a[0].x, 0.0);
}

TEST(SphFluid, ViscosityDampsRelativeVelocityOnly) {
  SphParameters p = parameters();
  p.gas_constant = 0.0;
  SphFluid fluid(p, {});
  std::vector<Vec2> a;
  const std::vector<Vec2> x{{0.0, 0.0}, {0.03, 0.0}};
  fluid.compute_accelerations(x, {{0.0, 1.0}, {0.0, -1.0}}, {1.0, 1.0}, a);
  EXPECT_LT(a[0].y, 0.0);
  EXPECT_GT(a[1].y, 0.0);
  fluid.compute_accelerations(x, {{0.7, 1.0}, {0.7, 1.0}}, {1.0, 1.0}, a);  // uniform motion: no force
  EXPECT_EQ(a[0], (Vec2{0.0, 0.0}));
}

TEST(SphFluid, PairForcesConserveMomentum) {
  test::Random rng(11);
  std::vector<Vec2> x, v;
  std::vector<double> m;
  for (int i = 0; i < 400; ++i) {
    x.push_back(rng.point(0.4));
    v.push_back(rng.point(1.0));
    m.push_back(rng.uniform(0.5, 3.0));
  }
  for (int threads : {1, 2}) {
    SphFluid fluid(parameters(), {}, threads);
    std::vector<Vec2> a;
    fluid.compute_accelerations(x, v, m, a);
    Vec2 total{};
    double scale = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      total += a[i] * m[i];
      scale += norm(a[i]) * m[i];
    }
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(norm(total), 1e-12 * scale) << threads << " threads";
  }
}

/// `count` particles uniformly in the square of half-width `half_width` with velocities uniform in
/// the square of half-width `speed`.
void scatter(test::Random& rng, int count, double half_width, double speed, std::vector<Vec2>& x, std::vector<Vec2>& v) {
  for (int i = 0; i < count; ++i) {
    x.push_back(rng.point(half_width));
    v.push_back(rng.point(speed));
  }
}

TEST(SphFluid, ThreadsGiveBitIdenticalAccelerations) {
  test::Random rng(3);
  std::vector<Vec2> x, v;
  scatter(rng, 900, 0.5, 0.1, x, v);
  const std::vector<double> m(x.size(), 1.3);
  const std::vector<Wall> walls = box_walls({-0.5, -0.5}, {0.5, 0.5});
  SphFluid one(parameters(), walls, 1), two(parameters(), walls, 2), three(parameters(), walls, 3);
  // Sizes change between evaluations (buffers are reused), including one below the parallel cut-off.
  for (std::size_t n : {900u, 300u, 40u, 900u}) {
    const std::vector<Vec2> xn(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n)),
        vn(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
    const std::vector<double> mn(n, 1.3);
    std::vector<Vec2> a1, a2, a3;
    one.compute_accelerations(xn, vn, mn, a1);
    two.compute_accelerations(xn, vn, mn, a2);
    three.compute_accelerations(xn, vn, mn, a3);
    EXPECT_EQ(a1, a2) << n;
    EXPECT_EQ(a1, a3) << n;
    EXPECT_EQ(one.density(), three.density()) << n;
    EXPECT_EQ(one.mirrored_count(), three.mirrored_count()) << n;
    EXPECT_GT(one.mirrored_count(), 0u) << n;
  }
}

// The load hook writes each thread's particles straight into the fluid: the same accelerations,
// bit for bit, as the vectors given to the plain overload, with one and two threads; each range is
// loaded once, and each stored range is one that was loaded. Misuse of the two overloads throws.
TEST(SphFluid, LoadHookGivesTheSameAccelerationsAsVectors) {
  test::Random rng(8);
  std::vector<Vec2> x, v;
  scatter(rng, 500, 0.45, 0.1, x, v);
  const std::vector<double> m(x.size(), 1.3);
  const std::vector<Wall> walls = box_walls({-0.5, -0.5}, {0.5, 0.5});
  for (int threads : {1, 2}) {
    SphFluid plain(parameters(), walls, threads), hooked(parameters(), walls, threads);
    std::vector<Vec2> a_plain, a_hooked;
    plain.compute_accelerations(x, v, m, a_plain);
    std::vector<int> loads(x.size(), 0), stores(x.size(), 0);  // each index is touched by one thread
    EvaluationHooks hooks;
    hooks.load = [&](std::size_t b, std::size_t e, Vec2* xs, Vec2* vs) {
      for (std::size_t i = b; i < e; ++i) {
        xs[i] = x[i];
        vs[i] = v[i];
        ++loads[i];
      }
    };
    hooks.store = [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) stores[i] += loads[i];
    };
    hooked.compute_accelerations(m, a_hooked, hooks);
    EXPECT_EQ(a_plain, a_hooked) << threads;
    EXPECT_EQ(plain.density(), hooked.density()) << threads;
    EXPECT_EQ(std::count(loads.begin(), loads.end(), 1), static_cast<std::ptrdiff_t>(x.size())) << threads;
    EXPECT_EQ(std::count(stores.begin(), stores.end(), 1), static_cast<std::ptrdiff_t>(x.size())) << threads;
    EXPECT_THROW(plain.compute_accelerations(x, v, m, a_plain, hooks), std::invalid_argument);
    EXPECT_THROW(hooked.compute_accelerations(m, a_hooked, EvaluationHooks{}), std::invalid_argument);
    EXPECT_THROW(plain.compute_accelerations(x, std::vector<Vec2>(3), m, a_plain), std::invalid_argument);
  }
}

/// Accelerations of a fresh fluid object (neighbours from a new grid search) at x, v, m.
std::vector<Vec2> fresh_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                                      const std::vector<double>& m, const std::vector<Wall>& walls) {
  SphFluid fresh(parameters(), walls);
  std::vector<Vec2> a;
  fresh.compute_accelerations(x, v, m, a);
  return a;
}

/// Largest |a − b| over the particles, relative to the largest |b|.
double relative_difference(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, norm(a[i] - b[i]));
    scale = std::max(scale, norm(b[i]));
  }
  return diff / scale;
}

// The Verlet lists: moves shorter than skin/2 reuse them, a longer one rebuilds them, and either way
// the forces are those of a fresh grid search (up to the order of the sums), twins included.
TEST(SphFluid, NeighbourListsFollowSmallMovesAndRebuildAfterLongOnes) {
  test::Random rng(11);
  const double h = parameters().smoothing_radius_m, half_skin = 0.5 * SphFluid::kListSkin * h;
  std::vector<Vec2> x, v;
  scatter(rng, 400, 0.45, 0.2, x, v);
  const std::vector<double> m(x.size(), 1.1);
  const std::vector<Wall> walls = box_walls({-0.5, -0.5}, {0.5, 0.5});
  for (int threads : {1, 2}) {
    SphFluid fluid(parameters(), walls, threads);
    std::vector<Vec2> a, xs = x;
    fluid.compute_accelerations(xs, v, m, a);
    EXPECT_EQ(fluid.list_rebuilds(), 1);
    for (int round = 0; round < 5; ++round) {  // each particle drifts up to 0.9 skin/2 in all
      for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = x[i] + rng.point(0.9 * half_skin / std::sqrt(2.0));
      fluid.compute_accelerations(xs, v, m, a);
      EXPECT_EQ(fluid.list_rebuilds(), 1) << threads << " threads, round " << round;
      EXPECT_LT(relative_difference(a, fresh_accelerations(xs, v, m, walls)), 1e-12) << threads << " threads";
    }
    xs[7] = x[7] + Vec2{1.01 * half_skin, 0.0};  // one particle far enough: the lists are rebuilt
    fluid.compute_accelerations(xs, v, m, a);
    EXPECT_EQ(fluid.list_rebuilds(), 2) << threads << " threads";
    EXPECT_LT(relative_difference(a, fresh_accelerations(xs, v, m, walls)), 1e-12) << threads << " threads";
    const std::vector<Vec2> fewer(xs.begin(), xs.end() - 1);  // a new particle count rebuilds too
    fluid.compute_accelerations(fewer, std::vector<Vec2>(v.begin(), v.end() - 1), std::vector<double>(fewer.size(), 1.1), a);
    EXPECT_EQ(fluid.list_rebuilds(), 3) << threads << " threads";
  }
}

// Over a drifting sequence of states the lists are reused and rebuilt, and the parts' ranges move
// (balanced by the lists' lengths and the measured speed of each thread); none of that changes a bit.
TEST(SphFluid, ThreadsStayBitIdenticalWhileListsAndRangesChange) {
  test::Random rng(23);
  std::vector<Vec2> x, v;
  for (int i = 0; i < 700; ++i) {
    const Vec2 p = rng.point(0.48);
    x.push_back({p.x, 0.5 * p.y - 0.24 + 0.2 * p.x * p.x});  // uneven density: uneven work per particle
    v.push_back(rng.point(1.0));
  }
  const std::vector<double> m(x.size(), 0.9);
  const std::vector<Wall> walls = box_walls({-0.5, -0.5}, {0.5, 0.5});
  SphFluid one(parameters(), walls, 1), two(parameters(), walls, 2), three(parameters(), walls, 3);
  std::vector<Vec2> a1, a2, a3;
  for (int step = 0; step < 40; ++step) {
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += v[i] * 0.002;  // 2 mm: a rebuild every few steps
    one.compute_accelerations(x, v, m, a1);
    two.compute_accelerations(x, v, m, a2);
    three.compute_accelerations(x, v, m, a3);
    ASSERT_EQ(a1, a2) << "step " << step;
    ASSERT_EQ(a1, a3) << "step " << step;
    ASSERT_EQ(one.mirrored_count(), three.mirrored_count()) << "step " << step;
  }
  EXPECT_GT(one.list_rebuilds(), 3);
  EXPECT_LT(one.list_rebuilds(), 30);
  EXPECT_EQ(one.list_rebuilds(), three.list_rebuilds());
}

// A particle approaching a wall gets its twin as soon as it is within h, without a rebuild; leaving
// again removes it. The forces match a fresh search at every position.
TEST(SphWalls, TwinsAppearAndVanishWithoutARebuild) {
  const std::vector<Wall> walls{Wall{{0.0, 0.0}, {0.0, 1.0}, true}};
  const double h = parameters().smoothing_radius_m, half_skin = 0.5 * SphFluid::kListSkin * h;
  SphFluid fluid(parameters(), walls);
  const std::vector<Vec2> v{{0.0, -0.3}, {0.1, 0.0}};
  const std::vector<double> m{10.0, 10.0};
  std::vector<Vec2> a;
  const auto at = [&](double height) { return std::vector<Vec2>{{0.5, height}, {0.53, h + 0.2 * half_skin}}; };
  for (double height : {h + 0.4 * half_skin, h - 0.4 * half_skin, h + 0.3 * half_skin}) {
    fluid.compute_accelerations(at(height), v, m, a);
    EXPECT_EQ(fluid.mirrored_count(), height < h ? 1u : 0u) << height;
    EXPECT_LT(relative_difference(a, fresh_accelerations(at(height), v, m, walls)), 1e-12) << height;
  }
  EXPECT_EQ(fluid.list_rebuilds(), 1);
}

TEST(SphWalls, MirroredTwinsRepelParticlesFromAWall) {
  SphFluid fluid(parameters(), {Wall{{0.0, 0.0}, {0.0, 1.0}, true}});
  std::vector<Vec2> a;
  fluid.compute_accelerations({{0.5, 0.01}}, {{0.0, -1.0}}, {10.0}, a);
  EXPECT_EQ(fluid.mirrored_count(), 1u);
  EXPECT_GT(a[0].y, 0.0);                    // pushed off the wall
  EXPECT_NEAR(a[0].x, 0.0, 1e-12 * a[0].y);  // straight away from it
  fluid.compute_accelerations({{0.5, 0.06}}, {{0.0, 0.0}}, {10.0}, a);
  EXPECT_EQ(fluid.mirrored_count(), 0u);  // farther than h: no twin
}

TEST(SphInitialConditions, TriangularLatticeHasSixEquidistantNeighbours) {
  const double a = 0.04;
  const std::vector<Vec2> x = triangular_lattice({0.0, 0.0}, {1.0, 1.0}, a);
  int interior = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i].x < 0.2 || x[i].x > 0.8 || x[i].y < 0.2 || x[i].y > 0.8) continue;
    ++interior;
    const auto near = brute_force_neighbours(x, i, 1.01 * a);
    ASSERT_EQ(near.size(), 6u);
    for (std::size_t j : near) EXPECT_NEAR(norm(x[j] - x[i]), a, 1e-12);
  }
  EXPECT_GT(interior, 100);
  for (Vec2 p : x) {
    EXPECT_GE(std::min({p.x, p.y, 1.0 - p.x, 1.0 - p.y}), 0.5 * a - 1e-12);
  }
}

TEST(SphInitialConditions, LatticeWithCountHasExactlyThatManyPointsOutsideTheHole) {
  const auto hole = [](Vec2 p) { return std::abs(p.x - 0.5) < 0.2 && std::abs(p.y - 0.5) < 0.025; };
  const std::vector<Vec2> x = triangular_lattice_with_count({0.0, 0.0}, {1.0, 1.0}, 625, hole);
  ASSERT_EQ(x.size(), 625u);
  for (Vec2 p : x) EXPECT_FALSE(hole(p));
}

TEST(SphInitialConditions, MassBisectionReachesTheRestDensity) {
  const std::vector<Vec2> x = triangular_lattice({0.0, 0.0}, {1.0, 1.0}, 0.043);
  const SphParameters p = parameters();
  const std::vector<Wall> walls = box_walls({0.0, 0.0}, {1.0, 1.0});
  const MassSearch r = find_particle_mass(x, 1.0, p, walls, 1e-6);
  EXPECT_NEAR(r.mean_density, p.rest_density, 1e-6 * p.rest_density);
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(std::abs(r.mass_kg - r.initial_guess_kg), 0.01 * r.initial_guess_kg);  // eq. 5.21 alone is off
  SphFluid fluid(p, walls);
  fluid.compute_density(x, std::vector<Vec2>(x.size()), std::vector<double>(x.size(), r.mass_kg));
  double mean = 0.0;
  for (double rho : fluid.density()) mean += rho / static_cast<double>(x.size());
  EXPECT_NEAR(mean, p.rest_density, 1e-6 * p.rest_density);
}

TEST(SphInitialConditions, ThermalisedVelocitiesOpposeTheNoiseAndAreSeeded) {
  std::vector<Vec2> x0 = triangular_lattice({0.0, 0.0}, {1.0, 1.0}, 0.05), x = x0, v, x2 = x0, v2;
  thermalise(x, v, 0.004, 0.01, 42);
  thermalise(x2, v2, 0.004, 0.01, 42);
  EXPECT_EQ(x, x2);
  EXPECT_EQ(v, v2);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec2 eps = x[i] - x0[i];
    EXPECT_LE(norm(eps), 0.004 + 1e-15);
    EXPECT_NEAR(v[i].x, -0.01 * eps.x, 1e-15);
    EXPECT_NEAR(v[i].y, -0.01 * eps.y, 1e-15);
  }
}

}  // namespace
}  // namespace jellysim::sph

namespace jellysim::sph {
namespace {

TEST(SphFluid, AccelerationsMatchADirectSumOverAllPairs) {
  // Reference: eqs. 5.5, 5.6 (with its minus sign) and 5.8 (with v_j − v_i), written out with the
  // Kernels functions over all pairs, no grid and no walls.
  test::Random rng(17);
  const SphParameters p = parameters();
  const Kernels k(p.smoothing_radius_m);
  std::vector<Vec2> x, v;
  std::vector<double> m;
  for (int i = 0; i < 300; ++i) {
    x.push_back(rng.point(0.25));
    v.push_back(rng.point(0.5));
    m.push_back(rng.uniform(1.0, 4.0));
  }
  const std::size_t n = x.size();
  std::vector<double> rho(n, 0.0), pressure(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) rho[i] += m[j] * k.poly6(norm(x[i] - x[j]));
    pressure[i] = p.gas_constant * (rho[i] - p.rest_density);
  }
  SphFluid fluid(p, {});
  std::vector<Vec2> a;
  fluid.compute_accelerations(x, v, m, a);
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 f_pressure{}, f_viscous{};
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const Vec2 d = x[i] - x[j];
      const double r = norm(d);
      f_pressure -= k.spiky_gradient(d, r) * (m[j] / rho[j] * 0.5 * (pressure[i] + pressure[j]));
      f_viscous += (v[j] - v[i]) * (m[j] / rho[j] * k.viscosity_laplacian(r));
    }
    const Vec2 expected = f_pressure / rho[i] + f_viscous * (p.viscosity * p.rest_density / rho[i]);
    ASSERT_NEAR(fluid.density()[i], rho[i], 1e-12 * rho[i]);
    ASSERT_NEAR(a[i].x, expected.x, 1e-9 * (norm(expected) + 1.0)) << i;
    ASSERT_NEAR(a[i].y, expected.y, 1e-9 * (norm(expected) + 1.0)) << i;
  }
}

}  // namespace
}  // namespace jellysim::sph
