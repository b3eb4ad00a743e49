// Derived fields and tracers.
#include <gtest/gtest.h>

#include <cmath>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/fluid/reference_data.hpp"
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

// A velocity whose face fluxes are differences of a stream function given at the nodes:
// u(i, j) = (ψ(i, j+1) − ψ(i, j))/Δy, v(i, j) = −(ψ(i+1, j) − ψ(i, j))/Δx (discretely divergence-free).
template <class Psi>
Velocity velocity_from_node_stream_function(const MacGrid& g, Psi&& psi) {
  Velocity vel(g);
  const Field nodes(g, kNodes);
  auto at = [&](int i, int j) { return psi(nodes.position(i, j)); };
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) vel.u(i, j) = (at(i, j + 1) - at(i, j)) / g.dy();
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) vel.v(i, j) = -(at(i + 1, j) - at(i, j)) / g.dx();
  return vel;
}

TEST(Diagnostics, StreamFunctionOfAFieldBuiltFromAStreamFunctionIsThatFunction) {
  // Off-origin, non-square cells, ψ nonzero on every side (so the bottom-row integration of −v
  // matters): recovered up to its value at the origin corner, to round-off.
  const MacGrid g(12, 9, 1.5, 1.2, {-0.3, 0.2});
  auto psi = [](Vec2 p) { return std::sin(2.0 * p.x + 0.3) * std::cos(1.5 * p.y) + 0.2 * p.x * p.y * p.y; };
  const Field s = stream_function_at_nodes(velocity_from_node_stream_function(g, psi));
  EXPECT_EQ(s.count_x(), g.nx + 1);
  EXPECT_EQ(s.count_y(), g.ny + 1);
  const double offset = psi(g.origin_m);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i) EXPECT_NEAR(s(i, j), psi(s.position(i, j)) - offset, 1e-13) << i << "," << j;
}

TEST(Diagnostics, StreamFunctionOfTheTaylorGreenFieldIsExactUpToTheMidpointSumFactor) {
  // u = U sin kx cos ky, v = −U cos kx sin ky sampled at the faces; ψ = (U/k) sin kx sin ky, and
  // the sum of the face values up a column is Σ_{m<j} cos(k(m+½)h) h = sin(kjh) h / (2 sin(kh/2)):
  // the nodes get ψ · (kh/2)/sin(kh/2) exactly. One period per side: ψ = 0 on all four sides.
  const int n = 32;
  const TaylorGreen tg{1.0, 0.8, 0.0};
  const MacGrid g(n, n, tg.length_m, tg.length_m);
  const Field s = stream_function_at_nodes(tg.sample(g, 0.0));
  const double k = tg.wavenumber(), h = g.dx();
  const double factor = 0.5 * k * h / std::sin(0.5 * k * h);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Vec2 p = s.position(i, j);
      const double exact = tg.speed_m_per_s / k * std::sin(k * p.x) * std::sin(k * p.y);
      EXPECT_NEAR(s(i, j), exact * factor, 1e-14) << i << "," << j;
    }
  for (int m = 0; m <= n; ++m) {
    EXPECT_NEAR(s(m, 0), 0.0, 1e-14);
    EXPECT_NEAR(s(m, n), 0.0, 1e-14);
    EXPECT_NEAR(s(0, m), 0.0, 1e-14);
    EXPECT_NEAR(s(n, m), 0.0, 1e-14);
  }
  // The vortex centred at (3L/4, L/4) turns clockwise (u > 0 above its centre, u < 0 below) and
  // has ψ < 0 there, the sign convention of Ghia et al.
  EXPECT_GT(tg.velocity({0.75, 0.3}, 0.0).x, 0.0);
  EXPECT_LT(tg.velocity({0.75, 0.2}, 0.0).x, 0.0);
  EXPECT_LT(s(3 * n / 4, n / 4), 0.0);
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
