#pragma once
// The swappable fluid solvers behind one small interface: the classical Eulerian method (§4.1)
// and Stam's semi-Lagrangian method (§4.2). Both advance a FlowState on a MAC grid with the same
// boundary conditions, pressure solvers and body accelerations.
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <string_view>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/fluid/projection.hpp"
#include "jellysim/fluid/schemes.hpp"

namespace jellysim::fluid {

/// What the Eulerian solver does with a Δt above its stability limit (eqs. 4.8–4.9).
enum class TimeStepPolicy {
  refuse,  ///< throw std::domain_error with the limit in the message
  reduce,  ///< split the step into stable sub-steps and say so in StepReport::message
};

struct FluidSettings {
  /// Planar flow, or axisymmetric flow without swirl (x = r from the axis, y = z): the grid's
  /// origin must then be on the axis (x = 0) and its west side free-slip (the symmetry condition
  /// u_r = 0, ∂u_z/∂r = 0); the Eulerian solver with donor-cell (γ) convection, or the
  /// semi-Lagrangian solver with any advection scheme.
  Geometry geometry = Geometry::planar;
  double viscosity_m2_per_s = 1.0e-6;  ///< kinematic viscosity ν
  double density_kg_per_m3 = 1000.0;   ///< ρ: pressure p = ρφ (Pa)
  Vec2 gravity_m_per_s2{};             ///< uniform body acceleration added to the face forces
  Boundaries boundaries{};
  std::string pressure_solver = "multigrid";  ///< "sor" or "multigrid"
  PressureSolverSettings pressure{};
  /// Initial guess of each pressure solve: the linear extrapolation in time of the last two
  /// pressures (when nobody edited the pressure in between) instead of the last one alone.
  /// Fewer V-cycles for smoothly changing flows; the solve stops on the same residual either way.
  bool extrapolate_pressure_guess = true;

  // Classical Eulerian method.
  double safety_factor = 0.5;  ///< τ ∈ (0, 1]: Δt_max = τ · min(eq. 4.8, eq. 4.9)
  /// Donor-cell weight γ ∈ [0, 1] of the convective terms (0: central differences). Unset: the
  /// smallest stable value of Griebel et al., γ = max(|u|Δt/Δx, |v|Δt/Δy), chosen every step.
  std::optional<double> donor_cell_blend{};
  TimeStepPolicy time_step_policy = TimeStepPolicy::reduce;
  /// The limited schemes replace γ (donor_cell_blend is then unused) and need a smaller step:
  /// see the second stability_time_step().
  ConvectionScheme convection = ConvectionScheme::donor_cell;

  // Semi-Lagrangian method.
  bool project_before_advection = false;  ///< the extra projection of §4.2.4 (linear advection only)
  double diffusion_tolerance = 1e-8;      ///< relative max-norm residual of eq. 4.17's CG solve
  /// Every scheme but linear also takes the second-order step (Crank–Nicolson along the
  /// trajectories, incremental pressure, extrapolated carrier; docs/fluids.md).
  AdvectionScheme advection = AdvectionScheme::linear;
};

struct StepReport {
  double dt_s = 0.0;  ///< time advanced
  int substeps = 1;
  std::string message;  ///< non-empty when the requested Δt was reduced
  PressureSolveReport pressure{};  ///< of the last projection
  int diffusion_iterations = 0;
};

class FluidSolver {
 public:
  virtual ~FluidSolver() = default;
  FluidSolver(const FluidSolver&) = delete;
  FluidSolver& operator=(const FluidSolver&) = delete;

  virtual std::string_view name() const = 0;
  /// Advances the flow by dt_s seconds.
  virtual StepReport step(double dt_s) = 0;
  /// Largest Δt (s) the solver accepts in one step now (infinity when unconditionally stable).
  virtual double stable_time_step() const = 0;
  /// True when a step of at most stable_time_step() ends with P(u* + Δt a): the body acceleration
  /// enters only as Δt·a added before the one projection, so the step is affine in a.
  virtual bool projects_body_acceleration_linearly() const { return false; }

  FlowState& state() { return state_; }
  const FlowState& state() const { return state_; }
  /// Body accelerations (m/s²) on the faces, applied on every step until changed; zero at start.
  /// The immersed-boundary coupling writes its spread forces / (ρΔxΔy) here (eq. 4.19).
  FaceAccelerations& body_acceleration() { return body_acceleration_; }
  const FluidSettings& settings() const { return settings_; }
  double time_s() const { return time_s_; }
  /// Sets the clock (a solver that takes over another's flow).
  void set_time_s(double t) { time_s_ = t; }
  /// Changes the kinematic viscosity ν (m²/s, ≥ 0) from the next step on (live edits).
  void set_viscosity(double nu_m2_per_s);
  /// Re-applies the boundary conditions to the current velocity (after external edits).
  void apply_boundaries() { apply_velocity_boundaries(state_.velocity, settings_.boundaries); }
  /// Checkpoints (core/state_archive.hpp): the flow, the body accelerations, the clock, the
  /// viscosity and every history a step reads (pressures of the extrapolated guess, the
  /// second-order step's last velocities), so that a restored solver continues bit for bit.
  virtual void archive(core::StateArchive& a);

 protected:
  FluidSolver(const MacGrid& grid, const FluidSettings& settings);
  /// u += Δt (g + a) on the interior faces (thesis §4.2.4 step 1; the f of eq. 4.6).
  void add_body_accelerations(Velocity& vel, double dt_s) const;
  PressureSolveReport project(double dt_s);

  FluidSettings settings_;
  FlowState state_;
  FaceAccelerations body_acceleration_;
  Projector projector_;
  double time_s_ = 0.0;
};

/// The names make_fluid_solver accepts: "eulerian", "semi-lagrangian".
const std::vector<std::string>& fluid_solver_names();
/// "eulerian" or "semi-lagrangian"; throws std::invalid_argument for other names.
std::unique_ptr<FluidSolver> make_fluid_solver(std::string_view name, const MacGrid& grid,
                                               const FluidSettings& settings);

/// The scheme names a solver offers: convection schemes for "eulerian", advection schemes for
/// "semi-lagrangian"; the first is the thesis's.
const std::vector<std::string>& scheme_names_for(std::string_view solver);
/// Sets settings.convection ("eulerian") or settings.advection ("semi-lagrangian") from a name of
/// scheme_names_for(solver); throws std::invalid_argument naming the allowed ones otherwise.
void set_scheme(FluidSettings& settings, std::string_view solver, std::string_view scheme);

/// Eqs. 4.8 and 4.9: τ · min(Δx/max|u|, Δy/max|v|, 1/(2ν) (1/Δx² + 1/Δy²)⁻¹). The maxima run
/// over the faces and, when given, the prescribed side velocities (a moving lid).
double stability_time_step(const Velocity& vel, double viscosity_m2_per_s, double safety_factor,
                           const Boundaries* sides = nullptr);
/// The same for a convection scheme. donor_cell: eqs. 4.8–4.9 as above. The limited schemes:
/// 1/Δt = (2(max|u|/Δx + max|v|/Δy) + 1/Δt_viscous)/τ, i.e. a Courant sum of ½ (forward Euler with
/// a limiter of range [0, 2] is TVD up to there) and eq. 4.9's viscous step, added as rates.
double stability_time_step(const Velocity& vel, double viscosity_m2_per_s, double safety_factor,
                           ConvectionScheme scheme, const Boundaries* sides = nullptr);

}  // namespace jellysim::fluid
