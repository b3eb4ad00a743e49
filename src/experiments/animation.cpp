// The main job (`jellysim run`): the default jellyfish simulated in 2D (thesis §7.1, Fig. 8.21),
// then extrapolated to a lit, noisy 3D animation (§7.2–7.4) written as MP4, glTF, PNG frames,
// meshes and an HTML viewer, with the swimming metrics and summary.json.
#include <memory>
#include <utility>

#include "jellysim/core/interrupt.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/jellyfish/stroke_loop.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellyfish_3d.hpp"

namespace jellysim::experiments {
namespace {

// ---- render.loop (issue 39 item 3; jellyfish/stroke_loop.hpp, docs/rendering.md) ----

nlohmann::ordered_json mismatch_json(const jellyfish::StrokeMismatch& m) {
  return {{"cycle", m.cycle}, {"shape", m.shape}, {"speed", m.speed}};
}

/// A loop run's settings: every cycle start a frame, the run to the cap, stopped once the loop is recorded.
void prepare_loop(const jellyfish::LoopSettings& loop, jellyfish::SwimSettings& settings, SwimOutputOptions& options,
                  render::PipelineSettings& pipeline) {
  settings = jellyfish::loop_search_settings(settings, loop);
  const int per_cycle = jellyfish::frames_per_cycle(settings.frames_per_second, settings.jellyfish().frequency_hz);
  const double diameter = settings.jellyfish().diameter_m, frequency = settings.jellyfish().frequency_hz;
  // Asked before every step; the answer changes only when a frame was recorded.
  auto seen = std::make_shared<std::pair<std::size_t, bool>>(0, false);
  options.stop_when = [=](const jellyfish::SwimRecord& rec) {
    if (rec.frames.size() != seen->first)
      *seen = {rec.frames.size(), jellyfish::search_loop(rec.frames, per_cycle, loop, diameter, frequency)
                                      .recorded(rec.frames.size(), per_cycle)};
    return seen->second;
  };
  pipeline.geometry.noise.time_frequency_hz = 0.0;  // the noise's drift does not repeat: frozen in a loop
}

/// The loop cut from the run (its frames, the marine snow frozen at its first frame) into `frames`
/// and `tracers`, loop_slices.csv (the closing frame last) and summary.json's "loop"; returns a
/// failure when no loop closed within the tolerance (the loop is then cut at the best match).
std::string cut_animation_loop(const jellyfish::LoopSettings& loop, const jellyfish::SwimSettings& settings,
                               const SwimRecording& rec, const io::OutputDir& out, nlohmann::ordered_json& figures,
                               std::vector<jellyfish::SliceFrame>& frames, std::vector<std::vector<Vec2>>& tracers,
                               render::PipelineSettings& pipeline) {
  const jellyfish::JellyfishSpec& j = settings.jellyfish();
  const int per_cycle = jellyfish::frames_per_cycle(settings.frames_per_second, j.frequency_hz);
  const jellyfish::LoopSearch search = jellyfish::search_loop(rec.frames, per_cycle, loop, j.diameter_m, j.frequency_hz);
  if (!search.loop_check()) throw RunError("render.loop: the run recorded no cycle start to compare");
  const jellyfish::StrokeMismatch& start = *search.loop_check();
  const auto first = static_cast<std::size_t>(search.start_cycle() * per_cycle);
  const auto count = static_cast<std::size_t>(loop.cycles * per_cycle);
  jellyfish::LoopClip clip = jellyfish::cut_loop(rec.frames, first, count, settings.frames_per_second,
                                                 loop.root_motion, j.diameter_m, j.frequency_hz);
  clip.closure.cycle = search.start_cycle() + loop.cycles;
  write_slices_csv(out, clip.frames, "loop_slices.csv");
  nlohmann::ordered_json checked = nlohmann::ordered_json::array();
  for (const jellyfish::StrokeMismatch& m : search.checked) checked.push_back(mismatch_json(m));
  figures["duration_rounded_to_frames"] = rec.frame_times.back();  // where the search stopped
  figures["loop"] = {{"periodic_cycle", search.periodic_cycle}, {"start_cycle", search.start_cycle()},
                     {"first_frame", first}, {"frames", count}, {"cycles", loop.cycles},
                     {"frames_per_cycle", per_cycle}, {"duration", clip.duration_s}, {"tolerance", loop.tolerance},
                     {"mismatch", mismatch_json(start)},
                     {"closure", mismatch_json(clip.closure)}, {"checked", checked},
                     {"root_motion", loop.root_motion == jellyfish::RootMotion::remove ? "remove" : "constant"},
                     {"travel", {clip.travel.x, clip.travel.y}},
                     {"root_velocity", {clip.travel.x / clip.duration_s, clip.travel.y / clip.duration_s}}};
  clip.frames.pop_back();  // the closing frame is the first again: the .glb's closing key (below)
  const Vec2 kept = loop.root_motion == jellyfish::RootMotion::remove ? Vec2{} : clip.travel;
  pipeline.loop_travel_m = geometry::Vec3{kept.x, kept.y, 0.0};  // the slice plane is the 3D z = 0 plane
  frames = std::move(clip.frames);
  if (!tracers.empty()) tracers.assign(count, rec.tracers.at(first));
  if (search.periodic_cycle > 0) return {};
  return "render.loop: no loop closed within render.loop_tolerance = " +
         config::format_number(loop.tolerance) + " by render.loop_max_cycles = " + std::to_string(loop.max_cycles) +
         " (the best match: the loop closing at cycle " + std::to_string(start.cycle) + ", shape " +
         config::format_number(start.shape) + ", speed " + config::format_number(start.speed) + "); the loop was cut there";
}

std::function<Outcome(const io::OutputDir&)> prepare_animation(const Context& ctx) {
  if (scene::is_3d_scene(ctx.config)) return prepare_animation_3d(ctx);  // the simulated surface, rendered
  jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  SwimOutputOptions options = read_output_options(ctx.config);
  if (settings.school.empty())
    throw InputError("the 3D animation needs a jellyfish: set jellyfish.enabled = true or add an [[objects]] entry "
                     "of type \"jellyfish\"");
  render::PipelineSettings pipeline = scene::read_render_settings(ctx.config);
  const jellyfish::LoopSettings loop = scene::read_loop_settings(ctx.config);
  if (loop.enabled) prepare_loop(loop, settings, options, pipeline);
  pipeline.fps = settings.frames_per_second > 0.0 ? settings.frames_per_second
                                                  : 1.0 / settings.frame_interval_s;  // the video plays in real time
  // The materials of jellyfish.glb and jellyfish.usda are the renderer's look: colours, opacities,
  // render.transmission and render.attenuation_distance (docs/rendering.md).
  pipeline.look = render::export_look(pipeline.style);
  options.record_tracers = pipeline.marine_snow && settings.tank.tracers_per_side > 0;
  return [settings, options, pipeline, loop, ctx](const io::OutputDir& out) {
    render::PipelineSettings run_pipeline = pipeline;  // a loop adds its travel (cut_animation_loop)
    // With checkpoints, the simulation's end stays checkpointed until the animation is whole.
    const SwimRecording rec = run_swim(settings, options, &out, ctx.progress, ctx.checkpoints.get());
    write_metrics_csv(out, rec.metrics);
    write_slices_csv(out, rec.frames);
    write_scene_extras(out, rec);
    if (!rec.metrics.empty()) write_swim_plots(out, rec.metrics, "jellyfish");
    nlohmann::ordered_json figures = swim_figures(settings, rec);
    // Every jellyfish in one animation; individual j's noise seed is render.noise.seed plus its
    // noise_seed − 1 (docs/scenes.md), so the first one keeps render.noise.seed.
    std::vector<std::vector<jellyfish::SliceFrame>> school{rec.frames};
    school.insert(school.end(), rec.others.begin(), rec.others.end());
    std::vector<std::vector<Vec2>> tracers = rec.tracers;
    std::string failure = rec.stats.failure;
    if (loop.enabled && failure.empty())
      failure = cut_animation_loop(loop, settings, rec, out, figures, school[0], tracers, run_pipeline);
    std::vector<std::uint64_t> seeds;
    for (const jellyfish::JellyfishSpec& j : settings.school)
      seeds.push_back(pipeline.geometry.noise.seed + static_cast<std::uint64_t>(j.noise_seed) - 1);
    if (ctx.render_progress) ctx.render_progress(0, school[0].size());  // the render stage starts
    const render::AnimationOutputs anim = render::write_animation_outputs(
        school, seeds, run_pipeline, out,
        [&ctx](std::size_t done, std::size_t total) {
          if (ctx.render_progress) ctx.render_progress(done, total);
        },
        loop.enabled ? render::ObstacleFrames{} : rec.obstacle_outlines, tracers);  // a loop's tank has none
    figures["animation"] = anim.figures();
    if (failure.empty() && core::interrupt_signal() != 0 && anim.frames < school[0].size())
      failure = "interrupted by " + core::signal_name(core::interrupt_signal()) + " while rendering, after " +
                std::to_string(anim.frames) + " of " + std::to_string(school[0].size()) + " frames";
    write_summary(out, "run", ctx.config, figures, failure);
    if (ctx.checkpoints && failure.empty()) out.remove(io::kCheckpointName);  // whole: nothing to resume
    return Outcome{failure};
  };
}

}  // namespace

Experiment animation_experiment() {
  Experiment e{"animation", "The main job: the default jellyfish simulated and rendered as a 3D animation (`jellysim run`)",
               "experiments/animation.toml", prepare_animation};
  e.base_path = "scenes/jellyfish.toml";
  e.renders = true;
  return e;
}

}  // namespace jellysim::experiments
