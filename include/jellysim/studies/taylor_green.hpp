#pragma once
// Periodic Taylor–Green vortex against its exact solution: error norms and measured orders of
// convergence for both fluid solvers over several grids, and the solver-cost table.
#include <string>
#include <vector>

#include "jellysim/fluid/reference_data.hpp"

namespace jellysim::studies {

struct TaylorGreenSettings {
  std::vector<std::string> solvers{"eulerian", "semi-lagrangian"};
  /// The schemes each solver is run with (fluid::scheme_names_for): convection schemes of the
  /// Eulerian solver, advection schemes of the semi-Lagrangian one.
  std::vector<std::string> convection_schemes{"donor-cell", "van-leer", "koren"};
  std::vector<std::string> advection_schemes{"linear", "maccormack", "bfecc", "cubic"};
  std::vector<int> grids{16, 32, 64, 128};  ///< cells per side
  fluid::TaylorGreen flow{};                       ///< L = 2π, U = 1, ν = 0.1
  double end_time_s = 1.0;
  double safety_factor = 0.5;  ///< Eulerian Δt = τ·limit(eqs. 4.8–4.9), fitted to end exactly
  /// Semi-Lagrangian Δt = courant·Δx/U (it has no stability limit; Δt ∝ Δx keeps the ratio).
  double semi_lagrangian_courant = 0.5;
  std::string pressure_solver = "multigrid";
  double pressure_tolerance = 1e-10;
};

struct TaylorGreenRun {
  std::string solver;
  std::string scheme;
  int cells = 0;
  double dt_s = 0.0;
  int steps = 0;
  double error_l2 = 0.0;   ///< RMS velocity error over all faces (m/s)
  double error_max = 0.0;  ///< max velocity error over all faces (m/s)
  double wall_time_s = 0.0;
};

struct ConvergenceOrder {
  std::string solver;
  std::string scheme;
  int coarse_cells = 0;
  int fine_cells = 0;
  double order_l2 = 0.0;  ///< log2(e_coarse / e_fine) per halving of Δx
  double order_max = 0.0;
};

struct TaylorGreenResult {
  std::vector<TaylorGreenRun> runs;
  std::vector<ConvergenceOrder> orders;  ///< between consecutive grids, per solver and scheme
  /// Least-squares slope of log(error_l2) against log(Δx) over all grids of one solver and scheme.
  double fitted_order_l2(const std::string& solver, const std::string& scheme) const;
};

/// The schemes of `solver` the settings ask for (convection_schemes or advection_schemes).
const std::vector<std::string>& schemes_of(const TaylorGreenSettings& s, const std::string& solver);
TaylorGreenRun run_taylor_green_once(const std::string& solver, const std::string& scheme, int cells,
                                     const TaylorGreenSettings& s);
TaylorGreenResult run_taylor_green(const TaylorGreenSettings& settings);

/// `solver-cost`: time per step and per simulated second and accuracy for every pair of fluid
/// solver and pressure solver on the Taylor–Green problem, across grid sizes.
struct SolverCostSettings {
  std::vector<int> grids{32, 64, 128, 256, 512};
  std::vector<std::string> solvers{"eulerian", "semi-lagrangian"};
  std::vector<std::string> pressure_solvers{"sor", "multigrid"};
  int steps = 5;                     ///< steps timed per configuration (after one warm-up step)
  fluid::TaylorGreen flow{6.283185307179586, 1.0, 0.01};
  double pressure_tolerance = 1e-6;  ///< relative max-norm residual
  double safety_factor = 0.5;        ///< Eulerian Δt = τ·limit
  double semi_lagrangian_courant = 1.0;
  /// SOR uses ω = 2/(1 + sin(π/n)) (optimal for the model problem) instead of Griebel's 1.7.
  bool sor_optimal_omega = true;
};

struct SolverCostRow {
  std::string solver;
  std::string pressure_solver;
  int cells = 0;  ///< per side
  double dt_s = 0.0;
  int steps = 0;
  double seconds_per_step = 0.0;
  double seconds_per_simulated_second = 0.0;
  double mean_pressure_iterations = 0.0;
  double error_l2 = 0.0;  ///< RMS velocity error against the exact solution after the steps
};

std::vector<SolverCostRow> run_solver_cost(const SolverCostSettings& settings);

/// ω = 2 / (1 + sin(π / max(nx, ny))), the optimal SOR relaxation for the five-point Laplacian.
double optimal_sor_omega(int nx, int ny);

}  // namespace jellysim::studies
