// Particle–edge and wall collisions (thesis §5.2.1-5.2.2): the swap rule, momentum and energy,
// no tunnelling in a randomized stress test, trapped particles.
#include "jellysim/sph/collisions.hpp"
#include "sph_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace jellysim::sph {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(SphCollisionPair, EqualMassesSwapTheirNormalComponents) {
  const Vec2 c{0.6, 0.8};
  const Vec2 vp{0.3, -2.0}, ve{-0.5, 0.4};
  const PairResult r = collide_pair(vp, 2.0, ve, 2.0, c);
  EXPECT_NEAR(dot(r.particle, c), dot(ve, c), 1e-15);  // eq. 5.26
  EXPECT_NEAR(dot(r.endpoint, c), dot(vp, c), 1e-15);  // eq. 5.27
  EXPECT_NEAR(cross(r.particle, c), cross(vp, c), 1e-15);
  EXPECT_NEAR(cross(r.endpoint, c), cross(ve, c), 1e-15);
}

TEST(SphCollisionPair, UnequalMassesConserveMomentumAndEnergy) {
  test::Random rng(5);
  for (int k = 0; k < 1000; ++k) {
    const double angle = rng.uniform(0.0, 6.3);
    const Vec2 c{std::cos(angle), std::sin(angle)};
    const Vec2 vp = rng.point(3.0), ve = rng.point(3.0);
    const double mp = rng.uniform(0.1, 10.0), me = rng.uniform(0.1, 10.0);
    const PairResult r = collide_pair(vp, mp, ve, me, c);
    const Vec2 dp = (r.particle * mp + r.endpoint * me) - (vp * mp + ve * me);
    EXPECT_LT(norm(dp), 1e-12 * (mp + me) * 6.0);                        // eq. 5.22
    const double e0 = mp * norm_squared(vp) + me * norm_squared(ve);
    const double e1 = mp * norm_squared(r.particle) + me * norm_squared(r.endpoint);
    EXPECT_NEAR(e1, e0, 1e-12 * e0);                                     // eq. 5.24
    EXPECT_GE(dot(r.particle - r.endpoint, c), -1e-12);                 // separating afterwards
  }
}

TEST(SphCollisionPair, InfiniteMassReflectsAndSeparatingPairsAreLeftAlone) {
  const Vec2 c{0.0, 1.0};
  const PairResult r = collide_pair({1.0, -2.0}, 1.0, {0.0, 0.5}, kInf, c);
  EXPECT_EQ(r.particle, (Vec2{1.0, 3.0}));
  EXPECT_EQ(r.endpoint, (Vec2{0.0, 0.5}));
  const PairResult s = collide_pair({1.0, 2.0}, 1.0, {0.0, 0.5}, 1.0, c);
  EXPECT_EQ(s.particle, (Vec2{1.0, 2.0}));
}

/// A square body of four free points (counter-clockwise) and one particle.
struct Layout {
  std::vector<Vec2> b0, b1, bv, p0, p1, pv;
  std::vector<double> bm, pm;
  CollisionOutline outline;
  MovingPoints body() { return {&b0, &b1, &bv, &bm}; }
  MovingPoints particles() { return {&p0, &p1, &pv, &pm}; }
  Vec2 momentum() const {
    Vec2 p{};
    for (std::size_t i = 0; i < bv.size(); ++i) p += bv[i] * bm[i];
    for (std::size_t i = 0; i < pv.size(); ++i) p += pv[i] * pm[i];
    return p;
  }
  double energy() const {
    double e = 0.0;
    for (std::size_t i = 0; i < bv.size(); ++i) e += 0.5 * bm[i] * norm_squared(bv[i]);
    for (std::size_t i = 0; i < pv.size(); ++i) e += 0.5 * pm[i] * norm_squared(pv[i]);
    return e;
  }
};

/// Square of side `side` centred at c, rotating by ω and translating with u over one step of dt.
Layout moving_square(test::Random& rng, double dt) {
  Layout s;
  const Vec2 c = rng.point(0.2);
  const double side = rng.uniform(0.02, 0.3), angle = rng.uniform(0.0, 6.3), omega = rng.uniform(-3.0, 3.0) / dt;
  const Vec2 u = rng.point(1.0) / dt;
  const Vec2 corners[4] = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  for (const Vec2& k : corners) {
    const Vec2 r0 = rotated(k * side, angle), r1 = rotated(k * side, angle + omega * dt);
    s.b0.push_back(c + r0);
    s.b1.push_back(c + u * dt + r1);
    s.bv.push_back((s.b1.back() - s.b0.back()) / dt);
    s.bm.push_back(rng.uniform(0.2, 5.0));
  }
  s.outline.add_loop({0, 1, 2, 3});
  return s;
}

