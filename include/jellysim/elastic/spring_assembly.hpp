#pragma once
// The springs' forces and their Jacobian ∂F/∂x, assembled over a body: the one assembly the ODE
// form of a body (ElasticSystem) and the immersed-boundary coupling (the semi-implicit step's K)
// both use. Linear springs first, then angular ones, each in the body's order: the sums are the
// same bits wherever they are formed.
#include <vector>

#include "jellysim/elastic/body.hpp"
#include "jellysim/elastic/forces.hpp"

namespace jellysim::elastic {

/// Adds every spring's force at positions x to `force` (sized to the point count).
void add_spring_forces(const Body& body, const std::vector<Vec2>& x, std::vector<Vec2>& force);

/// Calls block(a, b, ∂F_a/∂x_b) for every 2 × 2 block of the springs' Jacobian at positions x:
/// each linear spring's four blocks (i i, i j, j i, j j), then each angular spring's nine.
/// Blocks of one pair of points repeat across springs; the caller sums them.
template <typename Block>
void for_each_spring_jacobian_block(const Body& body, const std::vector<Vec2>& x, Block&& block) {
  const auto& lin = body.linear;
  for (std::size_t s = 0; s < lin.size(); ++s) {
    const int i = lin.i[s], j = lin.j[s];
    const Mat2 d = linear_spring_force_and_jacobian(x[i], x[j], lin.stiffness[s], lin.rest_length[s]).d_on_i_d_xi;
    block(i, i, d);
    block(i, j, -d);
    block(j, i, -d);
    block(j, j, d);
  }
  const auto& ang = body.angular;
  for (std::size_t s = 0; s < ang.size(); ++s) {
    const int idx[3] = {ang.i[s], ang.j[s], ang.k[s]};
    const AngularSpringForce f =
        angular_spring_force_and_jacobian(x[idx[0]], x[idx[1]], x[idx[2]], ang.stiffness[s], ang.rest_angle[s]);
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) block(idx[p], idx[q], f.jacobian[p][q]);
  }
}

}  // namespace jellysim::elastic
