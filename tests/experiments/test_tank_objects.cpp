// A tank with more than one thing in it (beyond the thesis): several jellyfish, rigid obstacles
// held by the immersed boundary, and currents. Measured figures are in docs/scenes.md.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/jellyfish/obstacle.hpp"
#include "jellyfish_test_util.hpp"

namespace jellysim::experiments {
namespace {

config::Config scene(const std::string& overlay) { return testing::scene_with(overlay); }

Vec2 centroid(const std::vector<Vec2>& p) {
  Vec2 c{};
  for (Vec2 q : p) c += q;
  return (1.0 / static_cast<double>(p.size())) * c;
}

// Two identical jellyfish placed as mirror images about the tank's centre line push water at each
// other; whatever they do, they do it symmetrically: over two cycles their centroids stay mirror
// images (x) and level (y) to round-off (measured 3.2e-13 and 2.3e-13 m; allowed 3e-12 m), while
// each moves forward. This is the solver's own symmetry (tank.symmetry = "none").
TEST(Tank, TwoJellyfishSideBySideMoveSymmetrically) {
  const jellyfish::SwimSettings s = read_swim_settings(scene(R"(
duration = 2.857142857142857
tank.symmetry = "none"
[jellyfish]
position = [0.34, 0.3]
[[objects]]
type = "jellyfish"
position = [0.46, 0.3]
)"));
  ASSERT_EQ(s.school.size(), 2u);
  jellyfish::SwimSimulation sim(s);
  const double axis = 0.5 * s.tank.width_m;
  const Vec2 left0 = centroid(sim.jellyfish(0).umbrella_points()), right0 = centroid(sim.jellyfish(1).umbrella_points());
  double worst_x = 0.0, worst_y = 0.0;
  const jellyfish::SwimRunStats stats = sim.run([&](const jellyfish::SwimSimulation& state) -> std::string {
    const Vec2 l = centroid(state.jellyfish(0).umbrella_points()), r = centroid(state.jellyfish(1).umbrella_points());
    worst_x = std::max(worst_x, std::abs((l.x - axis) + (r.x - axis)));
    worst_y = std::max(worst_y, std::abs(l.y - r.y));
    return {};
  });
  ASSERT_TRUE(stats.failure.empty()) << stats.failure;
  const Vec2 left = centroid(sim.jellyfish(0).umbrella_points()), right = centroid(sim.jellyfish(1).umbrella_points());
  EXPECT_LT(worst_x, 3e-12);
  EXPECT_LT(worst_y, 3e-12);
  EXPECT_GT(left.y - left0.y, 0.005) << "each swims forward";
  const double separation_change = (right.x - left.x) - (right0.x - left0.x);
  std::printf("separation change over two cycles: %.3g m; mirror mismatch x %.3g m, y %.3g m\n", separation_change,
              worst_x, worst_y);
}

// One copy of the state: every jellyfish reads and actuates its markers in the world's body, so
// what the coupling moves is what the jellyfish sees, and dragging one moves only its markers.
TEST(Tank, TheSchoolLivesInTheWorldsBody) {
  const jellyfish::SwimSettings s = read_swim_settings(scene(R"(
[jellyfish]
position = [0.3, 0.3]
[[objects]]
type = "jellyfish"
position = [0.5, 0.3]
phase = 0.25
)"));
  jellyfish::SwimSimulation sim(s);
  ASSERT_EQ(sim.jellyfish_count(), 2u);
  const jellyfish::Jellyfish& a = sim.jellyfish(0);
  const jellyfish::Jellyfish& b = sim.jellyfish(1);
  EXPECT_EQ(&a.body(), &sim.body());
  EXPECT_EQ(&b.body(), &sim.body());
  EXPECT_EQ(b.first_point(), a.point_count());
  EXPECT_EQ(b.first_linear_spring(), a.linear_spring_count());
  EXPECT_EQ(a.point_count() + b.point_count(), sim.body().points.size());
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(sim.step().failure.empty());
  // The umbrella the jellyfish reports is the world's markers after the steps.
  const std::vector<Vec2> umbrella = b.umbrella_points();
  for (std::size_t k = 0; k < umbrella.size(); ++k)
    EXPECT_EQ(umbrella[k], sim.body().points.position[static_cast<std::size_t>(b.layout().umbrella[k])]);
  // Its muscles were actuated in the world's body (phase 0.25: contracting, shorter than at rest).
  const auto muscle = static_cast<std::size_t>(b.layout().muscle_springs.back());
  EXPECT_LT(sim.body().linear.rest_length[muscle], b.layout().muscle_uncontracted_m.back());
  const std::vector<Vec2> before = sim.body().points.position;
  sim.move_jellyfish(1, {0.01, 0.0});
  for (std::size_t p = 0; p < before.size(); ++p)
    EXPECT_EQ(sim.body().points.position[p].x, before[p].x + (p >= b.first_point() ? 0.01 : 0.0));
}

// scenes/two-jellyfish.toml: two bells half a cycle apart each keep swimming upward. In the thesis's
// coarse tank (3 cells per bell) the second turned 90 degrees within 2 s, and so does a lone bell
// placed off the centre line there: the grid, not the neighbour. Measured on the resolved tank
// over three cycles: largest tilts 8.2 and 4.5 degrees, distances 3.8 and 8.1 cm (the later one
// swims into the water its neighbour set moving).
TEST(SlowTank, TwoJellyfishKeepTheirHeadingOverThreeCycles) {
  config::Config c = scene::builtin_jellyfish_scene();
  c.merge(config::Config::load(std::string(JELLYSIM_SOURCE_DIR) + "/scenes/two-jellyfish.toml"));
  c.set("tank.tracers_per_side=0");
  c.set("duration=4.285714285714286");  // three cycles at 0.7 Hz
  jellyfish::SwimSimulation sim(read_swim_settings(c));
  ASSERT_EQ(sim.jellyfish_count(), 2u);
  const Vec2 start[2] = {centroid(sim.jellyfish(0).umbrella_points()), centroid(sim.jellyfish(1).umbrella_points())};
  double worst_tilt_deg[2] = {0.0, 0.0};
  const jellyfish::SwimRunStats stats = sim.run([&](const jellyfish::SwimSimulation& state) -> std::string {
    for (std::size_t j = 0; j < 2; ++j) {
      const Vec2 h = state.jellyfish(j).heading();
      worst_tilt_deg[j] = std::max(worst_tilt_deg[j], std::abs(std::atan2(h.x, h.y)) * 180.0 / std::numbers::pi);
    }
    return {};
  });
  ASSERT_TRUE(stats.failure.empty()) << stats.failure;
  for (std::size_t j = 0; j < 2; ++j) {
    const double forward = centroid(sim.jellyfish(j).umbrella_points()).y - start[j].y;
    std::printf("jellyfish %zu: largest tilt %.2f degrees, swam %.2f cm\n", j + 1, worst_tilt_deg[j], 100.0 * forward);
    EXPECT_LT(worst_tilt_deg[j], 15.0) << "jellyfish " << j + 1;
    EXPECT_GT(forward, 0.02) << "jellyfish " << j + 1 << " swims forward";
  }
}

// Uniform flow from the west past a fixed cylinder (Re = U·D/ν ≈ 30): the fluid goes around it,
// the leakage through the outline is a small fraction of the flux the cylinder blocks (U·D), and
// the fluid's force on the cylinder is a drag pointing downstream.
TEST(Tank, FlowGoesAroundAFixedCircle) {
  const jellyfish::SwimSettings s = read_swim_settings(scene(R"(
duration = 2.0
[tank]
width = 0.4
height = 0.2
cells = [80, 40]
boundaries = ["inflow", "outflow", "free-slip", "free-slip"]
inflow_velocity = [0.01, 0.0]
current = [0.01, 0.0]
[jellyfish]
enabled = false
[[objects]]
type = "circle"
centre = [0.1, 0.1]
radius = 0.02
)"));
  ASSERT_TRUE(s.school.empty());
  ASSERT_EQ(s.obstacles.size(), 1u);
  jellyfish::SwimSimulation sim(s);
  const jellyfish::SwimRunStats stats = sim.run({});
  ASSERT_TRUE(stats.failure.empty()) << stats.failure;
  const double blocked_flux = 0.01 * 0.04;  // U·D, m²/s
  const double leak = sim.obstacle_leakage(0);
  const Vec2 force = sim.obstacle_force(0);
  std::printf("leakage %.3g of U·D; force (%.3g, %.3g) N/m\n", leak / blocked_flux, force.x, force.y);
  EXPECT_LT(leak, 0.05 * blocked_flux);
  EXPECT_GT(force.x, 0.0) << "drag points downstream";
  EXPECT_LT(std::abs(force.y), 0.2 * force.x) << "a symmetric body in a symmetric flow has little lift";
  // Order of magnitude: the drag coefficient F/(½ρU²D) of a cylinder at Re ≈ 30 is about 2; the
  // coarse grid and the walls 2.5 diameters away raise it, but not tenfold.
  const double cd = force.x / (0.5 * 1000.0 * 0.01 * 0.01 * 0.04);
  EXPECT_GT(cd, 0.5);
  EXPECT_LT(cd, 20.0);
}

// A jellyfish in a uniform current (periodic sides keep the flow uniform) drifts with it. With
// free-slip walls the problem is Galilean invariant, so after 1.5 s its centroid should have moved
// downstream by U·t (its own swimming is along y). The semi-Lagrangian fluid keeps that within
// 3 % (we allow 10 %); the Eulerian solver, whose advection at 3 cells per bell and a cell Reynolds
// number of 20 is far from invariant, overshoots by 34 % (we allow 40 %; docs/scenes.md).
double drift_in_current(const std::string& solver) {
  const jellyfish::SwimSettings s = read_swim_settings(scene(R"(
duration = 1.5
[tank]
solver = ")" + solver + R"("
boundaries = ["periodic", "periodic", "free-slip", "free-slip"]
current = [0.02, 0.0]
)"));
  jellyfish::SwimSimulation sim(s);
  const Vec2 start = centroid(sim.jellyfish().umbrella_points());
  const jellyfish::SwimRunStats stats = sim.run({});
  EXPECT_TRUE(stats.failure.empty()) << stats.failure;
  const Vec2 drift = centroid(sim.jellyfish().umbrella_points()) - start;
  std::printf("%s: drift (%.4g, %.4g) m; U t = %.4g m\n", solver.c_str(), drift.x, drift.y, 0.02 * 1.5);
  return drift.x;
}

TEST(Tank, JellyfishDriftsWithAUniformCurrent) {
  const double carried = 0.02 * 1.5;
  EXPECT_NEAR(drift_in_current("semi-lagrangian"), carried, 0.10 * carried);
  EXPECT_NEAR(drift_in_current("eulerian"), carried, 0.40 * carried);
}

// A moving obstacle follows its prescribed path, and the fluid moves with it.
TEST(Tank, MovingObstacleFollowsItsPath) {
  const jellyfish::SwimSettings s = read_swim_settings(scene(R"(
duration = 1.0
[jellyfish]
enabled = false
[[objects]]
type = "box"
centre = [0.3, 0.4]
size = [0.06, 0.04]
velocity = [0.03, 0.0]
)"));
  jellyfish::SwimSimulation sim(s);
  const Vec2 start = centroid(sim.obstacle_outline(0));
  const jellyfish::SwimRunStats stats = sim.run({});
  ASSERT_TRUE(stats.failure.empty()) << stats.failure;
  const Vec2 moved = centroid(sim.obstacle_outline(0)) - start;
  EXPECT_NEAR(moved.x, 0.03, 0.002);
  EXPECT_NEAR(moved.y, 0.0, 0.002);
  // The fluid just ahead of the box is pushed along.
  const fluid::Velocity& u = sim.flow().velocity;
  EXPECT_GT(u.u.sample(Vec2{0.3 + 0.03 + 0.04, 0.4}), 0.005);
}

// Steering (beyond the thesis, §9.2.2): with a target ahead on its left (bearing 72°) the default
// jellyfish turns by tens of degrees within four cycles (measured: 86°), while the same jellyfish
// unsteered keeps its heading exactly (measured: 0°: a centred bell keeps the mirror symmetry, on
// half the tank; without it the wake's symmetry starts to break near five cycles).
TEST(SlowTank, SteeredJellyfishTurnsTowardItsTarget) {
  auto heading_after_four_cycles = [](bool steer) {
    const jellyfish::SwimSettings s = read_swim_settings(scene(std::string(R"(
duration = 5.714285714285714
[jellyfish]
steer_target = [0.1, 0.4]
steering = )") + (steer ? "true" : "false")));
    jellyfish::SwimSimulation sim(s);
    const jellyfish::SwimRunStats stats = sim.run({});
    EXPECT_TRUE(stats.failure.empty()) << stats.failure;
    const Vec2 h = sim.jellyfish().heading();
    return std::atan2(-h.x, h.y) * 180.0 / 3.141592653589793;  // from +y, counter-clockwise
  };
  const double steered = heading_after_four_cycles(true), free = heading_after_four_cycles(false);
  std::printf("heading after four cycles: steered %.3g deg, not steered %.3g deg\n", steered, free);
  EXPECT_GT(steered, 40.0);
  EXPECT_LT(steered, 110.0);
  EXPECT_LT(std::abs(free), 1e-9);
}

void expect_rejected(const std::string& overlay, const std::string& words) {
  try {
    read_swim_settings(scene(overlay));
    ADD_FAILURE() << "accepted: " << overlay;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

// An obstacle's tethers are a stiffness per metre of outline (issue 33): at marker spacings ds and
// ds/2 the tethers of a circle add up to the same 2π r k (so it gives the same under a load), each
// marker's the outline it stands for; `stiffness` keeps IB2d's per-marker constant.
TEST(Tank, ObstacleTethersAreAStiffnessPerUnitLengthOfOutline) {
  jellyfish::ObstacleSpec circle;
  circle.centre_m = {0.1, 0.1};
  circle.radius_m = 0.02;
  double total[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    elastic::Body body;
    const jellyfish::ObstacleParts parts = jellyfish::add_obstacle(circle, k == 0 ? 0.00125 : 0.000625, body);
    for (int t : parts.tethers) total[k] += body.linear.stiffness[static_cast<std::size_t>(t)];
  }
  const double expected = circle.tether_stiffness_n_per_m2 * 2.0 * std::numbers::pi * circle.radius_m;
  EXPECT_NEAR(total[0] / expected, 1.0, 2e-4);  // the chords' length against the circle's: (1 − (π/n)²/6)
  EXPECT_NEAR(total[1] / expected, 1.0, 1e-4);
  circle.tether_stiffness_n_per_m = 50.0;
  elastic::Body body;
  const jellyfish::ObstacleParts parts = jellyfish::add_obstacle(circle, 0.00125, body);
  EXPECT_EQ(body.linear.stiffness[static_cast<std::size_t>(parts.tethers.front())], 50.0);
}

TEST(Tank, BadScenesAreRejectedWithAClearMessage) {
  // Overlapping bodies.
  expect_rejected(R"(
[[objects]]
type = "circle"
centre = [0.4, 0.31]
radius = 0.01
)",
                  "jellyfish 1 and objects[0] (circle) overlap");
  expect_rejected(R"(
[[objects]]
type = "jellyfish"
position = [0.41, 0.3]
)",
                  "jellyfish 1 and jellyfish 2 overlap");
  // Outside the domain.
  expect_rejected(R"(
[[objects]]
type = "box"
centre = [0.79, 0.5]
size = [0.1, 0.1]
)",
                  "objects[0] (box) reaches outside the tank");
  expect_rejected(R"(
[jellyfish]
position = [0.4, 0.79]
)",
                  "jellyfish 1 reaches outside the tank");
  // Two tether stiffnesses.
  expect_rejected(R"(
[[objects]]
type = "circle"
centre = [0.2, 0.6]
radius = 0.01
stiffness = 50.0
tether_stiffness = 40000.0
)",
                  "objects[0] (circle): give either 'tether_stiffness'");
  // Unknown object types and fields.
  expect_rejected(R"(
[[objects]]
type = "octopus"
)",
                  "objects[0]");
  expect_rejected(R"(
[[objects]]
type = "circle"
centre = [0.2, 0.6]
radius = 0.02
colour = "red"
)",
                  "unknown field 'colour'");
  expect_rejected(R"(
[[objects]]
type = "circle"
centre = [0.2, 0.6]
)",
                  "missing field 'radius'");
  expect_rejected(R"(
[[objects]]
type = "polygon"
points = [0.1, 0.6, 0.2, 0.7, 0.1, 0.7, 0.2, 0.6]
)",
                  "self-intersecting");
  expect_rejected(R"(
[[objects]]
type = "jellyfish"
position = [0.2, 0.6]
frequency = -1.0
)",
                  "objects[0] (jellyfish)");
}

}  // namespace
}  // namespace jellysim::experiments
