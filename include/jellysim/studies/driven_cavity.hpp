#pragma once
// Driven-cavity experiments of thesis §8.1.3: a unit square of fluid whose top side moves with
// speed U (in-flow tangential to the side, i.e. a moving no-slip lid), the other sides no-slip.
// Library functions only: the CLI, CSV, summary.json and pictures are written by the caller.
#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jellysim/fluid/grid.hpp"
#include "jellysim/fluid/reference_data.hpp"
#include "jellysim/fluid/schemes.hpp"

namespace jellysim::studies {

struct DrivenCavitySettings {
  std::string solver = "eulerian";         ///< "eulerian" or "semi-lagrangian"
  double reynolds = 100.0;                 ///< Re = U L / ν
  int cells = 64;                          ///< cells per side
  double size_m = 1.0;                     ///< L
  double lid_speed_m_per_s = 1.0;          ///< U
  std::string pressure_solver = "multigrid";
  double pressure_tolerance = 1e-8;        ///< relative max-norm residual
  /// Δt (s). 0: Eulerian uses its adaptive limit (eqs. 4.8–4.9 × safety factor), semi-Lagrangian
  /// uses Δx/U. A fixed Δt above the Eulerian limit is split into stable sub-steps.
  double time_step_s = 0.0;
  double safety_factor = 0.9;
  std::optional<double> donor_cell_blend{};  ///< γ; unset: smallest stable (Eulerian)
  bool project_before_advection = false;     ///< semi-Lagrangian §4.2.4
  /// Eulerian convection / semi-Lagrangian advection (the thesis's schemes by default here; the
  /// experiment's scene defaults to the most accurate ones).
  fluid::ConvectionScheme convection = fluid::ConvectionScheme::donor_cell;
  fluid::AdvectionScheme advection = fluid::AdvectionScheme::linear;
  double max_time_s = 200.0;                 ///< stop here if not steady before
  /// Steady when max|u(t+Δt) − u(t)| / Δt < tolerance · U²/L (the change per unit time, relative
  /// to the lid's scale); 0: run to max_time_s.
  double steady_tolerance = 1e-6;
  /// Marker particles on a tracers_per_side² lattice, carried by the flow (Figures 8.11/8.12).
  int tracers_per_side = 0;
  /// Output frames: called at t = 0, every frame_interval_s (steps are shortened to land on those
  /// times) and at the end, with the flow and the tracer positions. 0 or no callback: no frames.
  double frame_interval_s = 0.0;
  std::function<void(double t_s, const fluid::FlowState& state, const std::vector<Vec2>& tracers_m)> on_frame;
};

/// A velocity component sampled along a line: positions (m) and values (m/s).
struct CentrelineProfile {
  std::vector<double> position_m;
  std::vector<double> velocity_m_per_s;
};

/// The primary vortex: where the stream function (fluid::stream_function_at_nodes, ψ = 0 on the
/// walls, ψ < 0 for the clockwise vortex under a lid moving in +x) has its minimum.
struct PrimaryVortex {
  Vec2 centre_m{};                        ///< the minimum node, refined by a paraboloid fit
  double stream_function_m2_per_s = 0.0;  ///< ψ_min: the paraboloid's value at the centre
};

/// Differences to Ghia et al. (1982) at their tabulated points (Re = 100, 400, 1000, 3200).
struct GhiaComparison {
  double reynolds = 0.0;
  std::span<const fluid::ProfilePoint> reference_u;  ///< Table I for this Re
  std::span<const fluid::ProfilePoint> reference_v;  ///< Table II for this Re
  std::vector<double> u_error;  ///< computed − reference at the reference_u points
  std::vector<double> v_error;  ///< computed − reference at the reference_v points
  double max_abs_u_error = 0.0;
  double max_abs_v_error = 0.0;  ///< without a misprinted point (GhiaCavityReference)
  PrimaryVortex vortex;                  ///< computed (find_primary_vortex)
  fluid::GhiaVortex reference_vortex{};  ///< Table V
  Vec2 vortex_centre_error_m{};          ///< computed − reference centre
  double psi_min_error = 0.0;            ///< computed − reference ψ_min
};

struct DrivenCavityResult {
  CentrelineProfile centreline_u;  ///< u along the vertical centreline x = L/2 (position = y)
  CentrelineProfile centreline_v;  ///< v along the horizontal centreline y = L/2 (position = x)
  std::optional<GhiaComparison> ghia;  ///< present when Ghia et al. tabulate Re and L = U = 1
  PrimaryVortex primary_vortex;        ///< of the final state
  double viscosity_m2_per_s = 0.0;
  double simulated_time_s = 0.0;
  int steps = 0;           ///< solver sub-steps taken
  bool steady = false;
  double final_change_rate = 0.0;  ///< max|Δu|/Δt · L/U² at the end
  /// The convergence history: after each step of at least half the regular size (shorter ones,
  /// landing on a frame or the end, measure round-off), its time and change rate.
  std::vector<std::array<double, 2>> history;
  double max_divergence_per_s = 0.0;
  double wall_time_s = 0.0;
  std::vector<std::string> messages;  ///< e.g. Δt reductions (first few)
  fluid::FlowState final_state;
  std::vector<Vec2> final_tracers_m;
};

DrivenCavityResult run_driven_cavity(const DrivenCavitySettings& settings);

/// Samples u along x = x0 (rows of cell centres plus both walls) and v along y = y0.
CentrelineProfile vertical_centreline_u(const fluid::FlowState& s, double x_m);
CentrelineProfile horizontal_centreline_v(const fluid::FlowState& s, double y_m);
/// Location and ψ of the stream function's minimum: the minimum interior node, refined by the
/// least-squares paraboloid through its 3 × 3 neighbourhood (exact for a quadratic ψ); the node
/// itself where that paraboloid has no minimum within one cell of it.
PrimaryVortex find_primary_vortex(const fluid::FlowState& s);
/// The comparison with Ghia et al. for a unit cavity with unit lid speed at this Re; nullopt
/// when they have no table for it (fluid::ghia_reference).
std::optional<GhiaComparison> compare_with_ghia(const fluid::FlowState& s, double reynolds);
/// compare_with_ghia(s, 100).
GhiaComparison compare_with_ghia_re100(const fluid::FlowState& s);

/// Thesis Figure 8.7: both solvers and several viscosities on a 30 × 30 unit cavity with Δt = 1/30.
struct CavityFigureSettings {
  std::vector<double> viscosities_m2_per_s{0.1, 0.01, 0.001};
  int cells = 30;
  double time_step_s = 1.0 / 30.0;
  double duration_s = 20.0;
  std::string pressure_solver = "multigrid";
};

struct CavityFigurePanel {
  std::string solver;
  double viscosity_m2_per_s = 0.0;
  DrivenCavityResult result;
};

/// One panel per (solver, viscosity), Eulerian first. The Eulerian solver keeps Δt = 1/30 as the
/// frame step but splits it into stable sub-steps where eqs. 4.8–4.9 demand (see messages).
std::vector<CavityFigurePanel> run_cavity_figure_8_7(const CavityFigureSettings& settings);

}  // namespace jellysim::studies
