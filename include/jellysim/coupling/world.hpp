#pragma once
// A coupled world: one spring body holding the markers of every body in the tank, the grid fluid,
// the immersed-boundary coupling between them (§4.3.2) and passive tracers. It is the one copy of
// a simulation's state: scene objects (jellyfish, obstacles) refer to their markers in body() by
// index and actuate them there. When the scene is its own mirror image it keeps the symmetry
// exactly and may solve only the east half of the tank (fluid/flow_mirror.hpp); flow() always shows the
// whole tank. Knows nothing of jellyfish, files or pixels.
#include <memory>
#include <string>
#include <vector>

#include "jellysim/coupling/immersed_boundary.hpp"
#include "jellysim/fluid/poisson.hpp"
#include "jellysim/fluid/schemes.hpp"
#include "jellysim/fluid/tracers.hpp"

namespace jellysim::coupling {

/// Whether a simulation keeps the mirror symmetry of a mirror-symmetric scene (fluid/flow_mirror.hpp).
enum class MirrorSymmetry {
  none,       ///< never: round-off grows into the 2D wake instability (the solver's own symmetry)
  automatic,  ///< when the scene is its own mirror image about the tank's centre line, else none
  mirror,     ///< always; a scene that is not its own mirror image is an error
};

/// The tank of water. Defaults here and in jellyfish::JellyfishSpec, CouplingSettings and
/// StabilityLimits are the built-in scene's (scene/jellyfish_scene.cpp; the test
/// SceneParameters.SpecDefaultsAreTheBuiltInScene).
struct TankSpec {
  double width_m = 0.24;
  double height_m = 0.48;
  int cells_x = 384;
  int cells_y = 768;
  std::string solver = "semi-lagrangian";
  fluid::ConvectionScheme convection = fluid::ConvectionScheme::donor_cell;  ///< of the Eulerian solver
  fluid::AdvectionScheme advection = fluid::AdvectionScheme::maccormack;    ///< of the semi-Lagrangian one
  std::string pressure_solver = "fft";
  double pressure_tolerance = 1e-8;  ///< relative max-norm residual of every pressure solve
  double viscosity_m2_per_s = 1.304e-5;
  double density_kg_per_m3 = 1000.0;
  fluid::Boundaries boundaries = fluid::Boundaries::all(fluid::BoundaryType::free_slip);
  int tracers_per_side = 40;  ///< marker particles on a lattice over the whole tank (Figs 8.11/8.12)
  Vec2 current_m_per_s{};    ///< uniform background flow at t = 0 (with inflow/outflow or periodic sides)
  MirrorSymmetry symmetry = MirrorSymmetry::automatic;
  /// While the mirror symmetry is kept, solve only the east half of the tank, with a symmetry
  /// plane (a free-slip wall) on the centre line: half the fluid. Needs an even cells_x.
  bool half_tank = true;
  /// planar: the slice is a plane section of an infinitely deep body (the thesis); axisymmetric:
  /// the tank is the (r, z) half plane of a cylinder whose axis is the centre line x = width/2,
  /// every marker a ring about it (fluid::Geometry). Axisymmetric tanks solve the east half and
  /// need a scene that is its own mirror image (the slice of a body of revolution).
  fluid::Geometry geometry = fluid::Geometry::planar;
};

/// The largest marker spacing Peskin's rule allows on a tank: half the smaller cell size.
double peskin_spacing(const TankSpec& tank);

class World {
 public:
  /// A tank at rest (or with its current) around `body`. `actuate` sets the body's time-dependent
  /// springs before each force evaluation. `mirror_partners` (elastic/body_mirror.hpp: per point its
  /// mirror image about x = width/2) non-empty keeps the mirror symmetry, solving the east half
  /// when tank.half_tank and cells_x is even; the caller checks that the scene is symmetric.
  World(const TankSpec& tank, std::unique_ptr<elastic::Body> body, const CouplingSettings& coupling,
        Actuator actuate, std::vector<int> mirror_partners = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  double time_s() const { return coupling_->time_s(); }
  long steps() const { return coupling_->steps(); }
  /// The largest stable coupled step now (eqs. 4.8, 4.9; CouplingSettings).
  double next_time_step() const { return coupling_->next_time_step(); }
  /// One coupled step of dt_s; then the mirror symmetry is kept and the tracers are advected.
  CoupledStepReport step(double dt_s);

  const TankSpec& tank() const { return tank_; }
  elastic::Body& body() { return *body_; }
  const elastic::Body& body() const { return *body_; }
  /// The fluid being solved (the east half while solving_half_tank()).
  const fluid::FluidSolver& fluid() const { return *fluid_; }
  /// The flow in the whole tank (unfolded from the east half when solving the half tank).
  const fluid::FlowState& flow() const;
  const fluid::Tracers& tracers() const { return tracers_; }

  bool mirror_symmetric() const { return mirror_active_; }
  bool solving_half_tank() const { return half_tank_; }
  /// Per point of body(), its mirror image (empty when no symmetry was kept from the start).
  const std::vector<int>& mirror_partners() const { return mirror_partner_; }
  /// Stops keeping the mirror symmetry (a live edit broke it) and continues on the whole tank.
  /// An axisymmetric tank keeps it always: throws std::invalid_argument.
  void end_mirror_symmetry();
  bool axisymmetric() const { return tank_.geometry == fluid::Geometry::axisymmetric; }
  /// Checkpoints (core/state_archive.hpp): every marker's position and velocity and the springs'
  /// actuated rest lengths and constants, the fluid, the coupling, the tracers, the symmetry kept.
  /// Restores into a world built from the same scene (a mismatch is core::StateMismatch).
  void archive(core::StateArchive& a);

  // ---- Live edits ----
  void set_viscosity(double nu_m2_per_s) { fluid_->set_viscosity(nu_m2_per_s); }
  /// Adds a Gaussian velocity splat Δu·exp(−r²/radius²) to the fluid; the next step's projection
  /// makes it divergence-free. Ends the mirror symmetry, except in an axisymmetric tank, where the
  /// splat (at a point east of the axis) is a ring.
  void stir(Vec2 at_m, Vec2 delta_velocity_m_per_s, double radius_m);

 private:
  /// A fluid solver for the whole tank or its east half, at rest or with the current.
  std::unique_ptr<fluid::FluidSolver> make_fluid(bool east_half) const;
  std::unique_ptr<ImmersedBoundary> make_coupling(bool east_half);
  void leave_half_tank();

  TankSpec tank_;
  CouplingSettings coupling_settings_;
  Actuator actuate_;
  std::unique_ptr<elastic::Body> body_;
  std::unique_ptr<fluid::FluidSolver> fluid_;
  std::unique_ptr<ImmersedBoundary> coupling_;
  fluid::Tracers tracers_;
  std::vector<int> mirror_partner_;
  bool mirror_active_ = false;
  bool half_tank_ = false;
  mutable fluid::FlowState unfolded_;  ///< flow() of the half tank, for the step it was made at
  mutable long unfolded_step_ = -1;
};

}  // namespace jellysim::coupling
