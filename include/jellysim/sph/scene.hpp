#pragma once
// A scene of the particle-fluid model (thesis ch. 5): free particles (SPH fluid and solid point
// masses), one spring-mass body with a collision outline and optional muscles, static walls; the
// whole as one ODE (§5.3), and the time loop that follows every accepted step with the collision
// pass of §5.2 and limits steps by eq. 5.31.
#include "jellysim/elastic/body.hpp"
#include "jellysim/ode/integrator.hpp"
#include "jellysim/sim/time_stepping.hpp"
#include "jellysim/ode/newton_krylov.hpp"
#include "jellysim/sph/collisions.hpp"
#include "jellysim/sph/fluid.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace jellysim::sph {

struct Scene {
  /// Free particles: the first `fluid_count` feel SPH forces, the rest are solid point masses.
  std::vector<Vec2> position, velocity;  ///< m, m/s
  std::vector<double> mass;              ///< kg, > 0
  std::size_t fluid_count = 0;
  Vec2 particle_gravity{0.0, 0.0};       ///< m/s², on every free particle
  elastic::Body body;                    ///< may have no points; pinned points have infinite mass
  CollisionOutline outline;              ///< the body's colliding edges (never its muscles)
  /// Sets time-dependent rest lengths (muscles) before the body's forces are evaluated at t.
  std::function<void(double t, elastic::Body& body)> muscles;
  std::vector<Wall> walls;
  SphParameters sph;
  CollisionSettings collision;
  int threads = 1;                       ///< threads for the SPH evaluation; 0: one per core
};

/// Throws std::invalid_argument when the scene is inconsistent (sizes, masses, outline indices,
/// prescribed body points, which this model does not support).
void validate(const Scene& scene);

/// y = [particle positions, body positions, particle velocities, body velocities] (x, y interleaved).
class CoupledSystem final : public ode::OdeSystem {
 public:
  explicit CoupledSystem(Scene& scene);
  Eigen::Index dimension() const override;
  Eigen::Index position_size() const override { return dimension() / 2; }

  ode::Vector pack_state() const;
  /// Copies y into the scene's particles and body points.
  void unpack_state(const ode::Vector& y) const;
  const SphFluid& fluid() const { return *fluid_; }

 protected:
  void compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const override;
  /// The stage state is formed inside the evaluation's parallel region: each thread forms the
  /// entries of its own particles before loading them (bit for bit the default's vector sums).
  void compute_stage_derivative(double t, const ode::Vector& y, double h, std::span<const double> weights,
                                std::span<const ode::Vector> k, ode::Vector& y_stage,
                                ode::Vector& dydt) const override;

 private:
  struct StageSum;
  /// y' at y; when `sum` is given, y is its output, formed part by part first.
  void evaluate(double t, const ode::Vector& y, const StageSum* sum, ode::Vector& dydt) const;
  void rest_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const;

  Scene& scene_;
  std::unique_ptr<SphFluid> fluid_;
  mutable elastic::Body body_;  ///< working copy (muscles change its rest lengths)
  mutable std::vector<Vec2> af_, xb_, vb_, fb_;
};

/// Particles released at a fixed interval from a fixed point (Figure 8.4).
struct Emitter {
  double interval_s = 0.0;  ///< 0: no emitter; the first particle leaves at t = 0
  Vec2 position, velocity;
  double mass_kg = 1.0;
  std::size_t max_count = 0;
};

struct RunSettings {
  sim::TimeSettings time;
  /// "embedded" (the method's embedded pair; step doubling when it has none) or "step-doubling".
  std::string error_control = "embedded";
  bool thin_boundary_limit = true;  ///< eq. 5.31
  double max_speed = 1e3;           ///< a particle or body point faster than this stops the run (m/s)
  Emitter emitter;
  ode::NewtonKrylovSettings newton; ///< backward Euler's Jacobian-free Newton–Krylov solve
};

struct RunResult {
  sim::RunStatistics statistics;
  CollisionStatistics collisions;
  double boundary_width_m = 0.0;  ///< w_b of eq. 5.31 (inf without a body)
  int threads = 1;                     ///< threads of the SPH evaluation
  std::int64_t parallel_evaluations = 0;  ///< SPH evaluations run on all threads (see PathChooser)
  std::int64_t list_rebuilds = 0;         ///< SPH evaluations that rebuilt the neighbour lists
  bool failed = false;
  std::string failure;
};

/// Called at t = 0 and at every frame with the scene holding the state at t; returns a problem
/// description to stop the run, or an empty string.
using SceneFrameCallback = std::function<std::string(double t, const Scene& scene, const CoupledSystem& system)>;

/// Integrates the scene to settings.time.duration. Never throws for a diverging run.
RunResult run(Scene& scene, const RunSettings& settings, const SceneFrameCallback& on_frame,
              const sim::ProgressCallback& progress = {});

/// Wraps an integrator so that the adaptive controller uses step doubling even when the method has
/// an embedded pair (Figure 8.6's SD variants).
std::unique_ptr<ode::Integrator> without_embedded_pair(std::unique_ptr<ode::Integrator> inner);

/// Kinetic energy of particles and free body points (J per unit depth).
double kinetic_energy(const Scene& scene);
/// Total momentum of particles and free body points (kg m/s).
Vec2 momentum(const Scene& scene);

}  // namespace jellysim::sph
