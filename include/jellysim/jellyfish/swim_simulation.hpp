#pragma once
// Jellyfish swimming in a grid fluid through the immersed boundary method (thesis §7.1,
// §8.1.4–8.2.1), and beyond the thesis a tank with more than one thing in it: several jellyfish,
// rigid obstacles (fixed or on a prescribed path) and a background current. All bodies are
// markers of one coupled spring body, so they push water at each other through the one fluid.
// The simulation steps to each output frame, or one step at a time for an interactive viewer,
// and accepts live edits (frequency, contraction, stiffness, viscosity, dragging, stirring).
// Knows nothing of files or pixels.
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "jellysim/coupling/immersed_boundary.hpp"
#include "jellysim/fluid/tracers.hpp"
#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/jellyfish/obstacle.hpp"
#include "jellysim/sim/time_stepping.hpp"

namespace jellysim::jellyfish {

/// Whether the simulation keeps the mirror symmetry of a mirror-symmetric scene (fluid/mirror.hpp).
enum class MirrorSymmetry {
  none,       ///< never: round-off grows into the 2D wake instability (the solver's own symmetry)
  automatic,  ///< when the scene is its own mirror image about the tank's centre line, else none
  mirror,     ///< always; a scene that is not its own mirror image is an error
};

/// Defaults here and in JellyfishSpec, CouplingSettings and StabilityLimits are the built-in scene's
/// (scene/jellyfish_scene.cpp; the test SceneParameters.SpecDefaultsAreTheBuiltInScene).
struct TankSpec {
  double width_m = 0.24;
  double height_m = 0.32;
  int cells_x = 96;
  int cells_y = 128;
  std::string solver = "eulerian";
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
};

struct SwimSettings {
  TankSpec tank;
  std::vector<JellyfishSpec> school;     ///< every jellyfish in the tank (may be empty)
  std::vector<ObstacleSpec> obstacles;   ///< rigid obstacles
  double obstacle_max_displacement_m = 0.0;  ///< tether stretch that stops the run; 0: one cell
  coupling::CouplingSettings coupling;
  coupling::StabilityLimits limits;
  double duration_s = 10.0 / 0.7;  ///< ten contraction cycles at 0.7 Hz
  double frame_interval_s = 1.0 / 30.0;

  /// The first jellyfish (the one metrics.csv describes); throws when there is none.
  const JellyfishSpec& jellyfish() const;
};

struct SwimRunStats {
  long steps = 0;
  double simulated_seconds = 0.0;
  double wall_seconds = 0.0;
  double smallest_step_s = 0.0;
  double largest_step_s = 0.0;
  long krylov_iterations = 0;
  bool mirror_symmetric = false;  ///< the run kept the mirror symmetry (to its end)
  bool half_tank = false;         ///< the run solved the east half of the tank (to its end)
  std::string symmetry_note;      ///< why it did not, if symmetry was asked for
  std::string failure;  ///< "numerical instability: …" or "structural instability: …" with when/where
};

/// One coupled step taken by SwimSimulation::step.
struct SwimStep {
  double dt_s = 0.0;
  int krylov_iterations = 0;
  std::string failure;  ///< non-empty: the run cannot go on (the state that failed is kept)
};

class SwimSimulation {
 public:
  explicit SwimSimulation(const SwimSettings& settings);
  ~SwimSimulation();

  /// Called at t = 0 and at every frame time; a non-empty return stops the run with that failure.
  using FrameCallback = std::function<std::string(const SwimSimulation&)>;
  SwimRunStats run(const FrameCallback& on_frame, const sim::ProgressCallback& progress = {});

  /// One coupled step of the largest stable size, at most max_dt_s; advects the tracers and checks
  /// for instability. For interactive use; run() calls it too.
  SwimStep step(double max_dt_s = INFINITY);

  double time_s() const { return coupling_->time_s(); }
  long steps() const { return coupling_->steps(); }
  const SwimSettings& settings() const { return settings_; }
  std::size_t jellyfish_count() const { return school_.size(); }
  const Jellyfish& jellyfish(std::size_t i = 0) const;
  std::size_t obstacle_count() const { return obstacles_.size(); }
  /// The obstacle's outline markers as they are now (counter-clockwise, closed implicitly).
  std::vector<Vec2> obstacle_outline(std::size_t i) const;
  /// Force of the fluid on the obstacle, N per metre of depth (drag and lift).
  Vec2 obstacle_force(std::size_t i) const;
  /// Volume of fluid crossing the obstacle's outline per second and metre of depth (m²/s),
  /// relative to the outline's own motion: ½∮|(u − u_outline)·n| ds. Zero for a perfect wall.
  double obstacle_leakage(std::size_t i) const;
  /// Every marker of every body in one spring body (jellyfish first, then obstacles).
  const elastic::Body& body() const { return body_; }
  /// The flow in the whole tank (unfolded from the east half when solving the half tank).
  const fluid::FlowState& flow() const;
  /// True while only the east half of the tank is solved (TankSpec::half_tank).
  bool solving_half_tank() const { return half_tank_; }
  const fluid::Tracers& tracers() const { return tracers_; }
  /// The problem that should stop the run now, or "".
  std::string check() const;
  /// True while every step keeps the scene's mirror symmetry (TankSpec::symmetry).
  bool mirror_symmetric() const { return mirror_active_; }
  /// Why the mirror symmetry is not kept (the scene is not symmetric, or a live edit broke it), or "".
  const std::string& mirror_symmetry_note() const { return mirror_note_; }

