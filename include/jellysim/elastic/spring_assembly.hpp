#pragma once
// The springs' forces and their Jacobian ∂F/∂x, assembled over a body: the one assembly the ODE
// form of a body (ElasticSystem) and the immersed-boundary coupling (the semi-implicit step's K)
// both use. Linear springs first, then angular springs, torsional beams, non-invariant beams and
// power springs, each in the body's order: the sums are the same bits wherever they are formed.
// Dashpots depend on velocities and are assembled apart (add_dashpot_forces).
#include <vector>

#include "jellysim/elastic/body.hpp"
#include "jellysim/elastic/forces.hpp"

namespace jellysim::elastic {

/// Adds every spring's and beam's force at positions x to `force` (sized to the point count).
void add_spring_forces(const Body& body, const std::vector<Vec2>& x, std::vector<Vec2>& force);

/// Adds every dashpot's force at positions x and velocities v to `force` (sized to the point count).
void add_dashpot_forces(const Body& body, const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                        std::vector<Vec2>& force);

/// Calls block(a, b, ∂F_a/∂x_b) for every 2 × 2 block of the springs' Jacobian at positions x:
/// each linear spring's four blocks (i i, i j, j i, j j), then each angular spring's nine (rows
/// and columns in the order i, j, k), each torsional beam's nine, each non-invariant beam's nine,
/// then each power spring's four. Blocks of one pair of points repeat across springs; the caller
/// sums them. Dashpots are not included (they depend on velocities).
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
  const auto three_point_blocks = [&block](const int (&idx)[3], const ThreePointForce& f) {
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) block(idx[p], idx[q], f.jacobian[p][q]);
  };
  const auto& tb = body.torsional;
  for (std::size_t s = 0; s < tb.size(); ++s) {
    const int idx[3] = {tb.i[s], tb.j[s], tb.k[s]};
    three_point_blocks(idx, torsional_beam_force_and_jacobian(x[idx[0]], x[idx[1]], x[idx[2]], tb.stiffness[s],
                                                              tb.curvature[s]));
  }
  const auto& nb = body.non_invariant;
  for (std::size_t s = 0; s < nb.size(); ++s) {
    const int idx[3] = {nb.i[s], nb.j[s], nb.k[s]};
    three_point_blocks(idx, non_invariant_beam_force_and_jacobian(x[idx[0]], x[idx[1]], x[idx[2]], nb.stiffness[s],
                                                                  nb.curvature[s]));
  }
  const auto& pw = body.power;
  for (std::size_t s = 0; s < pw.size(); ++s) {
    const int i = pw.i[s], j = pw.j[s];
    const Mat2 d =
        power_spring_force_and_jacobian(x[i], x[j], pw.stiffness[s], pw.rest_length[s], pw.degree[s]).d_on_i_d_xi;
    block(i, i, d);
    block(i, j, -d);
    block(j, i, -d);
    block(j, j, d);
  }
}

}  // namespace jellysim::elastic
