#include "jellyfish/swim_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace jellysim::jellyfish {

namespace {

std::string when(double t, long step) {
  std::ostringstream s;
  s.precision(6);
  s << " at t = " << t << " s (step " << step << ")";
  return s.str();
}

}  // namespace

double peskin_spacing(const TankSpec& tank) {
  return 0.5 * std::min(tank.width_m / tank.cells_x, tank.height_m / tank.cells_y);
}

SwimSimulation::SwimSimulation(const SwimSettings& settings) : settings_(settings) {
  const TankSpec& t = settings_.tank;
  const fluid::MacGrid grid(t.cells_x, t.cells_y, t.width_m, t.height_m);
  fluid::FluidSettings fs;
  fs.viscosity_m2_per_s = t.viscosity_m2_per_s;
  fs.density_kg_per_m3 = t.density_kg_per_m3;
  fs.boundaries = t.boundaries;
  fs.pressure_solver = t.pressure_solver;
  fs.pressure.relative_tolerance = t.pressure_tolerance;
  fs.diffusion_tolerance = std::min(fs.diffusion_tolerance, t.pressure_tolerance);
  fs.safety_factor = 1.0;  // the coupling chooses Δt; the Eulerian solver only guards it
  fluid_ = fluid::make_fluid_solver(t.solver, grid, fs);
  jellyfish_ = std::make_unique<Jellyfish>(settings_.jellyfish);
  Jellyfish* jelly = jellyfish_.get();
  coupling_ = std::make_unique<coupling::ImmersedBoundary>(
      *fluid_, jellyfish_->body(), settings_.coupling, [jelly](double time, elastic::Body&) { jelly->actuate(time); });
  strain_reference_ = jellyfish_->body().linear.rest_length;
  for (std::size_t k = 0; k < jellyfish_->layout().muscle_springs.size(); ++k)
    strain_reference_[static_cast<std::size_t>(jellyfish_->layout().muscle_springs[k])] =
        jellyfish_->layout().muscle_uncontracted_m[k];
  if (t.tracers_per_side > 0) {
    const double margin_x = 0.5 * t.width_m / t.tracers_per_side, margin_y = 0.5 * t.height_m / t.tracers_per_side;
    tracers_ = fluid::Tracers::lattice({margin_x, margin_y}, {t.width_m - margin_x, t.height_m - margin_y},
                                       t.tracers_per_side, t.tracers_per_side);
  }
}

std::string SwimSimulation::check() const {
  std::string problem = coupling::check_stability(fluid_->state(), jellyfish_->body(), settings_.limits, &strain_reference_);
  if (!problem.empty()) return problem;
  if (polyline_self_intersects(jellyfish_->umbrella_points()))
    return "structural instability: the umbrella crossed itself (mesh inversion)";
  return {};
}

SwimRunStats SwimSimulation::run(const FrameCallback& on_frame, const sim::ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  SwimRunStats stats;
  stats.smallest_step_s = INFINITY;
  const double duration = settings_.duration_s;
  const double frame_dt = settings_.frame_interval_s;
  const long frames = std::max(1L, std::lround(duration / frame_dt));
  auto finish = [&]() {
    stats.simulated_seconds = time_s();
    stats.steps = coupling_->steps();
    stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!std::isfinite(stats.smallest_step_s)) stats.smallest_step_s = 0.0;
    return stats;
  };
  if (on_frame) {
    if (std::string stop = on_frame(*this); !stop.empty()) {
      stats.failure = stop;
      return finish();
    }
  }
  for (long f = 1; f <= frames; ++f) {
    const double frame_time = std::min(duration, f * frame_dt);
    while (time_s() < frame_time - 1e-12 * std::max(1.0, frame_time)) {
      double dt = coupling_->next_time_step();
      const double remaining = frame_time - time_s();
      if (dt >= remaining) dt = remaining;
      else if (dt > 0.5 * remaining) dt = 0.5 * remaining;  // avoid a sliver step before the frame
      if (!(dt >= settings_.coupling.min_time_step_s)) {
        stats.failure = "numerical instability: the stable time step fell to " + std::to_string(dt) +
                        " s, below min_time_step" + when(time_s(), coupling_->steps());
        return finish();
      }
      const coupling::CoupledStepReport r = coupling_->step(dt);
      stats.smallest_step_s = std::min(stats.smallest_step_s, dt);
      stats.largest_step_s = std::max(stats.largest_step_s, dt);
      stats.krylov_iterations += r.krylov.iterations;
      if (!tracers_.positions().empty())
        tracers_.advect(fluid_->state().velocity, settings_.tank.boundaries, dt);
      if (std::string problem = check(); !problem.empty()) {
        stats.failure = problem + when(time_s(), coupling_->steps());
        if (on_frame) on_frame(*this);  // keep the state that failed
        return finish();
      }
      if (progress) progress(time_s(), duration, coupling_->steps());
    }
    if (on_frame) {
      if (std::string stop = on_frame(*this); !stop.empty()) {
        stats.failure = stop;
        return finish();
      }
    }
  }
  return finish();
}

}  // namespace jellysim::jellyfish
