// Whole particle-fluid scenes (thesis §5.1.3, §5.3, §8.1.1-8.1.2): a fluid at rest between mirrored
// walls, momentum of the coupled fluid–body system, every integrator, determinism, eq. 5.31, and the
// bar against a static floor.
#include "jellysim/elastic/bar.hpp"
#include "jellysim/sph/bodies.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/scene.hpp"
#include "sph_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace jellysim::sph {
namespace {

RunSettings settings(const std::string& integrator, double duration, bool adaptive = true) {
  RunSettings s;
  s.time.integrator = integrator;
  s.time.dt = 1e-3;
  s.time.adaptive = adaptive;
  s.time.tolerances.atol = 1e-4;
  s.time.tolerances.rtol = 1e-3;
  s.time.duration = duration;
  s.time.frame_interval = duration / 4.0;
  return s;
}

/// A crystalline fluid filling the box [0, width] × [0, height]: triangular packing, mass from
/// bisection, then relaxed to its packing of least force (the mirrored walls do not continue the
/// triangular lattice, so the plain lattice starts with a small jolt near the walls).
Scene fluid_box(double width, double height) {
  Scene s;
  s.sph = {0.05, 2000.0, 40.0, 8.9e-3};
  s.walls = box_walls({0.0, 0.0}, {width, height});
  s.position = triangular_lattice({0.0, 0.0}, {width, height}, 0.043);
  const MassSearch m = find_particle_mass(s.position, width * height, s.sph, s.walls, 1e-8);
  s.velocity.assign(s.position.size(), Vec2{});
  s.mass.assign(s.position.size(), m.mass_kg);
  s.fluid_count = s.position.size();
  const double before = relax(s.position, s.mass, s.sph, s.walls, 0);
  const double after = relax(s.position, s.mass, s.sph, s.walls, 3000);
  EXPECT_LT(after, 0.1 * before);
  return s;
}

/// Σ m_i / ρ_i: the area the fluid occupies (m²).
double fluid_volume(const SphFluid& fluid, const Scene& s) {
  double v = 0.0;
  for (std::size_t i = 0; i < s.fluid_count; ++i) v += s.mass[i] / fluid.density()[i];
  return v;
}

double max_speed(const Scene& s) {
  double v = 0.0;
  for (Vec2 u : s.velocity) v = std::max(v, norm(u));
  return v;
}

TEST(SphScene, FluidAtRestBetweenMirroredWallsStaysAtRestAndKeepsItsVolume) {
  const double a = 0.043, width = 14 * a, height = (10 * std::sqrt(3.0) / 2.0 + 1.0) * a;  // the lattice fits
  Scene s = fluid_box(width, height);
  SphFluid probe(s.sph, s.walls);
  std::vector<double> volume, speed;
  bool inside = true;
  RunSettings rs = settings("dopri5", 3.0);
  rs.time.tolerances.atol = rs.time.tolerances.rtol = 1e-7;
  rs.time.frame_interval = 0.25;
  const RunResult r = run(s, rs, [&](double, const Scene& sc, const CoupledSystem&) {
    probe.compute_density(sc.position, sc.velocity, sc.mass);
    volume.push_back(fluid_volume(probe, sc));
    speed.push_back(max_speed(sc));
    for (Vec2 p : sc.position) inside = inside && p.x >= 0.0 && p.x <= width && p.y >= 0.0 && p.y <= height;
    return std::string();
  });
  ASSERT_FALSE(r.failed) << r.failure;
  const double sound_speed = std::sqrt(40.0);  // c² = dp/dρ = κ_p
  EXPECT_LT(*std::max_element(speed.begin(), speed.end()), 2e-3 * sound_speed) << "spurious flow";
  EXPECT_LT(*std::max_element(speed.end() - 4, speed.end()), 2e-4) << "flow does not die out";
  for (double v : volume) EXPECT_NEAR(v, volume.front(), 2e-3 * volume.front());
  const double mass_volume = static_cast<double>(s.fluid_count) * s.mass[0] / s.sph.rest_density;  // N m / ρ0
  EXPECT_NEAR(volume.front(), mass_volume, 0.01 * mass_volume);
  EXPECT_TRUE(inside);
}

TEST(SphScene, CoupledFluidAndWrigglingBodyConserveMomentum) {
  Scene s;
  s.sph = {0.05, 2000.0, 4.0, 8.9e-3};
  LarvaSpec spec;
  spec.centre = {0.0, 0.0};
  spec.frequency_hz = 2.0;
  Larva larva = make_larva(spec);
  s.body = larva.body;
  s.outline = larva.outline;
  s.muscles = larva.muscles;
  s.position = triangular_lattice({-0.4, -0.3}, {0.4, 0.3}, 0.043);
  std::erase_if(s.position, [&](Vec2 p) { return std::abs(p.x) < 0.22 && std::abs(p.y) < 0.045; });
  s.velocity.assign(s.position.size(), Vec2{0.05, -0.02});
  s.mass.assign(s.position.size(), 3.0);
  s.fluid_count = s.position.size();
  s.collision = {1e-6, 0.005};
  const Vec2 p0 = momentum(s);
  std::int64_t collisions = 0;
  const RunResult r = run(s, settings("dopri5", 0.5), [](double, const Scene&, const CoupledSystem&) { return std::string(); });
  ASSERT_FALSE(r.failed) << r.failure;
  collisions = r.collisions.edge_collisions;
  EXPECT_GT(collisions, 0);
  // Trapped particles are re-aimed (not momentum conserving), so compare only when none were.
  const Vec2 p1 = momentum(s);
  const double scale = 3.0 * static_cast<double>(s.position.size()) * 0.1;
  if (r.collisions.trapped == 0) {
    EXPECT_LT(norm(p1 - p0), 1e-9 * scale);
  }
  for (std::size_t i = 0; i < s.fluid_count; ++i) {
    EXPECT_FALSE(inside_outline(s.outline, s.body.points.position, s.position[i])) << "particle " << i;
  }
}

Scene small_larva_scene(int threads) {
  Scene s;
  s.sph = {0.05, 2000.0, 40.0, 8.9e-3};
  s.walls = box_walls({0.0, 0.0}, {0.6, 0.4});
  LarvaSpec spec;
  spec.centre = {0.3, 0.2};
  spec.length_m = 0.3;
  spec.segments = 6;
  Larva larva = make_larva(spec);
  s.body = larva.body;
  s.outline = larva.outline;
  s.muscles = larva.muscles;
  s.position = triangular_lattice({0.0, 0.0}, {0.6, 0.4}, 0.043);
  std::erase_if(s.position, [&](Vec2 p) { return std::abs(p.x - 0.3) < 0.17 && std::abs(p.y - 0.2) < 0.045; });
  s.velocity.assign(s.position.size(), Vec2{});
  s.mass.assign(s.position.size(), 3.3);
  s.fluid_count = s.position.size();
  s.collision = {1e-6, 0.005};
  s.threads = threads;
  return s;
}

TEST(SphScene, EveryIntegratorRunsTheLarvaScene) {
  for (const std::string& name : ode::integrator_names()) {
    for (const char* control : {"embedded", "step-doubling"}) {
      // Backward Euler (Jacobian-free Newton–Krylov) has no embedded pair: step doubling either way.
      if (name == "backward-euler" && std::string(control) == "embedded") continue;
      Scene s = small_larva_scene(1);
      RunSettings rs = settings(name, 0.1);
      rs.error_control = control;
      const RunResult r = run(s, rs, [](double, const Scene&, const CoupledSystem&) { return std::string(); });
      EXPECT_FALSE(r.failed) << name << " " << control << ": " << r.failure;
      EXPECT_NEAR(r.statistics.simulated_seconds, 0.1, 1e-12);
      EXPECT_GT(r.statistics.steps, 0);
    }
  }
}

TEST(SphScene, OneTwoAndThreeThreadsGiveBitIdenticalStates) {
  for (const char* integrator : {"dopri5", "backward-euler"}) {
    std::vector<std::vector<Vec2>> states;
    for (int threads : {1, 2, 3}) {
      Scene s = small_larva_scene(threads);
      ASSERT_GE(s.fluid_count, 64u) << "too few particles for the parallel path";
      s.velocity.assign(s.position.size(), Vec2{0.03, -0.01});  // some motion, so every term matters
      RunSettings rs = settings(integrator, 0.02);
      rs.time.frame_interval = 0.02;
      const RunResult r = run(s, rs, [](double, const Scene&, const CoupledSystem&) { return std::string(); });
      ASSERT_FALSE(r.failed) << r.failure;
      ASSERT_GT(r.statistics.steps, 3);
      std::vector<Vec2> state = s.position;
      state.insert(state.end(), s.velocity.begin(), s.velocity.end());
      state.insert(state.end(), s.body.points.position.begin(), s.body.points.position.end());
      state.insert(state.end(), s.body.points.velocity.begin(), s.body.points.velocity.end());
      states.push_back(std::move(state));
    }
    EXPECT_EQ(states[0], states[1]) << integrator << ": 1 vs 2 threads";
    EXPECT_EQ(states[0], states[2]) << integrator << ": 1 vs 3 threads";
  }
}

// The coupled system forms a Runge–Kutta stage state inside its parallel evaluation (each thread its
// own particles, the last one the body): state and derivative are bit for bit those of forming
// y + h Σ w_j k_j with vector operations and evaluating there, for one, two and three threads.
TEST(SphScene, FusedStageStateAndDerivativeMatchTheVectorSumsBitForBit) {
  for (int threads : {1, 2, 3}) {
    Scene s = small_larva_scene(threads);
    s.velocity.assign(s.position.size(), Vec2{0.03, -0.01});
    const CoupledSystem system(s);
    const ode::Vector y = system.pack_state();
    std::vector<ode::Vector> k(3);
    system.derivative(0.0, y, k[0]);
    k[1] = 0.5 * k[0] + ode::Vector::Constant(y.size(), 0.25);
    k[2] = ode::Vector::Zero(y.size());  // a stage not computed yet: its zero weight must skip it
    const std::vector<double> w{0.3, -0.7, 0.0};
    const double h = 1.3e-3;
    ode::Vector expected_y = y, expected_f, fused_y, fused_f;
    for (std::size_t j = 0; j < w.size(); ++j)
      if (w[j] != 0.0) expected_y += (h * w[j]) * k[j];
    system.derivative(0.01, expected_y, expected_f);
    const auto before = system.evaluations();
    system.stage_derivative(0.01, y, h, w, k, fused_y, fused_f);
    EXPECT_EQ(system.evaluations(), before + 1);
    ASSERT_EQ(fused_y.size(), y.size());
    for (Eigen::Index e = 0; e < y.size(); ++e) {
      ASSERT_EQ(fused_y[e], expected_y[e]) << threads << " threads, entry " << e;
      ASSERT_EQ(fused_f[e], expected_f[e]) << threads << " threads, entry " << e;
    }
  }
}

TEST(SphScene, SameInputsGiveIdenticalResultsWithOneOrTwoThreads) {
  std::vector<Vec2> finals[3];
  for (int k = 0; k < 3; ++k) {
    Scene s = small_larva_scene(k == 2 ? 2 : 1);
    const RunResult r = run(s, settings("rk2", 0.3), [](double, const Scene&, const CoupledSystem&) { return std::string(); });
    ASSERT_FALSE(r.failed) << r.failure;
    finals[k] = s.position;
    finals[k].insert(finals[k].end(), s.body.points.position.begin(), s.body.points.position.end());
  }
  EXPECT_EQ(finals[0], finals[1]);
  EXPECT_EQ(finals[0], finals[2]);
}

TEST(SphScene, ThinBoundaryStepLimitOfEq531HoldsEveryStep) {
  // A point mass flying at 2 m/s towards a fixed strip 0.01 thick: Δt < w_b / (2 v) = 2.5e-3 s.
  Scene s;
  LarvaSpec spec;
  spec.centre = {0.0, 0.0};
  spec.height_m = 0.01;
  spec.contraction = 0.0;
  Larva larva = make_larva(spec);
  s.body = larva.body;
  for (auto& kind : s.body.points.kind) kind = elastic::PointKind::Pinned;
  s.outline = larva.outline;
  s.position = {{0.0, 0.5}};
  s.velocity = {{0.0, -2.0}};
  s.mass = {1.0};
  RunSettings rs = settings("dopri5", 0.5, false);
  rs.time.dt = 0.1;
  double t_last = 0.0, dt_max = 0.0;
  const RunResult r = run(s, rs, [](double, const Scene&, const CoupledSystem&) { return std::string(); },
                          [&](double t, double, std::int64_t) {
                            dt_max = std::max(dt_max, t - t_last);
                            t_last = t;
                          });
  EXPECT_DOUBLE_EQ(r.boundary_width_m, 0.01);
  EXPECT_LE(dt_max, 2.5e-3 * (1.0 + 1e-12));
  EXPECT_EQ(r.collisions.edge_collisions, 1);
  EXPECT_GT(s.position[0].y, 0.0);  // bounced back off the strip
  EXPECT_NEAR(s.velocity[0].y, 2.0, 1e-12);
  rs.thin_boundary_limit = false;  // without the limit, 0.1 s steps
  s.position = {{0.0, 0.5}};
  s.velocity = {{0.0, -2.0}};
  EXPECT_LT(run(s, rs, [](double, const Scene&, const CoupledSystem&) { return std::string(); }).statistics.steps, 10);
}

TEST(SphScene, BarSwingsOntoAStaticFloorWithoutPassingIt) {
  Scene s;
  s.body = elastic::make_bar(elastic::BarSpec{});
  s.outline = strip_outline(10);
  const double floor = -0.045 - 0.45;
  s.walls = {Wall{{0.0, floor}, {0.0, 1.0}, false}};
  double lowest = 0.0;
  RunSettings rs = settings("dopri5", 12.0, false);
  rs.time.dt = 0.01;
  rs.time.frame_interval = 0.05;
  const RunResult r = run(s, rs, [&](double, const Scene& sc, const CoupledSystem&) {
    for (Vec2 p : sc.body.points.position) lowest = std::min(lowest, p.y);
    return std::string();
  });
  ASSERT_FALSE(r.failed) << r.failure;
  EXPECT_GT(r.collisions.wall_collisions, 0);
  EXPECT_GE(lowest, floor);
  EXPECT_LT(lowest, floor + 0.01);  // it does reach the floor
}

}  // namespace
}  // namespace jellysim::sph
