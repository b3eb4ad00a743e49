#pragma once
// Projection onto divergence-free velocity fields (eq. 4.14, and eqs. 3.3 + 4.7 of the classical
// method, which is the same operation): solve ∇²φ = ∇·u*/Δt, then u = u* − Δt∇φ; the pressure
// is p = ρφ.
#include <memory>
#include <vector>

#include "fluid/boundary.hpp"
#include "fluid/poisson.hpp"

namespace jellysim::fluid {

/// Discrete divergence at the cell centres (1/s): (u_{i+1,j} − u_{i,j})/Δx + (v_{i,j+1} − v_{i,j})/Δy.
double cell_divergence(const Velocity& vel, int i, int j);
Field divergence(const Velocity& vel);
/// max |∇·u| over all cells.
double max_divergence(const Velocity& vel);

class Projector {
 public:
  explicit Projector(std::unique_ptr<PressureSolver> solver) : solver_(std::move(solver)) {}

  /// Makes state.velocity discretely divergence-free (normal velocities on the sides must be set)
  /// and stores the pressure (Pa) in state.pressure; the old pressure is the initial guess.
  PressureSolveReport project(FlowState& state, const Boundaries& b, double dt_s, double density_kg_per_m3);
  PressureSolver& pressure_solver() { return *solver_; }

 private:
  std::unique_ptr<PressureSolver> solver_;
  std::vector<double> rhs_, phi_;
};

/// Ghost values of a cell-centred field for the pressure sides: copy (Neumann), negate
/// (p = 0 on the side), or wrap (periodic).
void fill_pressure_ghosts(Field& p, const Boundaries& b);

}  // namespace jellysim::fluid
