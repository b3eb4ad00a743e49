// Thesis Figure 8.19: the stages from the 2D slice to the noisy 3D jellyfish, expanded and
// contracted, as one picture. By default the two slices come from one simulated contraction
// cycle of the built-in jellyfish (the rest state and the frame of smallest bell volume);
// `bell.source = "synthetic"` uses an analytic contracting bell instead.
#include <chrono>

#include "jellysim/scene/resolve.hpp"
#include "jellysim//experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/scene/experiment_scenes.hpp"

namespace jellysim::experiments {
namespace {

using StagesSetup = scene::StagesScene;

Outcome run_stages(const StagesSetup& s, const config::Config& config, const io::OutputDir& out) {
  const auto t0 = std::chrono::steady_clock::now();
  jellyfish::SliceFrame a, b;
  if (s.simulated) {
    // One contraction cycle of the built-in scene: expanded = the rest state, contracted = the
    // frame with the smallest sub-umbrellar volume.
    config::Config scene = jellysim::scene::builtin_jellyfish_scene();
    scene.set("tank.tracers_per_side=0");
    scene.set("duration=" + io::format_double(1.0 / scene.number("jellyfish.frequency")));
    const SwimRecording rec = run_swim(read_swim_settings(scene), {}, nullptr, {});
    std::size_t smallest = 0;
    for (std::size_t k = 0; k < rec.metrics.size(); ++k)
      if (rec.metrics[k].volume < rec.metrics[smallest].volume) smallest = k;
    a = rec.frames.front();
    b = rec.frames[smallest];
  } else {
    geometry::SyntheticBell expanded = s.bell, contracted = s.bell;
    expanded.contraction = 0.0;
    contracted.contraction = s.contracted;
    a = geometry::synthetic_bell(expanded);
    b = geometry::synthetic_bell(contracted);
  }
  const render::RgbImage picture = render::render_stages_picture(a, b, s.pipeline, s.panel_width, s.panel_height);
  out.write_text("stages.png", render::png_bytes(picture));
  const geometry::GeometryBuilder builder(s.pipeline.geometry, geometry::resolve_noise_length(s.pipeline.geometry.noise, a));
  const geometry::FrameGeometry g = builder.build(a);
  nlohmann::ordered_json figures;
  figures["stages"] = render::stage_names();
  figures["columns"] = {"expanded", "contracted"};
  figures["source"] = s.simulated ? "simulation" : "synthetic";
  figures["contracted_time_s"] = b.time_s;
  figures["picture"] = "stages.png";
  figures["picture_size_px"] = {picture.width, picture.height};
  figures["noise_length_scale_m"] = builder.length_scale_m();
  figures["vertices_per_frame"] = g.mesh.vertex_count();
  figures["triangles_per_frame"] = g.mesh.triangle_count();
  figures["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_summary(out, "experiment stages", config, figures, "");
  return {};
}

}  // namespace

Experiment stages_experiment() {
  Experiment e;
  e.name = "stages";
  e.description = "Figure 8.19: each stage from 2D slice to noisy 3D jellyfish, expanded and contracted (stages.png)";
  e.definition_path = "experiments/stages.toml";
  e.renders = true;
  e.prepare = [](const Context& ctx) {
    const StagesSetup setup = scene::read_stages_scene(ctx.config);
    const config::Config config = ctx.config;
    return std::function<Outcome(const io::OutputDir&)>(
        [setup, config](const io::OutputDir& out) { return run_stages(setup, config, out); });
  };
  return e;
}

}  // namespace jellysim::experiments
