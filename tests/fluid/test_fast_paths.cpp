// The optimised kernels of the semi-Lagrangian step against simple reference versions: row-wise
// advection against the point-wise back_trace()/Field::sample() advection, the pipelined
// red-black smoother against two plain half-sweeps, the implicit diffusion against its equation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "jellysim/fluid/fluid_solver.hpp"
#include "jellysim/fluid/multigrid.hpp"
#include "jellysim/fluid/projection.hpp"
#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid/semi_lagrangian.hpp"
#include "fluid_test_util.hpp"

namespace jellysim::fluid {
namespace {

using testing::Mix;
using testing::randomise;
std::vector<Mix> mixes() { return testing::boundary_mixes(); }

double max_difference(const Field& a, const Field& b) {
  double m = 0.0;
  for (int j = -1; j <= a.count_y(); ++j)
    for (int i = -1; i <= a.count_x(); ++i) m = std::max(m, std::abs(a(i, j) - b(i, j)));
  return m;
}

TEST(FastAdvection, EqualsThePointwiseReferenceToRoundOff) {
  // Odd cell counts, unequal spacings and an offset origin; Courant numbers from 0.3 (mostly the
  // unclamped interior path) to 40 (every point clamped, or wrapped by several periods).
  const MacGrid g(37, 23, 1.3, 0.9, {0.2, -0.4});
  for (const Mix& mix : mixes())
    for (double courant : {0.3, 1.0, 2.5, 40.0}) {
      Velocity src(g);
      randomise(src, 5);
      apply_velocity_boundaries(src, mix.b);
      const double dt = courant * std::min(g.dx(), g.dy());
      Velocity fast(g), reference(g);
      advect_velocity(src, mix.b, dt, fast);
      advect_velocity_reference(src, mix.b, dt, reference);
      // Positions are computed in cells rather than metres; their round-off grows with the
      // distance travelled (wrapped by fmod at large Courant numbers).
      const double tolerance = 1e-12 * std::max(1.0, courant / 4.0);
      EXPECT_LT(max_difference(fast.u, reference.u), tolerance) << mix.name << " courant " << courant;
      EXPECT_LT(max_difference(fast.v, reference.v), tolerance) << mix.name << " courant " << courant;
    }
}

TEST(FastAdvection, SmoothFieldOnALargeGridUsesTheInteriorPathAndMatches) {
  // 300 faces per row: several unclamped chunks per row, with clamped ones at both ends.
  const MacGrid g(300, 40, 3.0, 0.4);
  for (const Mix& mix : {mixes()[0], mixes()[4]}) {
    Velocity src(g);
    for (int j = 0; j < src.u.count_y(); ++j)
      for (int i = 0; i < src.u.count_x(); ++i) src.u(i, j) = std::sin(7.0 * i / 300.0) * std::cos(3.0 * j / 40.0);
    for (int j = 0; j < src.v.count_y(); ++j)
      for (int i = 0; i < src.v.count_x(); ++i) src.v(i, j) = 0.3 * std::cos(5.0 * i / 300.0);
    apply_velocity_boundaries(src, mix.b);
    Velocity fast(g), reference(g);
    advect_velocity(src, mix.b, 1.7 * g.dx(), fast);
    advect_velocity_reference(src, mix.b, 1.7 * g.dx(), reference);
    EXPECT_LT(max_difference(fast.u, reference.u), 1e-12) << mix.name;
    EXPECT_LT(max_difference(fast.v, reference.v), 1e-12) << mix.name;
  }
}

// Cells between two indices along a dimension of n cells, the short way round (periodic wrap).
int cells_apart(int a, int b, int n) {
  const int d = std::abs(a - b) % n;
  return std::min(d, n - d);
}

// The largest difference between two fields (NaN where one is NaN) over the points at least
// `margin` cells (either way round) from every point of `near` (interior and ghosts).
double max_difference_away_from(const Field& a, const Field& b, const std::vector<std::pair<int, int>>& near,
                                 int margin) {
  double m = 0.0;
  for (int j = -1; j <= a.count_y(); ++j)
    for (int i = -1; i <= a.count_x(); ++i) {
      bool far = true;
      for (const auto& [ni, nj] : near)
        far = far && (cells_apart(i, ni, a.count_x()) >= margin || cells_apart(j, nj, a.count_y()) >= margin);
      const double d = std::abs(a(i, j) - b(i, j));
      if (far && !(d <= m)) m = d;
    }
  return m;
}

// How many points (interior and ghosts) of two fields differ, NaN counting as different.
int points_that_differ(const Field& a, const Field& b) {
  int count = 0;
  for (int j = -1; j <= a.count_y(); ++j)
    for (int i = -1; i <= a.count_x(); ++i) count += a(i, j) == b(i, j) ? 0 : 1;
  return count;
}

TEST(FastAdvection, NonFiniteVelocityStaysInsideTheArrays) {
  // A NaN or infinite velocity must not turn into an out-of-range index (ASan checks the reads),
  // and its harm stays local: away from the two upset faces (three cells, past any departure point
  // at dt = 0.1 and its interpolation stencil), the result is the clean field's advection.
  const MacGrid g(16, 12, 1.0, 1.0);
  const std::vector<std::pair<int, int>> upset{{5, 5}, {7, 3}};
  for (const Mix& mix : mixes()) {
    Velocity clean(g);
    randomise(clean, 9);
    Velocity src = clean;
    src.u(5, 5) = std::numeric_limits<double>::quiet_NaN();
    src.v(7, 3) = std::numeric_limits<double>::infinity();
    apply_velocity_boundaries(clean, mix.b);
    apply_velocity_boundaries(src, mix.b);
    Velocity out(g), expected(g);
    advect_velocity(src, mix.b, 0.1, out);
    advect_velocity(clean, mix.b, 0.1, expected);
    EXPECT_LT(max_difference_away_from(out.u, expected.u, upset, 3), 1e-12) << mix.name;
    EXPECT_LT(max_difference_away_from(out.v, expected.v, upset, 3), 1e-12) << mix.name;
    EXPECT_GT(points_that_differ(out.u, expected.u) + points_that_differ(out.v, expected.v), 0) << mix.name;
  }
}

TEST(PipelinedSmoother, EqualsRedThenBlackHalfSweeps) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (const Mix& mix : mixes())
    for (int n : {2, 3, 8, 9}) {
      const int ny = n;
      const int nx = n % 2 == 0 ? 10 : 7;
      const PoissonOperator op(MacGrid(nx, ny, 1.0, 0.8), mix.b);
      std::vector<double> b(static_cast<std::size_t>(op.size())), p(b.size());
      for (double& x : b) x = d(rng);
      for (double& x : p) x = d(rng);
      std::vector<double> expected = p;
      for (int sweep = 0; sweep < 2; ++sweep)
        for (int colour = 0; colour < 2; ++colour)
          for (int j = 0; j < op.ny(); ++j)
            for (int i = (j + colour) % 2; i < op.nx(); i += 2) {
              const std::size_t k = static_cast<std::size_t>(j) * op.nx() + i;
              if (op.diagonal(i, j) != 0.0) expected[k] = (op.neighbour_sum(expected, i, j) - b[k]) / op.diagonal(i, j);
            }
      smooth_red_black(op, b, p, 2);
      double diff = 0.0;
      for (std::size_t k = 0; k < p.size(); ++k) diff = std::max(diff, std::abs(p[k] - expected[k]));
      EXPECT_LT(diff, 1e-12) << mix.name << " ny " << ny;
    }
}

TEST(ImplicitDiffusion, SolvesTheHelmholtzEquationOnTheInteriorFaces) {
  const MacGrid g(24, 18, 1.2, 0.9);
  const double nu_dt = 2e-3;
  for (const Mix& mix : mixes()) {
    Velocity before(g);
    randomise(before, 3);
    apply_velocity_boundaries(before, mix.b);
    Velocity after = before;
    ImplicitDiffusion diffusion(g);
    diffusion.solve(after, mix.b, nu_dt, 1e-12);
    // (I − νΔt∇²)u_new = u_old on every interior face, with u_new's boundary values.
    const double cx = nu_dt / (g.dx() * g.dx());
    const double cy = nu_dt / (g.dy() * g.dy());
    double worst = 0.0;
    auto check = [&](const Field& f, const Field& old, FaceRange r) {
      for (int j = r.j_begin; j < r.j_end; ++j)
        for (int i = r.i_begin; i < r.i_end; ++i) {
          const double lhs = (1.0 + 2.0 * cx + 2.0 * cy) * f(i, j) - cx * (f(i - 1, j) + f(i + 1, j)) -
                             cy * (f(i, j - 1) + f(i, j + 1));
          worst = std::max(worst, std::abs(lhs - old(i, j)));
        }
    };
    check(after.u, before.u, interior_u_faces(g, mix.b));
    check(after.v, before.v, interior_v_faces(g, mix.b));
    EXPECT_LT(worst, 1e-10) << mix.name;
  }
}

TEST(PressureGuess, ExtrapolationSavesCyclesAndGivesTheSameFlowToTheTolerance) {
  const TaylorGreen flow{6.283185307179586, 1.0, 1e-3};
  const MacGrid g(64, 64, flow.length_m, flow.length_m);
  std::vector<Velocity> results;
  std::vector<int> last_cycles;
  for (bool extrapolate : {false, true}) {
    FluidSettings f;
    f.viscosity_m2_per_s = flow.viscosity_m2_per_s;
    f.density_kg_per_m3 = 1000.0;  // the stored pressure is ρφ: the history test must see through it
    f.boundaries = Boundaries::all(BoundaryType::periodic);
    f.pressure.relative_tolerance = 1e-8;
    f.extrapolate_pressure_guess = extrapolate;
    auto solver = make_fluid_solver("semi-lagrangian", g, f);
    solver->state().velocity = flow.sample(g, 0.0);
    solver->apply_boundaries();
    StepReport r;
    for (int s = 0; s < 6; ++s) {
      r = solver->step(g.dx());
      EXPECT_TRUE(r.pressure.converged);
      EXPECT_LT(max_divergence(solver->state().velocity), 1e-6);
    }
    last_cycles.push_back(r.pressure.iterations);
    results.push_back(solver->state().velocity);
  }
  EXPECT_LT(last_cycles[1], last_cycles[0]);
  EXPECT_LT(max_difference(results[0].u, results[1].u), 1e-6);
  EXPECT_LT(max_difference(results[0].v, results[1].v), 1e-6);
}

TEST(PressureGuess, EditedPressureIsUsedAsItIs) {
  // After the caller overwrites the pressure, the next guess is that pressure, not an
  // extrapolation of older ones: a projection of a divergence-free field from the exact φ = 0
  // needs no cycle.
  const MacGrid g(32, 32, 1.0, 1.0);
  const Boundaries b = Boundaries::all(BoundaryType::no_slip);
  Projector projector(make_pressure_solver("multigrid"));
  projector.set_extrapolation(true);
  FlowState s(g);
  for (int k = 0; k < 3; ++k) {
    randomise(s.velocity, 20 + k);
    apply_velocity_boundaries(s.velocity, b);
    projector.project(s, b, 0.1, 1.0);
  }
  s.pressure.fill(0.0);
  s.velocity = Velocity(g);  // at rest: ∇·u = 0, φ = 0 solves it exactly
  EXPECT_EQ(projector.project(s, b, 0.1, 1.0).iterations, 0);
}

}  // namespace
}  // namespace jellysim::fluid
