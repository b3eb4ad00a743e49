// The main job (`jellysim run`): the default jellyfish simulated in 2D (thesis §7.1, Fig. 8.21),
// then extrapolated to a lit, noisy 3D animation (§7.2–7.4) written as MP4, glTF, PNG frames,
// meshes and an HTML viewer, with the swimming metrics and summary.json.
#include "jellysim/core/interrupt.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/scene/render_settings.hpp"

namespace jellysim::experiments {
namespace {

std::function<Outcome(const io::OutputDir&)> prepare_animation(const Context& ctx) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  SwimOutputOptions options = read_output_options(ctx.config);
  if (settings.school.empty())
    throw InputError("the 3D animation needs a jellyfish: set jellyfish.enabled = true or add an [[objects]] entry "
                     "of type \"jellyfish\"");
  render::PipelineSettings pipeline = scene::read_render_settings(ctx.config);
  pipeline.fps = settings.frames_per_second > 0.0 ? settings.frames_per_second
                                                  : 1.0 / settings.frame_interval_s;  // the video plays in real time
  // The materials of jellyfish.glb and jellyfish.usda are the renderer's look: colours, opacities,
  // render.transmission and render.attenuation_distance (docs/rendering.md).
  pipeline.look = render::export_look(pipeline.style);
  options.record_tracers = pipeline.marine_snow && settings.tank.tracers_per_side > 0;
  return [settings, options, pipeline, ctx](const io::OutputDir& out) {
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
    std::vector<std::uint64_t> seeds;
    for (const jellyfish::JellyfishSpec& j : settings.school)
      seeds.push_back(pipeline.geometry.noise.seed + static_cast<std::uint64_t>(j.noise_seed) - 1);
    if (ctx.render_progress) ctx.render_progress(0, rec.frames.size());  // the render stage starts
    const render::AnimationOutputs anim = render::write_animation_outputs(
        school, seeds, pipeline, out,
        [&ctx](std::size_t done, std::size_t total) {
          if (ctx.render_progress) ctx.render_progress(done, total);
        },
        rec.obstacle_outlines, rec.tracers);
    figures["animation"] = anim.figures();
    std::string failure = rec.stats.failure;
    if (failure.empty() && core::interrupt_signal() != 0 && anim.frames < rec.frames.size())
      failure = "interrupted by " + core::signal_name(core::interrupt_signal()) + " while rendering, after " +
                std::to_string(anim.frames) + " of " + std::to_string(rec.frames.size()) + " frames";
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
