// The 3D pressure solvers and the projection: exact FFT solves, agreement with conjugate gradients,
// a divergence-free velocity after every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/fluid3d/fluid_solver_3d.hpp"
#include "jellysim/fluid3d/pressure_3d.hpp"

namespace jellysim::fluid3d {
namespace {

struct Case {
  const char* name;
  Boundaries3d b;
};

std::vector<Case> boundary_cases() {
  return {{"closed-box", Boundaries3d::closed_box()},
          {"periodic-box", Boundaries3d::periodic_box()},
          {"duct-along-x", Boundaries3d::duct(0)},
          {"duct-along-z", Boundaries3d::duct(2)},
          {"lid-driven-cavity", Boundaries3d::lid_driven_cavity(1.0)}};
}

Field3d random_cell_field(const Grid3d& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Field3d f(g.padded_size(), 0.0);
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i) f[g.index(i, j, k)] = uniform(rng);
  return f;
}

// max |b − mean(b) − ∇²p| over the cells, relative to max|b|.
double relative_residual(const Grid3d& g, const Field3d& b, const Field3d& p) {
  const double mean = interior_mean(g, b);
  double r = 0.0, bmax = 0.0;
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i) {
        r = std::max(r, std::abs(b[g.index(i, j, k)] - mean - centre_laplacian(g, p, i, j, k)));
        bmax = std::max(bmax, std::abs(b[g.index(i, j, k)]));
      }
  return r / bmax;
}

// An anisotropic grid with odd, even and non-power-of-two counts.
const Grid3d kGrid({12, 9, 10}, {1.2, 0.7, 1.0});

TEST(FftPressure3d, SolvesTheSevenPointProblemToRoundOffOnEveryBoundaryMix) {
  for (const Case& c : boundary_cases()) {
    const Field3d b = random_cell_field(kGrid, 7);
    Field3d p(kGrid.padded_size(), 0.0);
    make_pressure_solver_3d("fft", kGrid, c.b)->solve(b, p);
    const double residual = relative_residual(kGrid, b, p);
    std::printf("  %s: fft residual %.2e, mean %.1e\n", c.name, residual, interior_mean(kGrid, p));
    EXPECT_LT(residual, 1e-13) << c.name;  // measured 2e-15 .. 5e-15
    EXPECT_LT(std::abs(interior_mean(kGrid, p)), 1e-15) << c.name;
  }
}

// max |p − q| / max |p| over the interior cells.
double relative_difference(const Grid3d& g, const Field3d& p, const Field3d& q) {
  double diff = 0.0, scale = 0.0;
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i) {
        diff = std::max(diff, std::abs(p[g.index(i, j, k)] - q[g.index(i, j, k)]));
        scale = std::max(scale, std::abs(p[g.index(i, j, k)]));
      }
  return diff / scale;
}

// The iterative solvers at a 1e-13 relative residual against the exact FFT solve; the multigrid
// grid has even counts (16 × 24 × 8 → 8 × 12 × 4 → 4 × 6 × 2) and cubic cells (the point smoother
// slows down on stretched cells: 28–33 cycles at aspect ratio 2.1).
TEST(FftPressure3d, AgreesWithMultigridAndConjugateGradients) {
  const Grid3d even({16, 24, 8}, {1.0, 1.5, 0.5});
  for (const Case& c : boundary_cases())
    for (const char* name : {"multigrid", "cg"}) {
      const Grid3d& g = std::string(name) == "cg" ? kGrid : even;
      const Field3d b = random_cell_field(g, 11);
      Field3d p_fft(g.padded_size(), 0.0), p(g.padded_size(), 0.0);
      make_pressure_solver_3d("fft", g, c.b)->solve(b, p_fft);
      PressureSettings3d s;
      s.relative_tolerance = 1e-13;
      const PressureReport3d report = make_pressure_solver_3d(name, g, c.b, s)->solve(b, p);
      const double diff = relative_difference(g, p_fft, p);
      std::printf("  %s: |fft - %s| / max|p| = %.2e after %d iterations\n", c.name, name, diff, report.iterations);
      EXPECT_LT(diff, 3e-13) << c.name << ", " << name;  // measured 9e-15 .. 1.2e-13
      if (std::string(name) == "multigrid") {
        EXPECT_LE(report.iterations, 16) << c.name;  // measured 12–16: about 0.15 per V(2,2) cycle
      }
    }
}

// Repeated solves, another instance, and two threads (the transforms' fixed chunks as the pool's
// tasks): the same bits.
TEST(FftPressure3d, RepeatedAndThreadedSolvesGiveTheSameBits) {
  const Grid3d g({16, 20, 24}, {1.0, 1.25, 1.5});
  const Field3d b = random_cell_field(g, 3);
  Field3d p1(g.padded_size(), 0.0), p2(g.padded_size(), 0.0), p3(g.padded_size(), 0.0);
  make_pressure_solver_3d("fft", g, Boundaries3d::duct(2))->solve(b, p1);
  auto solver = make_pressure_solver_3d("fft", g, Boundaries3d::duct(2));
  solver->solve(b, p2);
  solver->solve(b, p2);
  EXPECT_EQ(p1, p2);
  WorkerPool pool(2);
  make_pressure_solver_3d("fft", g, Boundaries3d::duct(2), {}, &pool)->solve(b, p3);
  EXPECT_EQ(p1, p3);
}

// A random velocity (walls and periodic faces as the boundaries say) and one step: the projected
// velocity is divergence-free to round-off with either pressure solver.
TEST(Projection3d, LeavesTheVelocityDivergenceFreeToRoundOff) {
  for (const Case& c : boundary_cases())
    for (const char* pressure : {"fft", "multigrid", "cg"}) {
      FluidSettings3d s;
      s.boundaries = c.b;
      s.viscosity_m2_per_s = 1e-3;
      s.pressure_solver = pressure;
      s.pressure.relative_tolerance = 1e-12;
      if (std::string(pressure) == "cg") s.method = FluidMethod3d::semi_lagrangian;  // the other predictor too
      auto solver = make_fluid_solver_3d(kGrid, s);
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> uniform(-1.0, 1.0);
      for (int comp = 0; comp < 3; ++comp)
        set_component(kGrid, c.b, solver->mutable_state().velocity, comp,
                      [&](double, double, double) { return uniform(rng); });
      const double before = max_divergence(kGrid, solver->state().velocity);
      solver->step(0.5 * solver->stable_time_step());
      const double after = max_divergence(kGrid, solver->state().velocity);
      std::printf("  %s, %s: max|div u| %.2e -> %.2e 1/s\n", c.name, pressure, before, after);
      EXPECT_GT(before, 1.0);
      EXPECT_LT(after, 1e-11 * before) << c.name << ", " << pressure;
    }
}

TEST(Fluid3dMemory, EstimateGrowsWithTheGridAndIsRefusedAboveTheBudget) {
  const Grid3d swimmer({48, 96, 48}, {0.24, 0.48, 0.24});
  const std::uint64_t bytes = estimated_memory_bytes_3d(swimmer, {});
  std::printf("  48 x 96 x 48: %.1f MiB estimated\n", static_cast<double>(bytes) / (1024.0 * 1024.0));
  // 15 padded fields of 53 × 101 × 53 doubles and the FFT's two 48 × 96 × 48 buffers.
  EXPECT_EQ(bytes, (15ull * 53 * 101 * 53 + 2ull * 48 * 96 * 48) * 8);
  EXPECT_THROW(make_fluid_solver_3d(Grid3d({2000, 2000, 2000}, {1.0, 1.0, 1.0}), {}), InputError);
}

}  // namespace
}  // namespace jellysim::fluid3d