TEST(SphCollisionStress, FastParticlesNeverTunnelThroughMovingEdges) {
  test::Random rng(2024);
  const double dt = 0.1;
  CollisionHandler handler(CollisionSettings{1e-9, 0.0});
  int collisions = 0, cases = 0;
  while (cases < 20000) {
    Layout s = moving_square(rng, dt);
    const Vec2 start = rng.point(0.45);
    if (inside_outline(s.outline, s.b0, start)) continue;  // particles start outside the body
    ++cases;
    const Vec2 v = rng.point(1.5) / dt;  // up to several body sizes per step
    s.p0 = {start};
    s.p1 = {start + v * dt};
    s.pv = {v};
    s.pm = {rng.uniform(0.2, 5.0)};
    const Vec2 p_before = s.momentum();
    const double e_before = s.energy();
    const CollisionStatistics st = handler.handle(s.particles(), s.body(), s.outline, {}, dt);
    collisions += static_cast<int>(st.edge_collisions);
    ASSERT_FALSE(inside_outline(s.outline, s.b1, s.p1[0]))
        << "case " << cases << " tunnelled: p0 " << start.x << "," << start.y << " p1 " << s.p1[0].x << ","
        << s.p1[0].y << " edges " << st.edge_collisions << " b1 " << s.b1[0].x << "," << s.b1[0].y << " "
        << s.b1[1].x << "," << s.b1[1].y << " " << s.b1[2].x << "," << s.b1[2].y << " " << s.b1[3].x << ","
        << s.b1[3].y;
    EXPECT_LT(norm(s.momentum() - p_before), 1e-9 * (norm(p_before) + 1.0)) << "case " << cases;
    EXPECT_LE(s.energy(), e_before * (1.0 + 1e-12)) << "case " << cases;
  }
  EXPECT_GT(collisions, 1500);  // the stress test really exercises collisions
}

TEST(SphCollisionStress, ParticlesNeverCrossStaticWalls) {
  test::Random rng(99);
  const std::vector<Wall> walls = box_walls({0.0, 0.0}, {1.0, 1.0});
  CollisionHandler handler(CollisionSettings{});
  for (int k = 0; k < 2000; ++k) {
    std::vector<Vec2> p0{rng.point(0.5) + Vec2{0.5, 0.5}}, v{rng.point(4.0)};
    std::vector<Vec2> p1{p0[0] + v[0] * 0.1};
    const std::vector<double> m{1.0};
    const double speed = norm(v[0]);
    handler.handle({&p0, &p1, &v, &m}, {}, {}, walls, 0.1);
    for (const Wall& w : walls) ASSERT_GE(w.distance(p1[0]), 0.0);
    EXPECT_NEAR(norm(v[0]), speed, 1e-12 * speed);  // elastic
  }
}

TEST(SphCollision, ParticleHitsTheMiddleOfAnEdgeAndSplitsItsMomentum) {
  // Bottom edge of a unit square at rest; equal masses; the particle comes straight down at s = 1/2.
  Layout s;
  // Counter-clockwise square [0,1] × [-1, 0]; its top edge runs from point 2 (1,0) to point 3 (0,0).
  s.b0 = {{0.0, -1.0}, {1.0, -1.0}, {1.0, 0.0}, {0.0, 0.0}};
  s.b1 = s.b0;
  s.bv.assign(4, Vec2{});
  s.bm.assign(4, 1.0);
  s.outline.add_loop({0, 1, 2, 3});
  s.p0 = {{0.5, 0.05}};
  s.p1 = {{0.5, -0.05}};
  s.pv = {{0.0, -1.0}};
  s.pm = {1.0};
  CollisionHandler handler(CollisionSettings{1e-9, 0.0});
  const CollisionStatistics st = handler.handle(s.particles(), s.body(), s.outline, {}, 0.1);
  EXPECT_EQ(st.edge_collisions, 1);
  EXPECT_NEAR(s.pv[0].y, 0.0, 1e-15);      // eq. 5.29: each endpoint swap leaves it at rest
  EXPECT_NEAR(s.bv[2].y, -0.5, 1e-15);     // eq. 5.30 with s = 1/2
  EXPECT_NEAR(s.bv[3].y, -0.5, 1e-15);
  EXPECT_GE(s.p1[0].y, 0.0);               // placed outside the edge
}

