// Derived fields and tracers.
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/fluid/tracers.hpp"

namespace jellysim::fluid {
namespace {

Velocity rigid_rotation(const MacGrid& g, double omega, Vec2 centre) {
  Velocity vel(g);
  for (int j = -1; j <= vel.u.count_y(); ++j)
    for (int i = -1; i <= vel.u.count_x(); ++i) vel.u(i, j) = -omega * (vel.u.position(i, j).y - centre.y);
  for (int j = -1; j <= vel.v.count_y(); ++j)
    for (int i = -1; i <= vel.v.count_x(); ++i) vel.v(i, j) = omega * (vel.v.position(i, j).x - centre.x);
  return vel;
}

TEST(Diagnostics, VorticityOfARigidRotationIsTwiceItsAngularVelocity) {
  const MacGrid g(10, 8, 2.0, 1.6, {-1.0, -0.8});
  const Velocity vel = rigid_rotation(g, 0.7, {0.0, 0.0});
  const Field w = vorticity_at_nodes(vel);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) EXPECT_NEAR(w(i, j), 1.4, 1e-12);
  const Field s = speed_at_centres(vel);
  EXPECT_NEAR(s(0, 0), 0.7 * norm(s.position(0, 0)), 1e-12);
}

TEST(Tracers, FollowARigidRotationAndStayInTheDomain) {
  const MacGrid g(32, 32, 2.0, 2.0, {-1.0, -1.0});
  const Velocity vel = rigid_rotation(g, 1.0, {0.0, 0.0});
  Tracers tracers({{0.5, 0.0}, {0.0, 0.25}});
  const Boundaries b = Boundaries::all(BoundaryType::no_slip);
  const int steps = 200;
  const double dt = 2.0 * M_PI / steps;
  for (int k = 0; k < steps; ++k) tracers.advect(vel, b, dt);  // one full turn
  EXPECT_NEAR(tracers.positions()[0].x, 0.5, 2e-3);
  EXPECT_NEAR(tracers.positions()[0].y, 0.0, 2e-3);
  EXPECT_NEAR(norm(tracers.positions()[1]), 0.25, 1e-3);
  // A tracer pushed against a wall stays on it.
  Tracers edge({{0.99, 0.0}});
  Velocity outward(g);
  outward.u.fill(5.0);
  edge.advect(outward, b, 1.0);
  EXPECT_DOUBLE_EQ(edge.positions()[0].x, 1.0);
}

TEST(Tracers, WrapAroundPeriodicSides) {
  const MacGrid g(8, 8, 1.0, 1.0);
  Velocity vel(g);
  vel.u.fill(0.3);
  Tracers t({{0.9, 0.5}});
  t.advect(vel, Boundaries::all(BoundaryType::periodic), 1.0);
  EXPECT_NEAR(t.positions()[0].x, 0.2, 1e-12);
}

TEST(Diagnostics, MomentumAndEnergyOfAUniformStream) {
  const MacGrid g(4, 5, 2.0, 1.0);
  Velocity vel(g);
  vel.u.fill(2.0);
  apply_velocity_boundaries(vel, Boundaries::all(BoundaryType::periodic));
  const Vec2 m = total_momentum(vel, true, true);
  EXPECT_NEAR(m.x, 2.0 * 2.0 * 1.0, 1e-12);  // u · area
  EXPECT_NEAR(m.y, 0.0, 1e-12);
  EXPECT_NEAR(kinetic_energy(vel, true, true), 0.5 * 4.0 * 2.0, 1e-12);
}

}  // namespace
}  // namespace jellysim::fluid
