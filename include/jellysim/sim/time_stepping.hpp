#pragma once
// The time loop shared by every simulation: fixed or adaptive steps with any integrator, output
// frames on a clock independent of the step size, divergence checks, and progress reporting.
#include "jellysim/ode/integrator.hpp"
#include "jellysim/sim/frame_clock.hpp"

#include <functional>
#include <string>

namespace jellysim::sim {

struct TimeSettings {
  std::string integrator = "dopri5";
  double dt = 0.01;             ///< fixed step, or the first step when adaptive (s)
  bool adaptive = false;
  ode::AdaptiveSettings tolerances;
  double duration = 1.0;        ///< simulated seconds
  double frame_interval = 0.1;  ///< output frames every this many simulated seconds
};

struct RunStatistics {
  std::int64_t steps = 0;                 ///< accepted steps
  std::int64_t rejected_steps = 0;
  std::int64_t function_evaluations = 0;
  std::int64_t jacobian_evaluations = 0;
  double simulated_seconds = 0.0;
};

/// Called at t = 0 and at every frame time with the current state. Returns an empty string when
/// the state is healthy, or a message saying what went wrong (e.g. "point 7 has a NaN position"),
/// which stops the run.
using FrameCallback = std::function<std::string(double t, const ode::Vector& y)>;

struct RunOutcome {
  RunStatistics statistics;
  bool failed = false;
  std::string failure;   ///< "diverged at t = ... s (step N): ..."
};

/// Integrates `system` from y at t = 0 to settings.duration on the frame clock (frame_clock.hpp):
/// frames land exactly on multiples of frame_interval (the step is shortened to hit them). Never throws for a diverging simulation: the
/// outcome says when and where, and the frames recorded so far stay valid.
RunOutcome integrate(const ode::OdeSystem& system, ode::Vector& y, const TimeSettings& settings,
                     const FrameCallback& on_frame, const ProgressCallback& on_progress = {});

/// Returns "component i is not finite" for the first NaN/inf in y, or an empty string.
std::string check_finite(const ode::Vector& y);

}  // namespace jellysim::sim