TEST(SphCollision, ParticleSweptOverByAFastEdgeIsDetected) {
  // A particle at rest; a square body moves down past it within one step (swept-region detection).
  Layout s;
  s.b0 = {{0.0, 0.2}, {1.0, 0.2}, {1.0, 0.4}, {0.0, 0.4}};
  s.b1 = {{0.0, -0.6}, {1.0, -0.6}, {1.0, -0.4}, {0.0, -0.4}};
  s.bv.assign(4, Vec2{0.0, -8.0});
  s.bm.assign(4, 1.0);
  s.outline.add_loop({0, 1, 2, 3});
  s.p0 = s.p1 = {{0.3, 0.0}};
  s.pv = {{0.0, 0.0}};
  s.pm = {1.0};
  CollisionHandler handler(CollisionSettings{1e-9, 0.0});
  EXPECT_EQ(handler.handle(s.particles(), s.body(), s.outline, {}, 0.1).edge_collisions, 1);
  EXPECT_LT(s.pv[0].y, -1.0);  // pushed down ahead of the edge
  EXPECT_FALSE(inside_outline(s.outline, s.b1, s.p1[0]));
  EXPECT_LT(s.p1[0].y, -0.6);
}

TEST(SphCollision, TrappedParticleIsReAimedAlongTheBoundaryWithoutGainingEnergy) {
  // A particle resting on a fixed floor (wall at y = 0) while a heavy edge comes down on it.
  Layout s;
  s.b0 = {{0.0, 0.03}, {1.0, 0.03}, {1.0, 0.2}, {0.0, 0.2}};
  s.b1 = {{0.0, 0.005}, {1.0, 0.005}, {1.0, 0.175}, {0.0, 0.175}};
  s.bv.assign(4, Vec2{0.0, -0.25});
  s.bm.assign(4, 10.0);
  s.outline.add_loop({0, 1, 2, 3});
  s.p0 = {{0.4, 0.01}};
  s.p1 = {{0.401, 0.01}};
  s.pv = {{0.01, 0.0}};
  s.pm = {1.0};
  const std::vector<Wall> floor{Wall{{0.0, 0.0}, {0.0, 1.0}, true}};
  const double e_before = s.energy();
  CollisionHandler handler(CollisionSettings{1e-9, 0.008});
  const CollisionStatistics st = handler.handle(s.particles(), s.body(), s.outline, floor, 0.1);
  EXPECT_EQ(st.edge_collisions, 1);
  EXPECT_EQ(st.trapped, 1);
  EXPECT_NEAR(cross(s.pv[0], s.b1[1] - s.b1[0]), 0.0, 1e-12);  // along the (slightly tilted) edge
  EXPECT_GT(norm(s.pv[0]), 0.1);
  EXPECT_LE(s.energy(), e_before * (1.0 + 1e-12));
  EXPECT_GE(s.p1[0].y, 0.0);
  EXPECT_FALSE(inside_outline(s.outline, s.b1, s.p1[0]));
}

TEST(SphCollision, BoundaryWidthOfAStripIsItsHeight) {
  std::vector<Vec2> x;
  for (int c = 0; c <= 8; ++c) x.push_back({0.05 * c, 0.0});
  for (int c = 0; c <= 8; ++c) x.push_back({0.05 * c, -0.05});
  CollisionOutline outline;
  std::vector<int> loop;
  for (int c = 0; c <= 8; ++c) loop.push_back(9 + c);  // bottom row left to right
  for (int c = 8; c >= 0; --c) loop.push_back(c);      // top row right to left
  outline.add_loop(loop);
  EXPECT_NEAR(boundary_width(outline, x), 0.05, 1e-15);
  EXPECT_TRUE(inside_outline(outline, x, {0.2, -0.02}));
  EXPECT_FALSE(inside_outline(outline, x, {0.2, 0.02}));
}

}  // namespace
}  // namespace jellysim::sph
