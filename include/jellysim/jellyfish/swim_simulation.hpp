#pragma once
// Jellyfish swimming in a grid fluid through the immersed boundary method (thesis §7.1,
// §8.1.4–8.2.1), and beyond the thesis a tank with more than one thing in it: several jellyfish,
// rigid obstacles (fixed or on a prescribed path) and a background current. All bodies are
// markers of one coupled spring body in one coupling::World (the one copy of the state), so they
// push water at each other through the one fluid; the jellyfish actuate their springs there.
// The simulation steps to each output frame, or one step at a time for an interactive viewer,
// and accepts live edits (frequency, contraction, stiffness, viscosity, dragging, stirring).
// Knows nothing of files or pixels.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "jellysim/coupling/world.hpp"
#include "jellysim/jellyfish/ib2d_object.hpp"
#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/jellyfish/obstacle.hpp"
#include "jellysim/sim/frame_clock.hpp"
#include "jellysim/sim/time_stepping.hpp"

namespace jellysim::jellyfish {

struct SwimSettings {
  coupling::TankSpec tank;
  std::vector<JellyfishSpec> school;     ///< every jellyfish in the tank (may be empty)
  std::vector<ObstacleSpec> obstacles;   ///< rigid obstacles
  std::vector<Ib2dObjectSpec> structures;  ///< IB2d structures (scene objects of type "ib2d")
  double obstacle_max_displacement_m = 0.0;  ///< tether stretch that stops the run; 0: one cell
  coupling::CouplingSettings coupling;
  coupling::StabilityLimits limits;
  double duration_s = 5.0 / 0.7;  ///< five contraction cycles at 0.7 Hz
  double frame_interval_s = 1.0 / 30.0;
  /// Frames a second (output.fps), > 0: frame k at k / frames_per_second exactly, and
  /// frame_interval_s is its reciprocal; 0: frames at k·frame_interval_s.
  double frames_per_second = 0.0;

  /// The run's frame clock to `duration_s` (simulate's: the last frame is the one nearest the
  /// duration, at its grid time).
  sim::FrameClock frame_clock(double duration_s) const;
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
  /// Steps to settings().duration_s, calling on_frame at every frame. A simulation restored from a
  /// checkpoint taken at frame k (restore_state) continues with frames_recorded = k + 1: the first
  /// frame it records is k + 1, and the stats count the whole run. `done`, when given, is asked
  /// before every step: true ends the run there, early and not as a failure (a loop is recorded).
  SwimRunStats run(const FrameCallback& on_frame, const sim::ProgressCallback& progress = {},
                   std::int64_t frames_recorded = 0, const std::function<bool()>& done = {});

  /// Checkpoints (issue 23, core/state_archive.hpp): everything a run changes — the world (fluid,
  /// markers, springs, coupling, tracers), each jellyfish's controllers and steering, obstacle
  /// drags, the run's step statistics. save_state only reads the simulation.
  void save_state(core::StateArchive& a) const;
  /// Restores a saved state into a simulation built from the same settings; throws
  /// core::StateMismatch when the checkpoint is of another scene.
  void restore_state(core::StateArchive& a);

  /// One coupled step of the largest stable size, at most max_dt_s; advects the tracers and checks
  /// for instability. For interactive use; run() calls it too.
  SwimStep step(double max_dt_s = INFINITY);
  /// One step toward an output frame's time, landing on it without a sliver step before it: run()'s
  /// steps (also the Python module's Simulation.advance, which must take the same steps).
  SwimStep step_toward(double frame_time_s);

