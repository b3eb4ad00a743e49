// The coupled world (coupling/world.hpp): one body, one fluid, one clock; the half tank of a
// mirror-symmetric world reproduces the whole tank, and leaving it mid-run continues the same flow.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "jellysim/coupling/world.hpp"
#include "jellysim/elastic/body_mirror.hpp"

namespace jellysim::coupling {
namespace {

TankSpec small_tank() {
  TankSpec t;
  t.width_m = 0.1;
  t.height_m = 0.1;
  t.cells_x = 32;
  t.cells_y = 32;
  t.viscosity_m2_per_s = 1e-5;
  t.tracers_per_side = 4;
  return t;
}

/// A stretched elastic ring (an ellipse of zero-rest-length springs) centred in the tank: it pulls
/// itself toward a circle and drives a mirror-symmetric flow.
std::unique_ptr<elastic::Body> stretched_ring(const TankSpec& t) {
  auto body = std::make_unique<elastic::Body>();
  const int n = 48;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * (k + 0.5) / n;
    body->add_point({0.5 * t.width_m + 0.025 * std::cos(a), 0.5 * t.height_m + 0.015 * std::sin(a)}, 1e-3);
  }
  for (int k = 0; k < n; ++k) body->add_linear_spring(k, (k + 1) % n, 5.0, 0.0);
  return body;
}

double aspect_ratio(const elastic::Body& b) {
  double w = 0, h = 0;
  for (Vec2 p : b.points.position) {
    w = std::max(w, std::abs(p.x - 0.05));
    h = std::max(h, std::abs(p.y - 0.05));
  }
  return w / h;
}

std::vector<int> partners_of(const elastic::Body& b, const TankSpec& t) {
  return elastic::mirror_partners(b, 0.5 * t.width_m, 1e-12);
}

void advance(World& w, int steps) {
  for (int k = 0; k < steps; ++k) w.step(std::min(w.next_time_step(), 1e-2));
}

double max_difference(const fluid::Field& a, const fluid::Field& b) {
  double d = 0;
  for (int j = 0; j < a.count_y(); ++j)
    for (int i = 0; i < a.count_x(); ++i) d = std::max(d, std::abs(a(i, j) - b(i, j)));
  return d;
}

TEST(World, StepsTheBodyTheFluidAndTheTracersOnOneClock) {
  const TankSpec t = small_tank();
  int actuations = 0;
  World w(t, stretched_ring(t), CouplingSettings{}, [&](double, elastic::Body&) { ++actuations; });
  const elastic::Body* body = &w.body();
  const std::vector<Vec2> tracers_before = w.tracers().positions();
  const double before = aspect_ratio(w.body());
  EXPECT_NEAR(before, 0.025 / 0.015, 0.01);
  advance(w, 60);
  EXPECT_EQ(w.steps(), 60);
  EXPECT_GT(w.time_s(), 0.0);
  EXPECT_EQ(&w.body(), body);  // stepped in place: no copy of the body
  EXPECT_GT(actuations, 0);
  EXPECT_NEAR(aspect_ratio(w.body()), 1.29, 0.02);               // the ring relaxes toward a circle (1.29 measured)
  EXPECT_NEAR(w.flow().velocity.u.max_abs_interior(), 8.7e-3, 5e-4);  // and pushes the water (8.74 mm/s)
  EXPECT_NE(w.tracers().positions(), tracers_before);   // which carries the tracers
  EXPECT_FALSE(w.mirror_symmetric());
  EXPECT_EQ(&w.flow(), &w.fluid().state());
}

TEST(World, HalfTankOfAMirrorSymmetricWorldReproducesTheWholeTank) {
  const TankSpec t = small_tank();
  auto ring = stretched_ring(t);
  std::vector<int> partners = partners_of(*ring, t);
  ASSERT_EQ(partners.size(), ring->points.size());
  World half(t, std::move(ring), CouplingSettings{}, {}, partners);
  World whole(t, stretched_ring(t), CouplingSettings{}, {});
  ASSERT_TRUE(half.solving_half_tank());
  EXPECT_EQ(half.fluid().state().velocity.u.count_x() * 2 - 1, whole.fluid().state().velocity.u.count_x());
  advance(half, 20);
  advance(whole, 20);
  EXPECT_EQ(half.flow().velocity.u.count_x(), whole.flow().velocity.u.count_x());
  const double scale = whole.flow().velocity.u.max_abs_interior();
  ASSERT_GT(scale, 1e-3);
  // Round-off apart (1e-13 of the largest speed measured).
  EXPECT_LT(max_difference(half.flow().velocity.u, whole.flow().velocity.u), 1e-11 * scale);
  EXPECT_LT(max_difference(half.flow().velocity.v, whole.flow().velocity.v), 1e-11 * scale);
  for (std::size_t p = 0; p < half.body().points.size(); ++p)
    EXPECT_NEAR(norm(half.body().points.position[p] - whole.body().points.position[p]), 0.0, 1e-15);  // 7e-17 m measured
}

TEST(World, EndingTheSymmetryContinuesTheSameFlowOnTheWholeTank) {
  const TankSpec t = small_tank();
  auto ring = stretched_ring(t);
  std::vector<int> partners = partners_of(*ring, t);
  World w(t, std::move(ring), CouplingSettings{}, {}, partners);
  advance(w, 10);
  const fluid::FlowState unfolded = w.flow();
  const double time = w.time_s();
  w.end_mirror_symmetry();
  EXPECT_FALSE(w.mirror_symmetric());
  EXPECT_FALSE(w.solving_half_tank());
  EXPECT_EQ(w.time_s(), time);
  EXPECT_EQ(w.steps(), 10);
  EXPECT_EQ(max_difference(w.flow().velocity.u, unfolded.velocity.u), 0.0);
  EXPECT_EQ(max_difference(w.flow().velocity.v, unfolded.velocity.v), 0.0);
  advance(w, 5);
  EXPECT_EQ(w.steps(), 15);
}

TEST(World, RejectsMirrorPartnersThatDoNotNameEveryPoint) {
  const TankSpec t = small_tank();
  EXPECT_THROW(World(t, stretched_ring(t), CouplingSettings{}, {}, std::vector<int>{0, 1}), std::invalid_argument);
  EXPECT_THROW(World(t, nullptr, CouplingSettings{}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace jellysim::coupling
