// The mirror-symmetric part of a flow (fluid/flow_mirror.hpp).
#include "jellysim/fluid/flow_mirror.hpp"

#include <gtest/gtest.h>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/fluid/projection.hpp"
#include "fluid_test_util.hpp"

namespace jellysim::fluid {
namespace {

FlowState random_flow(int nx, int ny, unsigned seed) {
  FlowState flow(MacGrid(nx, ny, 0.8, 0.6));
  testing::randomise(flow.velocity, seed);
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (double& p : flow.pressure.raw()) p = d(rng);
  return flow;
}

// The mirror image of sample (i, j) of a field with staggering s sits at column n − i − 2s.
TEST(Mirror, SymmetricPartIsExactlySymmetricAndIdempotent) {
  for (int nx : {7, 8}) {
    FlowState flow = random_flow(nx, 5, 3);
    EXPECT_GT(mirror_asymmetry(flow.velocity), 0.1);
    keep_mirror_symmetric_part(flow);
    EXPECT_EQ(mirror_asymmetry(flow.velocity), 0.0) << nx;
    for (int j = -1; j <= 5; ++j) {
      for (int i = -1; i <= nx + 1; ++i) EXPECT_EQ(flow.velocity.u(i, j), -flow.velocity.u(nx - i, j));
      for (int i = -1; i <= nx; ++i) {
        EXPECT_EQ(flow.velocity.v(i, j), flow.velocity.v(nx - 1 - i, j));
        EXPECT_EQ(flow.pressure(i, j), flow.pressure(nx - 1 - i, j));
      }
    }
    if (nx % 2 == 0) {
      for (int j = 0; j < 5; ++j) EXPECT_EQ(flow.velocity.u(nx / 2, j), 0.0);  // no flow across the axis
    }
    const FlowState once = flow;
    keep_mirror_symmetric_part(flow);
    for (std::size_t k = 0; k < once.velocity.u.raw().size(); ++k)
      ASSERT_EQ(flow.velocity.u.raw()[k], once.velocity.u.raw()[k]);
    for (std::size_t k = 0; k < once.velocity.v.raw().size(); ++k)
      ASSERT_EQ(flow.velocity.v.raw()[k], once.velocity.v.raw()[k]);
  }
}

// Each sample and its mirror image both become their average (with the x-velocity's sign flipped).
TEST(Mirror, AveragesEachSampleWithItsMirrorImage) {
  FlowState flow(MacGrid(4, 3, 1.0, 1.0));
  flow.velocity.u(1, 1) = 1.0;  // its mirror image is u(3, 1)
  flow.velocity.u(3, 1) = 3.0;
  flow.velocity.v(0, 2) = 2.0;  // its mirror image is v(3, 2)
  flow.pressure(1, 0) = 4.0;    // its mirror image is p(2, 0)
  keep_mirror_symmetric_part(flow);
  EXPECT_DOUBLE_EQ(flow.velocity.u(1, 1), -1.0);
  EXPECT_DOUBLE_EQ(flow.velocity.u(3, 1), 1.0);
  EXPECT_DOUBLE_EQ(flow.velocity.v(0, 2), 1.0);
  EXPECT_DOUBLE_EQ(flow.velocity.v(3, 2), 1.0);
  EXPECT_DOUBLE_EQ(flow.pressure(1, 0), 2.0);
  EXPECT_DOUBLE_EQ(flow.pressure(2, 0), 2.0);
}

// The mirror map commutes with the discrete divergence on the MAC grid, so the symmetric part of a
// divergence-free flow is divergence-free: keeping it does not undo the projection.
TEST(Mirror, SymmetricPartOfADivergenceFreeFlowIsDivergenceFree) {
  const Boundaries walls = Boundaries::all(BoundaryType::free_slip);
  FlowState flow = random_flow(24, 16, 11);
  apply_velocity_boundaries(flow.velocity, walls);
  Projector projector(make_pressure_solver("fft"));
  projector.project(flow, walls, 0.01, 1000.0);
  apply_velocity_boundaries(flow.velocity, walls);
  const double before = max_divergence(flow.velocity);
  ASSERT_LT(before, 1e-9);
  keep_mirror_symmetric_part(flow);
  EXPECT_LT(max_divergence(flow.velocity), 2.0 * before + 1e-12);
  EXPECT_EQ(mirror_asymmetry(flow.velocity), 0.0);
}

}  // namespace
}  // namespace jellysim::fluid