  double time_s() const { return world_->time_s(); }
  long steps() const { return world_->steps(); }
  /// The tank, its fluid and every marker: the one copy of the state.
  const coupling::World& world() const { return *world_; }
  const SwimSettings& settings() const { return settings_; }
  std::size_t jellyfish_count() const { return school_.size(); }
  const Jellyfish& jellyfish(std::size_t i = 0) const;
  std::size_t obstacle_count() const { return obstacles_.size(); }
  /// The obstacle's outline markers as they are now (counter-clockwise, closed implicitly).
  std::vector<Vec2> obstacle_outline(std::size_t i) const;
  /// Force of the fluid on the obstacle, N per metre of depth (drag and lift); in an axisymmetric
  /// tank the force on the body of revolution (N, along the axis).
  Vec2 obstacle_force(std::size_t i) const;
  /// Volume of fluid crossing the obstacle's outline per second and metre of depth (m²/s),
  /// relative to the outline's own motion: ½∮|(u − u_outline)·n| ds. Zero for a perfect wall. In
  /// an axisymmetric tank through the surface of revolution (m³/s).
  double obstacle_leakage(std::size_t i) const;
  std::size_t structure_count() const { return structures_.size(); }
  /// Where IB2d structure i's markers, springs and targets are in body().
  const Ib2dParts& structure(std::size_t i) const { return structures_.at(i); }
  /// Centroid of IB2d structure i's vertices that are not target points (e.g. a bell and its
  /// muscle markers, without the targets that hold a flow blocker).
  Vec2 structure_centroid(std::size_t i) const;
  /// Every marker of every body in one spring body (jellyfish, then obstacles, then IB2d structures).
  const elastic::Body& body() const { return world_->body(); }
  /// The flow in the whole tank (unfolded from the east half when solving the half tank).
  const fluid::FlowState& flow() const { return world_->flow(); }
  /// True while only the east half of the tank is solved (coupling::TankSpec::half_tank).
  bool solving_half_tank() const { return world_->solving_half_tank(); }
  const fluid::Tracers& tracers() const { return world_->tracers(); }
  /// The problem that should stop the run now, or "".
  std::string check() const;
  /// True when every marker's position and velocity is finite: a state that can be recorded as a
  /// frame (a failed step's state is kept as the last frame only then).
  bool finite_state() const;
  /// True while every step keeps the scene's mirror symmetry (coupling::TankSpec::symmetry).
  bool mirror_symmetric() const { return world_->mirror_symmetric(); }
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
  /// Axisymmetric tanks: scales an obstacle's tethers to hold whole rings.
  void make_ring_tethers(const ObstacleParts& parts, double spacing, elastic::Body& body) const;
  /// One coupled step of exactly dt_s (at most the stable step), then the checks.
  SwimStep advance(double dt_s);
  /// Both directions of save_state/restore_state.
  void archive(core::StateArchive& a);
  /// Why the scene is not its own mirror image (coupling::TankSpec::symmetry), "" when it is; on success
  /// fills the point and jellyfish mirror partners.
  std::string mirror_problem(const elastic::Body& body, std::vector<int>& partners);
  /// A live edit that makes the scene asymmetric ends the mirror symmetry, saying why.
  void end_mirror_symmetry(const std::string& why);
  /// Edits of one jellyfish keep the symmetry only if it is its own mirror image.
  void edit_of_jellyfish(std::size_t jellyfish, const char* what);

  SwimSettings settings_;
  std::vector<std::unique_ptr<Jellyfish>> school_;  ///< their markers live in world_->body()
  std::vector<ObstacleParts> obstacles_;
  std::vector<Ib2dParts> structures_;
  std::unique_ptr<coupling::World> world_;
  std::vector<double> strain_reference_;  ///< rest lengths at build time (muscles uncontracted)
  std::string mirror_note_;
  std::vector<int> jellyfish_mirror_;  ///< per jellyfish, the one that is its mirror image
  // The run's step statistics (SwimRunStats), kept across a checkpoint.
  double smallest_step_s_ = INFINITY, largest_step_s_ = 0.0;
  long krylov_iterations_ = 0;
  double earlier_wall_seconds_ = 0.0;  ///< wall-clock of the run before its checkpoint
  std::chrono::steady_clock::time_point run_start_{};  ///< when run() began (this process)
};

/// What a swim simulation will allocate, worked out from its settings before anything is built
/// (issue 23). Measured on this machine's Release build (docs/jellyfish.md, "Memory"): about 25 MB
/// for the program, 200 B per fluid cell on the half tank and 450 on the whole one, and the
/// marker-space solve's dense matrices, about 26 B per entry of a 2N × 2N matrix.
struct MemoryEstimate {
  double cells = 0.0;    ///< fluid cells of the whole tank
  double markers = 0.0;  ///< every body's points (targets included)
  double frames = 0.0;   ///< recorded frames
  double bytes = 0.0;    ///< the estimate (an upper bound with a margin)
  std::string breakdown; ///< "cells …, markers …, frames …": what drives it
};
MemoryEstimate estimate_memory(const SwimSettings& settings);

/// Checks what an axisymmetric tank needs (coupling::TankSpec::geometry): jellyfish on the axis, no
/// planar obstacles, an even cell count, settings the axisymmetric solvers have; throws
/// std::invalid_argument saying which. Nothing for planar tanks.
void validate_geometry(const SwimSettings& settings);

/// Checks that bodies lie inside the tank and do not overlap one another (and validate_geometry); throws
/// std::invalid_argument naming the bodies ("jellyfish 2", "objects[1] (circle)").
void validate_layout(const SwimSettings& settings);

/// Why the scene is not its own mirror image about the tank's centre line x = width/2 (walls,
/// current, bodies and springs, contraction and steering), or "" when it is.
std::string mirror_symmetry_problem(const SwimSettings& settings);

}  // namespace jellysim::jellyfish
