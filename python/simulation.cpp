// jellysim.Simulation's state (simulation.hpp): simulate's scene resolution and frame clock over
// SwimSimulation's public API (SwimSimulation::step_toward: run()'s steps).
#include "simulation.hpp"

#include <algorithm>
#include <cmath>

#include "jellysim/core/errors.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellysim/scene/resolve.hpp"
#include "jellysim/sim/frame_clock.hpp"

namespace jellysim::python {

std::atomic<long> Simulation::live_{0};

namespace {

/// simulate's clock (SwimSettings::frame_clock: frame n at n·interval, or n / output.fps, ending on
/// the frame nearest the duration, at its grid time) for a run to duration_s, with the frames
/// recorded so far counted as emitted.
sim::FrameClock simulate_clock(const jellyfish::SwimSettings& settings, double duration_s, std::int64_t frames_emitted) {
  sim::FrameClock clock = settings.frame_clock(duration_s);
  for (std::int64_t k = 0; k < frames_emitted; ++k) clock.frame_emitted();
  return clock;
}

/// The settings simulate runs: without pictures or VTK files the tracers are not advected
/// (experiments::run_swim); they never change the markers.
jellyfish::SwimSettings run_settings(const Scene& scene) {
  jellyfish::SwimSettings s = scene.settings;
  if (!scene.output.vtk && !scene.output.pictures && !scene.output.record_tracers) s.tank.tracers_per_side = 0;
  return s;
}

}  // namespace

Scene resolve_scene(const config::Config* overlay, const std::string& overlay_name, const std::vector<std::string>& sets) {
  scene::ConfigSources sources{{}, overlay_name, "jellyfish", false, sets};
  if (overlay) sources.scene_file = *overlay;
  Scene scene{scene::resolve_config(scene::builtin_jellyfish_scene(), sources, "the jellyfish scene"), {}, {}};
  scene.settings = scene::read_swim_settings(scene.config);
  scene.output = experiments::read_output_options(scene.config);
  return scene;
}

Simulation::Simulation(const Scene& scene)
    : scene_(scene), sim_(std::make_unique<jellyfish::SwimSimulation>(run_settings(scene))) {
  ++live_;
  record_frame();  // simulate's frame 0, at t = 0
}

Simulation::~Simulation() { --live_; }

void Simulation::record_frame() {
  if (sim_->jellyfish_count() > 0) frames_.push_back(sim_->jellyfish().slice_frame(sim_->time_s()));
  ++frames_emitted_;
}

std::string Simulation::step_toward(double frame_time) {
  if (!failure_.empty()) return failure_;
  const jellyfish::SwimStep s = sim_->step_toward(frame_time);  // SwimSimulation::run's steps
  if (s.failure.empty()) return {};
  // As run(): the state that failed is kept as a last frame when a step was taken.
  if (s.dt_s >= scene_.settings.coupling.min_time_step_s && sim_->jellyfish_count() > 0 && sim_->finite_state())
    frames_.push_back(sim_->jellyfish().slice_frame(sim_->time_s()));
  failure_ = s.failure;
  return failure_;
}

void Simulation::step() {
  // One step toward the next frame on simulate's clock, the frame recorded when it is due.
  const double interval = scene_.settings.frame_interval_s;
  const sim::FrameClock clock =
      simulate_clock(scene_.settings, static_cast<double>(frames_emitted_) * interval, frames_emitted_);
  if (std::string failure = step_toward(clock.target()); !failure.empty()) throw RunError(failure);
  if (clock.due(sim_->time_s())) record_frame();
}

bool Simulation::advance(double seconds, const std::function<bool()>& stop) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds))
    throw InputError("advance: seconds must be a finite number >= 0, got " + std::to_string(seconds));
  if (!failure_.empty()) throw RunError(failure_);
  // The durations asked for add up (advance(0.5) twice ends where advance(1.0) does), counted from
  // the time reached when step() went beyond them.
  const double requested = std::max(requested_s_, sim_->time_s()) + seconds;
  const double interval = scene_.settings.frame_interval_s;
  if (!(requested / interval <= 4503599627370496.0))  // 2^52 frames: FrameClock's limit
    throw InputError("advance: " + std::to_string(requested) + " s in all is more than 2^52 frames of " +
                     std::to_string(interval) + " s");
  requested_s_ = requested;
  // The frame nearest the total asked for, at its whole-frame time: every split of the same total
  // ends on the same frame, on simulate's clock (frame n at n·interval). When that frame is
  // recorded already (advance(0), advance(0.01) with 1/30 s frames) there is nothing to do.
  const auto last = static_cast<std::int64_t>(std::llround(requested / interval));
  if (last < frames_emitted_) return true;
  const double duration = static_cast<double>(last) * interval;
  sim::FrameClock clock = simulate_clock(scene_.settings, duration, frames_emitted_);
  sim::ClockedRun loop;
  loop.time = [this] { return sim_->time_s(); };
  bool stopped = false;
  loop.frame = [&](std::int64_t) {
    record_frame();
    stopped = stop && stop();
    return stopped ? std::string("stopped") : std::string();
  };
  loop.step = [this](double frame_time) {
    const std::string failure = step_toward(frame_time);
    return failure.empty() ? sim::StepResult{} : sim::StepResult::failed_with(failure);
  };
  const sim::ClockOutcome outcome = sim::run_frames(clock, loop);
  if (stopped) {
    requested_s_ = sim_->time_s();
    return false;
  }
  if (!outcome.failure.empty()) throw RunError(outcome.failure);
  return true;
}

std::vector<Vec2> Simulation::markers(std::size_t j) const {
  const jellyfish::SliceFrame f = sim_->jellyfish(j).slice_frame(sim_->time_s());
  std::vector<Vec2> points = f.umbrella;
  for (const std::vector<Vec2>& strand : f.tentacles) points.insert(points.end(), strand.begin(), strand.end());
  return points;
}

std::vector<jellyfish::MetricsRow> Simulation::metrics() const {
  if (frames_.empty()) return {};
  const jellyfish::SwimSettings& s = scene_.settings;
  return jellyfish::compute_metrics(frames_, {s.tank.density_kg_per_m3, std::max(s.tank.viscosity_m2_per_s, 1e-9)});
}

geometry::FrameGeometry Simulation::mesh(std::size_t frame) const {
  if (frame >= frames_.size())
    throw std::out_of_range("no recorded frame " + std::to_string(frame) + " (" + std::to_string(frames_.size()) +
                            " recorded)");
  if (!builder_) {
    // As `jellysim run`: the [render] defaults, the first jellyfish's noise seed, the noise length
    // from frame 0 (render::write_animation_outputs).
    geometry::GeometrySettings g = scene::read_render_settings(scene::render_parameters().defaults()).geometry;
    g.noise.seed += static_cast<std::uint64_t>(scene_.settings.jellyfish().noise_seed) - 1;
    builder_ = std::make_unique<geometry::GeometryBuilder>(g, geometry::resolve_noise_length(g.noise, frames_.front()));
  }
  return builder_->build(frames_[frame]);
}

}  // namespace jellysim::python
