// The marker-space mobility R = J P S / ρ from the Green's-function table of the discrete
// projection (coupling/mobility.hpp) against R built column by column through the fluid's own
// spread, FFT projection and interpolation, for every kind of side, both kernels, markers near
// walls and corners, and the half tank's mirror side.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <random>

#include "jellysim/core/parallel.hpp"
#include "jellysim/coupling/immersed_boundary.hpp"
#include "jellysim/coupling/mobility.hpp"
#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/flow_mirror.hpp"

namespace jellysim::coupling {
namespace {

using fluid::BoundaryType;

struct Case {
  const char* name;
  BoundaryType west, east, south, north;
  Kernel kernel;
};

fluid::Boundaries sides(const Case& c) {
  fluid::Boundaries b;
  b.west.type = c.west;
  b.east.type = c.east;
  b.south.type = c.south;
  b.north.type = c.north;
  return b;
}

/// Markers spread over the box, a third of them within two cells of a side or in a corner.
std::vector<Vec2> markers(const fluid::MacGrid& g, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> p;
  const Vec2 lo = g.origin_m, size{g.width_m, g.height_m};
  for (int k = 0; k < count; ++k) {
    Vec2 q{lo.x + size.x * u(rng), lo.y + size.y * u(rng)};
    if (k % 3 == 1) q.x = lo.x + g.dx() * 2.0 * u(rng);                          // near the west side
    if (k % 3 == 2) q = {lo.x + size.x - 2.0 * g.dx() * u(rng), lo.y + 2.0 * g.dy() * u(rng)};  // south-east corner
    p.push_back(q);
  }
  return p;
}

/// R by projections and by the table for one configuration; returns the largest difference
/// relative to the largest entry.
double table_error(const Case& c, const fluid::MacGrid& grid, const std::vector<Vec2>& points, bool west_mirror,
                   Eigen::MatrixXd* table_r = nullptr, Eigen::MatrixXd* projected_r = nullptr) {
  fluid::FluidSettings fs;
  fs.boundaries = sides(c);
  fs.pressure_solver = "fft";
  auto fluid = fluid::make_fluid_solver("eulerian", grid, fs);
  elastic::Body body;
  for (Vec2 p : points) body.add_point(p, 1.0);
  CouplingSettings settings;
  settings.kernel = c.kernel;
  settings.west_mirror = west_mirror;
  ImmersedBoundary ib(*fluid, body, settings);
  const Eigen::MatrixXd reference = ib.response_by_projections();
  const MobilityMatrix mobility({grid, fs.boundaries.homogeneous(), c.kernel, west_mirror});
  Eigen::MatrixXd r;
  mobility.assemble(points, {}, fs.density_kg_per_m3, {}, r);
  if (table_r) *table_r = r;
  if (projected_r) *projected_r = reference;
  return (r - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

class MobilityTable : public ::testing::TestWithParam<Case> {};

// 24 × 20 cells of 12.5 × 10 mm (not square), 30 markers. The table and the projections agree to
// round-off (measured 3.3e-16 to 9.0e-16 of the largest entry; allowed 1e-14).
TEST_P(MobilityTable, EqualsTheResponseBuiltByProjections) {
  const fluid::MacGrid grid(24, 20, 0.3, 0.2);
  const double error = table_error(GetParam(), grid, markers(grid, 30, 7), false);
  std::printf("%s: table against projections %.3g of the largest entry\n", GetParam().name, error);
  EXPECT_LT(error, 1e-14) << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(
    Sides, MobilityTable,
    ::testing::Values(
        Case{"free-slip box", BoundaryType::free_slip, BoundaryType::free_slip, BoundaryType::free_slip,
             BoundaryType::free_slip, Kernel::bilinear},
        Case{"no-slip box, Peskin", BoundaryType::no_slip, BoundaryType::no_slip, BoundaryType::no_slip,
             BoundaryType::no_slip, Kernel::peskin4},
        Case{"channel: in-flow south, outflow north", BoundaryType::no_slip, BoundaryType::free_slip,
             BoundaryType::inflow, BoundaryType::outflow, Kernel::bilinear},
        Case{"channel, Peskin", BoundaryType::free_slip, BoundaryType::no_slip, BoundaryType::inflow,
             BoundaryType::outflow, Kernel::peskin4},
        Case{"outflow on both ends", BoundaryType::outflow, BoundaryType::outflow, BoundaryType::no_slip,
             BoundaryType::free_slip, Kernel::bilinear},
        Case{"periodic across, walls along", BoundaryType::periodic, BoundaryType::periodic, BoundaryType::free_slip,
             BoundaryType::no_slip, Kernel::bilinear},
        Case{"periodic both ways, Peskin", BoundaryType::periodic, BoundaryType::periodic, BoundaryType::periodic,
             BoundaryType::periodic, Kernel::peskin4}),
    [](const ::testing::TestParamInfo<Case>& info) {
      std::string n = info.param.name;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

// Markers within two cells of the seams of a periodic tank (the 4-point kernel wraps around).
TEST(MobilityTable, EqualsTheResponseWithMarkersOnPeriodicSeams) {
  const fluid::MacGrid grid(24, 20, 0.3, 0.2);
  const std::vector<Vec2> p{{0.004, 0.1}, {0.296, 0.12}, {0.15, 0.003}, {0.1, 0.199}, {0.001, 0.002}};
  const Case c{"periodic seams", BoundaryType::periodic, BoundaryType::periodic, BoundaryType::periodic,
               BoundaryType::periodic, Kernel::peskin4};
  EXPECT_LT(table_error(c, grid, p, false), 1e-11);
}

// The half tank: a free-slip west side that is a mirror plane, markers on both sides of it and on
// it (a symmetric body and its west half, which only spills onto the east faces).
TEST(MobilityTable, EqualsTheResponseOnAHalfTankWithAMirrorSide) {
  for (Kernel k : {Kernel::bilinear, Kernel::peskin4}) {
    const fluid::MacGrid whole(24, 20, 0.24, 0.2);
    const fluid::MacGrid half = fluid::east_half(whole);
    std::vector<Vec2> p = markers(half, 12, 3);
    const std::size_t east = p.size();
    for (std::size_t i = 0; i < east; ++i) p.push_back({2 * half.origin_m.x - p[i].x, p[i].y});  // mirror images
    p.push_back({half.origin_m.x, 0.1});                                                        // on the axis
    const Case c{"half", BoundaryType::free_slip, BoundaryType::no_slip, BoundaryType::free_slip,
                 BoundaryType::free_slip, k};
    EXPECT_LT(table_error(c, half, p, true), 1e-11) << to_string(k);
  }
}

// On the half tank the response to a symmetric force is the whole tank's: R_half f = R_whole f at
// every marker (both built by projections, so this checks the mirror side itself).
TEST(MobilityTable, HalfTankRespondsToSymmetricForcesLikeTheWholeTank) {
  const fluid::MacGrid whole(24, 20, 0.24, 0.2);
  const fluid::MacGrid half = fluid::east_half(whole);
  std::vector<Vec2> p = markers(half, 10, 11);
  const std::size_t east = p.size();
  for (std::size_t i = 0; i < east; ++i) p.push_back({2 * half.origin_m.x - p[i].x, p[i].y});
  p.push_back({half.origin_m.x, 0.07});
  Eigen::VectorXd f(2 * static_cast<Eigen::Index>(p.size()));
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (std::size_t i = 0; i < east; ++i) {
    const double fx = normal(rng), fy = normal(rng);
    const auto a = 2 * static_cast<Eigen::Index>(i), b = 2 * static_cast<Eigen::Index>(i + east);
    f[a] = fx, f[a + 1] = fy, f[b] = -fx, f[b + 1] = fy;
  }
  f[f.size() - 2] = 0.0, f[f.size() - 1] = normal(rng);
  for (Kernel k : {Kernel::bilinear, Kernel::peskin4}) {
    const Case c{"", BoundaryType::free_slip, BoundaryType::free_slip, BoundaryType::no_slip, BoundaryType::free_slip, k};
    Eigen::MatrixXd r_half, r_whole, unused;
    table_error(c, half, p, true, &unused, &r_half);
    table_error(c, whole, p, false, &unused, &r_whole);
    const Eigen::VectorXd a = r_half * f, b = r_whole * f;
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * b.cwiseAbs().maxCoeff()) << to_string(k);
  }
}

// R is the fluid's response, J P Jᵀ/(ρΔxΔy) away from the sides: symmetric, and positive
// semi-definite (P is an orthogonal projector), with a positive self-mobility.
TEST(MobilityTable, IsSymmetricAndPositiveAwayFromTheSides) {
  const fluid::MacGrid grid(40, 40, 0.4, 0.4);
  std::vector<Vec2> p;
  for (int k = 0; k < 20; ++k) p.push_back({0.2 + 0.05 * std::cos(0.3 * k), 0.2 + 0.07 * std::sin(0.3 * k)});
  const MobilityMatrix m({grid, fluid::Boundaries::all(BoundaryType::no_slip), Kernel::bilinear, false});
  Eigen::MatrixXd r;
  m.assemble(p, {}, 1000.0, {}, r);
  EXPECT_LT((r - r.transpose()).cwiseAbs().maxCoeff(), 1e-12 * r.cwiseAbs().maxCoeff());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (r + r.transpose()));
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * eig.eigenvalues().maxCoeff());
  for (Eigen::Index i = 0; i < r.rows(); ++i) EXPECT_GT(r(i, i), 0.0);
}

// Rows for a subset of markers are those rows of the whole matrix; masked (target) points have
// zero rows and columns.
TEST(MobilityTable, RowSubsetsAndMasksSelectFromTheWholeMatrix) {
  const fluid::MacGrid grid(30, 30, 0.3, 0.3);
  const std::vector<Vec2> p = markers(grid, 9, 21);
  const MobilityMatrix m({grid, fluid::Boundaries::all(BoundaryType::free_slip), Kernel::bilinear, false});
  Eigen::MatrixXd all, some, masked;
  m.assemble(p, {}, 1000.0, {}, all);
  const std::vector<int> rows{4, 1, 7};
  m.assemble(p, {}, 1000.0, rows, some);
  for (std::size_t k = 0; k < rows.size(); ++k)
    EXPECT_LT((some.middleRows(2 * static_cast<Eigen::Index>(k), 2) - all.middleRows(2 * rows[k], 2))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12 * all.cwiseAbs().maxCoeff());
  std::vector<char> mask(p.size(), 0);
  mask[3] = 1;
  m.assemble(p, mask, 1000.0, {}, masked);
  EXPECT_EQ(masked.middleRows(6, 2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(masked.middleCols(6, 2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((masked.topLeftCorner(6, 6) - all.topLeftCorner(6, 6)).cwiseAbs().maxCoeff(), 1e-12 * all.norm());
}


// The rows of R built on a pool's threads are those built on one, bit for bit (each entry is
// computed alike; the entries copied by symmetry after all rows): periodic seams, walls, masks,
// row subsets.
TEST(MobilityTable, ThreadsBuildTheSameMatrixBitForBit) {
  const fluid::MacGrid grid(32, 24, 0.32, 0.24);
  const std::vector<Vec2> p = markers(grid, 40, 5);
  fluid::Boundaries sides = fluid::Boundaries::all(BoundaryType::no_slip);
  sides.west.type = sides.east.type = BoundaryType::periodic;
  std::vector<char> mask(p.size(), 0);
  mask[7] = mask[19] = 1;
  const std::vector<int> rows{0, 3, 7, 12, 19, 25, 31, 39};
  WorkerPool pool(2);
  for (Kernel kernel : {Kernel::bilinear, Kernel::peskin4}) {
    const MobilityMatrix m({grid, sides, kernel, false});
    Eigen::MatrixXd serial, threaded;
    for (std::span<const int> some : {std::span<const int>{}, std::span<const int>(rows)}) {
      m.assemble(p, mask, 1000.0, some, serial);
      m.assemble(p, mask, 1000.0, some, threaded, &pool);
      ASSERT_EQ(serial.rows(), threaded.rows());
      EXPECT_TRUE((serial.array() == threaded.array()).all());
      EXPECT_GT(serial.cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

// Target points (pinned, tethered to markers) have identity rows in M = I − Δt² R K: only the
// moving unknowns' block is factored, and the preconditioner stays exact: one GMRES iteration per
// step, and the same steps as plain GMRES within its tolerance.
TEST(MarkerSpaceSolve, TargetPointsLeaveThePreconditionerExact) {
  // A ring of 12 markers under tension (rest lengths 0.8 of their spacing), every third one
  // tethered to a target point 5 mm outward, pinned or moving east at 0.2 m/s (whose known
  // increments enter the moving unknowns' equations); 32² cells, FFT pressure.
  auto run = [](Preconditioner preconditioner, std::vector<int>& iterations) {
    const fluid::MacGrid grid(32, 32, 0.32, 0.32);
    fluid::FluidSettings fs;
    fs.pressure_solver = "fft";
    auto fluid = fluid::make_fluid_solver("eulerian", grid, fs);
    elastic::Body body;
    const int n = 12;
    std::vector<Vec2> x;
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * std::numbers::pi * k / n;
      x.push_back({0.16 + 0.05 * std::cos(a), 0.16 + 0.04 * std::sin(a)});
      body.add_point(x.back(), 1.0);
    }
    for (int k = 0; k < n; ++k) body.add_linear_spring(k, (k + 1) % n, 50.0, 0.8 * norm(x[(k + 1) % n] - x[k]));
    for (int k = 0; k < n; k += 3) {
      const Vec2 anchor = x[k] + 0.1 * (x[k] - Vec2{0.16, 0.16});
      const int target = k % 2 == 0 ? body.add_point(anchor, 1.0, elastic::PointKind::Pinned)
                                    : body.add_prescribed_point([anchor](double t) {
                                        return elastic::PrescribedState{anchor + Vec2{0.2 * t, 0.0}, {0.2, 0.0}, {}};
                                      });
      body.add_linear_spring(k, target, 500.0, 0.0);
    }
    CouplingSettings settings;
    settings.preconditioner = preconditioner;
    settings.krylov_tolerance = 1e-10;
    ImmersedBoundary ib(*fluid, body, settings);
    for (int step = 0; step < 8; ++step) iterations.push_back(ib.step(0.01).krylov.iterations);
    return body.points.position;
  };
  std::vector<int> preconditioned, plain;
  const std::vector<Vec2> a = run(Preconditioner::mobility, preconditioned);
  const std::vector<Vec2> b = run(Preconditioner::none, plain);
  for (int it : preconditioned) EXPECT_EQ(it, 1);
  double largest = 0.0;
  for (std::size_t p = 0; p < a.size(); ++p) largest = std::max(largest, norm(a[p] - b[p]));
  EXPECT_GT(norm(a[0] - Vec2{0.21, 0.16}), 1e-4);  // the ring moved
  EXPECT_LT(largest, 1e-12);
}

}  // namespace
}  // namespace jellysim::coupling
