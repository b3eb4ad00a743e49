#pragma once
// Projection onto divergence-free velocity fields (eq. 4.14, and eqs. 3.3 + 4.7 of the classical
// method, which is the same operation): solve ∇²φ = ∇·u*/Δt, then u = u* − Δt∇φ; the pressure
// is p = ρφ.
#include <memory>
#include <vector>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/poisson.hpp"

namespace jellysim::fluid {

/// Discrete divergence at the cell centres (1/s): (u_{i+1,j} − u_{i,j})/Δx + (v_{i,j+1} − v_{i,j})/Δy.
double cell_divergence(const Velocity& vel, int i, int j);
/// The axisymmetric divergence (x = r from the axis, y = z): (r_{i+½} u_{i+1,j} − r_{i−½} u_{i,j})/(r_i Δr)
/// + (v_{i,j+1} − v_{i,j})/Δz, with r_i = (i + ½)Δr.
double axisymmetric_cell_divergence(const Velocity& vel, int i, int j);
/// max |∇·u| over all cells in the given geometry.
double max_divergence(const Velocity& vel, Geometry geometry);
Field divergence(const Velocity& vel);
/// max |∇·u| over all cells.
double max_divergence(const Velocity& vel);

class Projector {
 public:
  explicit Projector(std::unique_ptr<PressureSolver> solver, Geometry geometry = Geometry::planar)
      : solver_(std::move(solver)), geometry_(geometry) {}
  Geometry geometry() const { return geometry_; }

  /// Makes state.velocity discretely divergence-free (normal velocities on the sides must be set)
  /// and stores the pressure (Pa) in state.pressure. Initial guess: the old pressure; with
  /// set_extrapolation(true), when the last two projections of this projector produced the old
  /// pressure (unedited since) and the one before on the same grid, their linear extrapolation
  /// in time, φ_n + (φ_n − φ_{n−1})·Δt/Δt_n (fewer cycles for flows that change smoothly).
  PressureSolveReport project(FlowState& state, const Boundaries& b, double dt_s, double density_kg_per_m3);
  PressureSolver& pressure_solver() { return *solver_; }
  /// Off by default (the old pressure alone is the guess).
  void set_extrapolation(bool on) { extrapolate_ = on; }
  /// Forgets the stored pressures (the next guess is the state's pressure alone).
  void reset_history() { have_previous_ = have_last_ = false; }
  /// Checkpoints: the stored pressures of the extrapolated guess.
  void archive(core::StateArchive& a);

 private:
  // rhs_ = ∇·u*/Δt (eq. 3.3) and phi_ = the initial guess of φ (see project()).
  void prepare_rhs_and_guess(const FlowState& state, double dt_s, double density_kg_per_m3);
  // Keeps φ_n and φ_{n−1} for the next guess (buffers rotate, no copy).
  void remember_phi(double dt_s);

  std::unique_ptr<PressureSolver> solver_;
  Geometry geometry_;
  std::vector<double> rhs_, phi_;
  // φ = p/ρ of the last two projections (for the extrapolated initial guess) and their Δt.
  std::vector<double> last_phi_, previous_phi_;
  double last_dt_s_ = 0.0;
  bool have_previous_ = false, have_last_ = false;
  bool extrapolate_ = false;
};

/// Ghost values of a cell-centred field for the pressure sides: copy (Neumann), negate
/// (p = 0 on the side), or wrap (periodic).
void fill_pressure_ghosts(Field& p, const Boundaries& b);

}  // namespace jellysim::fluid