  // ---- Live edits (the interactive viewer) ----
  /// Changes the contraction frequency keeping the current phase continuous.
  void set_frequency(std::size_t jellyfish, double hz);
  /// Changes γ, the contracted rest-length fraction (eq. 7.5), in (0, 1].
  void set_gamma(std::size_t jellyfish, double gamma);
  /// Scales the stiffness of the umbrella and tentacle springs relative to the spec's (> 0).
  void set_stiffness_scale(std::size_t jellyfish, double scale);
  /// Steers the jellyfish toward a point, or stops steering (nullopt).
  void set_steer_target(std::size_t jellyfish, std::optional<Vec2> target_m);
  void set_viscosity(double nu_m2_per_s);
  /// Adds a Gaussian velocity splat Δu·exp(−r²/radius²) to the fluid (stirring with the mouse);
  /// the next step's projection makes it divergence-free.
  void stir(Vec2 at_m, Vec2 delta_velocity_m_per_s, double radius_m);
  /// Moves a whole jellyfish (its markers) by delta (dragging with the mouse).
  void move_jellyfish(std::size_t jellyfish, Vec2 delta_m);
  /// Moves an obstacle's targets and markers by delta.
  void move_obstacle(std::size_t obstacle, Vec2 delta_m);

 private:
  /// One coupled step of exactly dt_s (at most the stable step), then the checks.
  SwimStep advance(double dt_s);
  void actuate(double t);
  void copy_back_to_jellyfish();
  /// A fluid solver for the whole tank or its east half, at rest or with the current.
  std::unique_ptr<fluid::FluidSolver> make_fluid(bool east_half) const;
  std::unique_ptr<coupling::ImmersedBoundary> make_coupling(bool east_half);
  /// Continues on the whole tank from the unfolded half (a live edit broke the symmetry).
  void leave_half_tank();
  void set_up_mirror_symmetry();
  void keep_mirror_symmetry();
  /// A live edit that makes the scene asymmetric ends the mirror symmetry, saying why.
  void end_mirror_symmetry(const std::string& why);
  /// Edits of one jellyfish keep the symmetry only if it is its own mirror image.
  void edit_of_jellyfish(std::size_t jellyfish, const char* what);

  SwimSettings settings_;
  std::unique_ptr<fluid::FluidSolver> fluid_;
  std::vector<std::unique_ptr<Jellyfish>> school_;
  std::vector<int> jellyfish_offset_;         ///< first point of each jellyfish in body_
  std::vector<int> jellyfish_spring_offset_;  ///< first linear spring of each jellyfish in body_
  std::vector<int> jellyfish_joint_offset_;   ///< first angular spring of each jellyfish in body_
  std::vector<ObstacleParts> obstacles_;
  std::vector<Vec2> obstacle_shift_;          ///< dragging offsets added to the prescribed paths
  elastic::Body body_;
  std::unique_ptr<coupling::ImmersedBoundary> coupling_;
  fluid::Tracers tracers_;
  std::vector<double> strain_reference_;  ///< rest lengths at build time (muscles uncontracted)
  SwimRunStats totals_;
  bool mirror_active_ = false;
  bool half_tank_ = false;
  mutable fluid::FlowState unfolded_;  ///< flow() of the half tank, for the step it was made at
  mutable long unfolded_step_ = -1;
  std::string mirror_note_;
  std::vector<int> mirror_partner_;          ///< per point of body_, its mirror image
  std::vector<int> jellyfish_mirror_;        ///< per jellyfish, the one that is its mirror image
};

/// The largest marker spacing Peskin's rule allows on a tank: half the smaller cell size.
double peskin_spacing(const TankSpec& tank);

/// Checks that bodies lie inside the tank and do not overlap one another; throws
/// std::invalid_argument naming the bodies ("jellyfish 2", "objects[1] (circle)").
void validate_layout(const SwimSettings& settings);

/// Why the scene is not its own mirror image about the tank's centre line x = width/2 (walls,
/// current, bodies and springs, contraction and steering), or "" when it is.
std::string mirror_symmetry_problem(const SwimSettings& settings);

}  // namespace jellysim::jellyfish
