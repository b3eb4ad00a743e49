// The ring jellyfish in axisymmetric water (issue 22, docs/jellyfish.md "Axisymmetric water"): the
// slice is the meridian of a body of revolution, every point a ring and every force a whole ring's.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//core/errors.hpp"
#include "jellysim/elastic/spring_assembly.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"

namespace jellysim::jellyfish {
namespace {

constexpr double kPi = std::numbers::pi;

JellyfishSpec ring_spec() {
  JellyfishSpec s;
  s.rings = true;
  return s;
}

// The conversion of make_rings, spring by spring against the planar slice built from the same spec:
// meridional springs and joints carry 2π r̄ (r̄ their mean distance from the axis, at least a quarter
// of the spacing), the muscles across the axis 2π (planar tension = hoop tension, radial pull 2π T),
// and only the ring jellyfish has hoop springs, one per umbrella ring off the axis.
TEST(RingJellyfish, SpringsCarryTheirRingsCircumference) {
  JellyfishSpec planar_spec = ring_spec();
  planar_spec.rings = false;
  const Jellyfish planar(planar_spec), ring(ring_spec());
  const elastic::Body &p = planar.body(), &r = ring.body();
  const double axis = ring.spec().aperture_centre_m.x;
  const std::size_t n = planar.layout().umbrella.size();
  ASSERT_EQ(r.points.size(), p.points.size());
  ASSERT_EQ(ring.layout().hoop_springs.size(), (n - 1) / 2);  // every umbrella ring but the apex
  ASSERT_EQ(r.linear.size(), p.linear.size() + ring.layout().hoop_springs.size());
  std::vector<char> muscle(p.linear.size(), 0);
  for (int m : planar.layout().muscle_springs) muscle[static_cast<std::size_t>(m)] = 1;
  const double spacing = norm(p.points.position[1] - p.points.position[0]);
  for (std::size_t s = 0; s < p.linear.size(); ++s) {
    const double mean_r = 0.5 * (std::abs(p.points.position[static_cast<std::size_t>(p.linear.i[s])].x - axis) +
                                 std::abs(p.points.position[static_cast<std::size_t>(p.linear.j[s])].x - axis));
    const double expected = muscle[s] ? 2.0 * kPi : 2.0 * kPi * std::max(mean_r, 0.25 * spacing);
    EXPECT_NEAR(r.linear.stiffness[s] / p.linear.stiffness[s], expected, 1e-12 * expected) << "spring " << s;
    EXPECT_EQ(r.linear.rest_length[s], p.linear.rest_length[s]) << "spring " << s;
  }
  for (std::size_t a = 0; a < p.angular.size(); ++a) {
    const auto at = [&](int q) { return std::abs(p.points.position[static_cast<std::size_t>(q)].x - axis); };
    const double mean_r = (at(p.angular.i[a]) + at(p.angular.j[a]) + at(p.angular.k[a])) / 3.0;
    const double expected = 2.0 * kPi * std::max(mean_r, 0.25 * spacing);
    EXPECT_NEAR(r.angular.stiffness[a] / p.angular.stiffness[a], expected, 1e-12 * expected) << "joint " << a;
  }
}

// The hoops hold the circumference: widen the bell by a factor 1 + ε about its axis. Each hoop
// spring of rest radius r₀ pulls its ring back with 2π C s ε (s the ring's meridional width, C = λϑ²
// the membrane stiffness of the umbrella springs), so the virtual work Σ F r₀ of the hoops is
// −C ε · 2π ∫ r ds = −C ε A, A the area of the umbrella's surface of revolution (Pappus, from a
// 16 385-point profile). The discrete sum (midpoint widths) is second order in the
// spacing: measured 0.033 % below A at the built-in spacing.
TEST(RingJellyfish, HoopsResistAWideningWithTheMembraneStiffnessOverTheBellsSurface) {
  Jellyfish ring(ring_spec());
  const JellyfishSpec& s = ring.spec();
  elastic::Body& b = ring.body();
  const double axis = s.aperture_centre_m.x, eps = 1e-3;
  std::vector<Vec2> x = b.points.position;
  std::vector<double> r0(x.size());
  for (std::size_t q = 0; q < x.size(); ++q) {
    r0[q] = x[q].x - axis;
    x[q].x = axis + (1.0 + eps) * r0[q];
  }
  elastic::Body hoops_only;
  for (std::size_t q = 0; q < x.size(); ++q) hoops_only.add_point(b.points.position[q], 1.0);
  for (int h : ring.layout().hoop_springs) {
    const auto k = static_cast<std::size_t>(h);
    hoops_only.add_linear_spring(b.linear.i[k], b.linear.j[k], b.linear.stiffness[k], b.linear.rest_length[k]);
  }
  std::vector<Vec2> f(x.size());
  elastic::add_spring_forces(hoops_only, x, f);
  double work = 0.0;
  for (std::size_t q = 0; q < x.size(); ++q)
    if (r0[q] > 0) work += f[q].x * r0[q];  // east points: each ring once (its force is the ring's)
  const std::vector<Vec2> fine = bell_profile(s.diameter_m, s.height_m, 8192);
  double area = 0.0;
  for (std::size_t k = 0; k + 1 < fine.size(); ++k)
    area += kPi * (std::abs(fine[k].x) + std::abs(fine[k + 1].x)) * norm(fine[k + 1] - fine[k]);
  area *= 0.5;  // the profile runs tip to tip: each ring twice
  const double c = s.bell_modulus_pa * s.thickness_m * s.thickness_m;
  std::printf("hoop virtual work %.6g J, -C eps A = %.6g J\n", work, -c * eps * area);
  EXPECT_NEAR(work / (-c * eps * area), 1.0, 1e-3);
}

// The ring muscle contracts the circumference by eq. 7.5's factor: its rest length across the axis
// (twice the rest radius) is the planar muscle's, and so is the contraction of every ring.
TEST(RingJellyfish, RingMusclesFollowTheContractionFunction) {
  JellyfishSpec planar_spec = ring_spec();
  planar_spec.rings = false;
  Jellyfish planar(planar_spec), ring(ring_spec());
  for (double t : {0.1, 0.4, 0.9}) {
    planar.actuate(t);
    ring.actuate(t);
    for (std::size_t k = 0; k < ring.layout().muscle_springs.size(); ++k) {
      const auto m = static_cast<std::size_t>(ring.layout().muscle_springs[k]);
      const double expected = contracted_rest_length(ring.layout().muscle_uncontracted_m[k], ring.spec().gamma,
                                                     ring.muscle_activation(k, t));
      EXPECT_DOUBLE_EQ(ring.body().linear.rest_length[m], expected) << "t " << t << ", muscle " << k;
      EXPECT_DOUBLE_EQ(ring.body().linear.rest_length[m], planar.body().linear.rest_length[m]);
    }
  }
}

TEST(RingJellyfish, MustSwimAlongTheAxis) {
  JellyfishSpec s = ring_spec();
  s.tilt_rad = 0.3;
  EXPECT_THROW(Jellyfish{s}, std::invalid_argument);
  s.tilt_rad = kPi;  // upside down is still a body of revolution
  EXPECT_NO_THROW(Jellyfish{s});
}

/// The built-in scene in axisymmetric water on the preview grid (96 × 192: 16 cells across the bell,
/// a sixtieth of the built-in grid's cost), with `overlay` laid over it.
config::Config axisymmetric_scene(const std::string& overlay = "") {
  config::Config c = scene::builtin_jellyfish_scene();
  c.set("tank.tracers_per_side=0");
  c.set("tank.geometry=\"axisymmetric\"");
  c.set("tank.cells=[96, 192]");
  if (!overlay.empty()) c.merge(config::Config::parse(overlay, "test scene"));
  return c;
}

std::string input_error(const std::string& overlay) {
  try {
    experiments::read_swim_settings(axisymmetric_scene(overlay));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// What an axisymmetric tank cannot take is an input error naming the reason.
TEST(RingJellyfish, AxisymmetricScenesRefuseWhatTheyCannotSimulate) {
  EXPECT_NE(input_error("[jellyfish]\nposition = [0.1, 0.08]\n").find("centre line"), std::string::npos);
  EXPECT_NE(input_error("[tank]\nsymmetry = \"none\"\n").find("tank.symmetry"), std::string::npos);
  EXPECT_NE(input_error("[tank]\npressure_solver = \"multigrid\"\n").find("multigrid"), std::string::npos);
  EXPECT_NE(input_error("[tank]\ncells = [95, 128]\n").find("even"), std::string::npos);
  // An obstacle off the axis without its mirror image is no body of revolution.
  EXPECT_NE(input_error("[[objects]]\ntype = \"circle\"\ncentre = [0.05, 0.25]\nradius = 0.01\n").find("revolution"),
            std::string::npos);
  EXPECT_EQ(input_error(""), "no error");
}

/// The water's axial momentum in the half tank, Σ ρ v 2π r Δr Δz (kg·m/s), and Σ |…|.
std::pair<double, double> axial_momentum(const fluid::FlowState& half) {
  const fluid::MacGrid& g = half.grid;
  double m = 0.0, scale = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double v = half.velocity.v(i, j) * (i + 0.5) * g.dx();
      m += v;
      scale += std::abs(v);
    }
  return {m, scale};
}

// In a cylinder periodic along the axis nothing but the bell exchanges axial momentum with the
// water, and the bell's forces are internal: the water's axial momentum stays zero to round-off
// while the bell strokes (a point on the axis feels each ring element once: the coupling spreads
// half the force on the axis points of the whole slice). Measured 3e-15 of Σ|v r| after 0.4 s
// (allowed 3e-14);
// with the whole force on the axis points instead, this test fails. The Eulerian solver, whose
// convection conserves momentum (a semi-Lagrangian step does not, by construction).
TEST(RingJellyfish, TheBellsForcesAreInternal) {
  jellyfish::SwimSettings s = experiments::read_swim_settings(axisymmetric_scene(
      "[tank]\nsolver = \"eulerian\"\nboundaries = [\"free-slip\", \"free-slip\", \"periodic\", \"periodic\"]\n"));
  SwimSimulation sim(s);
  while (sim.time_s() < 0.4) ASSERT_TRUE(sim.step().failure.empty());
  ASSERT_TRUE(sim.solving_half_tank());
  const auto [m, scale] = axial_momentum(sim.world().fluid().state());
  std::printf("axial momentum %.3g of %.3g\n", m, scale);
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(std::abs(m), 3e-14 * scale);
}

// One cycle of the built-in bell in axisymmetric water on the preview grid: the symmetric stroke
// moves it along the axis, farther than the planar slice (measured 3.31 cm against 0.93 cm; 3.46
// and 1.63 cm with the tentacles' roots along the margin), at one Krylov iteration per step.
TEST(RingJellyfish, SwimsAlongTheAxisFartherThanThePlanarSlice) {
  jellyfish::SwimSettings s = experiments::read_swim_settings(axisymmetric_scene());
  s.duration_s = 1.0 / s.jellyfish().frequency_hz;
  const experiments::SwimRecording rec = experiments::run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  EXPECT_TRUE(rec.stats.mirror_symmetric);
  const auto& last = rec.metrics.back();
  std::printf("one cycle: %.4g m forward, lateral %.3g m, %ld steps, %ld Krylov iterations\n", last.position,
              last.lateral, rec.stats.steps, rec.stats.krylov_iterations);
  EXPECT_GT(last.position, 0.8 * s.jellyfish().diameter_m);
  EXPECT_LT(last.position, 1.0 * s.jellyfish().diameter_m);
  EXPECT_LT(std::abs(last.lateral), 1e-15);  // round-off of the centroid
  EXPECT_LE(rec.stats.krylov_iterations, 2 * rec.stats.steps);
}

// An obstacle in an axisymmetric tank is a body of revolution: a circle on the axis is a sphere.
// Held on the axis of a pipe (radius 4a) whose water enters at U and whose mantle moves at U (both
// sides "inflow" at (0, U): a moving wall), it is AxisymmetricCoupling.StokesDragOnASphereInAPipe
// built from a scene: the force along the axis over 6πμaU times Haberman & Sayre's wall factor
// measured 1.163 at 6 cells per radius, as there (1.1627).
TEST(RingJellyfish, ASphereObstacleFeelsStokesDragFromTheScene) {
  config::Config c = axisymmetric_scene(
      "duration = 0.6\n"
      "[tank]\nwidth = 0.096\nheight = 0.288\ncells = [48, 144]\nviscosity = 1e-3\nsolver = \"eulerian\"\n"
      "boundaries = [\"inflow\", \"inflow\", \"inflow\", \"outflow\"]\n"
      "inflow_velocity = [0.0, 0.001]\ncurrent = [0.0, 0.001]\n"
      "[jellyfish]\nenabled = false\n"
      "[[objects]]\ntype = \"circle\"\ncentre = [0.048, 0.144]\nradius = 0.012\n"
      "[coupling]\nkernel = \"peskin4\"\nmobility_rebuild = 1.0\n"
      "[output]\nframe_interval = 0.1\n");
  jellyfish::SwimSettings s = experiments::read_swim_settings(c);
  SwimSimulation sim(s);
  while (sim.time_s() < 0.6 - 1e-12) ASSERT_TRUE(sim.step(0.6 - sim.time_s()).failure.empty());
  const double lambda = 0.25, exact = 6.0 * kPi * 1.0 * 0.012 * 1e-3 *
                                       (1 - 0.75857 * std::pow(lambda, 5)) /
                                       (1 - 2.1050 * lambda + 2.0865 * std::pow(lambda, 3) -
                                        1.7068 * std::pow(lambda, 5) + 0.72603 * std::pow(lambda, 6));
  const Vec2 f = sim.obstacle_force(0);
  std::printf("sphere: force along the axis / exact %.4f\n", f.y / exact);
  EXPECT_NEAR(f.y / exact, 1.163, 0.01);
}

// Ten cycles in a tank 64 cm tall (the ring bell swims about a diameter per cycle) on the preview
// grid: structurally sound, forward in every cycle by more than half a diameter (measured 3.3 to
// 5.3 cm, 0.83-1.34 diameters; 48.8 cm in all; with the tentacles' roots along the margin,
// jellyfish.tentacle_root = "margin", whose skirt folded across the aperture: 3.5 to 3.9 cm, 37.2 cm
// in all), its cavity volume oscillating at the contraction frequency.
TEST(SlowRingJellyfish, SwimsTenCyclesAlongTheAxis) {
  jellyfish::SwimSettings s = experiments::read_swim_settings(
      axisymmetric_scene("duration = 14.285714285714286\n[tank]\nheight = 0.64\ncells = [96, 256]\n"));
  ASSERT_NEAR(s.duration_s * s.jellyfish().frequency_hz, 10.0, 1e-9);
  const experiments::SwimRecording rec = experiments::run_swim(s, {}, nullptr, {});
  ASSERT_TRUE(rec.stats.failure.empty()) << rec.stats.failure;
  double previous = 0.0;
  for (int cycle = 1; cycle <= 10; ++cycle) {
    const double t = cycle / s.jellyfish().frequency_hz;
    const auto nearest = std::min_element(rec.metrics.begin(), rec.metrics.end(), [t](const auto& a, const auto& b) {
      return std::abs(a.t - t) < std::abs(b.t - t);
    });
    std::printf("cycle %d: %.4g m\n", cycle, nearest->position);
    EXPECT_GT(nearest->position - previous, 0.5 * s.jellyfish().diameter_m) << "cycle " << cycle;
    previous = nearest->position;
  }
  std::vector<double> volume;
  for (const auto& r : rec.metrics) volume.push_back(r.volume);
  EXPECT_NEAR(dominant_frequency(volume, s.frame_interval_s), s.jellyfish().frequency_hz, 1.0 / s.duration_s);
}

}  // namespace
}  // namespace jellysim::jellyfish
