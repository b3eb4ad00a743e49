#include "jellysim/sim/time_stepping.hpp"

#include <cmath>
#include <sstream>

namespace jellysim::sim {
namespace {

std::string diverged_message(double t, std::int64_t step, const std::string& what) {
  std::ostringstream s;
  s << "simulation diverged at t = " << t << " s (step " << step << "): " << what;
  return s.str();
}

}  // namespace

std::string check_finite(const ode::Vector& y) {
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    if (!std::isfinite(y[i])) return "state component " + std::to_string(i) + " is not finite";
  }
  return {};
}

RunOutcome integrate(const ode::OdeSystem& system, ode::Vector& y, const TimeSettings& settings,
                     const FrameCallback& on_frame, const ProgressCallback& on_progress) {
  RunOutcome outcome;
  auto integrator = ode::make_integrator(settings.integrator);
  ode::AdaptiveStepper adaptive(*integrator, settings.tolerances);
  system.reset_counters();
  ode::Vector y_next(y.size());

  double t = 0.0;
  double dt_next = settings.dt;
  // A frame time within this distance of t counts as reached (guards against round-off).
  const double eps = 1e-9 * settings.frame_interval;
  FrameClock clock(settings.frame_interval, settings.duration, eps, FrameClock::Ending::whole_frames);
  ClockedRun run;
  run.time = [&] { return t; };
  run.frame = [&](std::int64_t) -> std::string {
    if (std::string problem = on_frame(t, y); !problem.empty())
      return diverged_message(t, outcome.statistics.steps, problem);
    return {};
  };
  run.step = [&](double t_target) -> StepResult {
    const double dt_limit = t_target - t;
    try {
      if (settings.adaptive) {
        double dt_taken = 0.0;
        dt_next = adaptive.step(system, t, y, dt_next, dt_limit, dt_taken);
        if (std::abs(t - t_target) <= eps) t = t_target;
      } else {
        const double dt = std::min(settings.dt, dt_limit);
        if (!integrator->step(system, t, dt, y, y_next, nullptr).ok) {
          return StepResult::failed_with(diverged_message(
              t, outcome.statistics.steps,
              settings.integrator + " could not complete a step of " + std::to_string(dt) +
                  " s (try a smaller dt or adaptive stepping)"));
        }
        y.swap(y_next);
        t = (dt == dt_limit || std::abs(t + dt - t_target) <= eps) ? t_target : t + dt;
      }
    } catch (const ode::StepSizeUnderflow& e) {
      return StepResult::failed_with(diverged_message(t, outcome.statistics.steps, e.what()));
    }
    ++outcome.statistics.steps;
    if (std::string problem = check_finite(y); !problem.empty())
      return StepResult::failed_with(diverged_message(t, outcome.statistics.steps, problem));
    return {};
  };
  const ClockOutcome clocked = run_frames(clock, run, on_progress);
  outcome.statistics.simulated_seconds = t;
  outcome.statistics.function_evaluations = system.evaluations();
  outcome.statistics.jacobian_evaluations = system.jacobian_evaluations();
  outcome.statistics.rejected_steps = adaptive.statistics().rejected;
  outcome.failed = !clocked.failure.empty();
  outcome.failure = clocked.failure;
  return outcome;
}

}  // namespace jellysim::sim
