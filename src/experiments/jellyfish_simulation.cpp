// The 2D jellyfish simulation (`jellysim simulate`, scene "jellyfish"): the built-in scene
// by default, with metrics per frame, fluid fields and a picture per frame (Figure 8.11 style). A
// 3D scene (tank.geometry = "3d") runs in jellyfish_3d.cpp.
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellyfish_3d.hpp"

namespace jellysim::experiments {
namespace {

std::function<Outcome(const io::OutputDir&)> prepare_jellyfish(const Context& ctx) {
  if (scene::is_3d_scene(ctx.config)) return prepare_jellyfish_3d(ctx);
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  const SwimOutputOptions options = read_output_options(ctx.config);
  return [settings, options, ctx](const io::OutputDir& out) {
    const SwimRecording rec = run_swim(settings, options, &out, ctx.progress, ctx.checkpoints.get());
    write_metrics_csv(out, rec.metrics);
    write_slices_csv(out, rec.frames);
    write_scene_extras(out, rec);
    if (!rec.metrics.empty()) write_swim_plots(out, rec.metrics, "jellyfish");
    write_summary(out, "simulate", ctx.config, swim_figures(settings, rec), rec.stats.failure);
    return Outcome{rec.stats.failure};
  };
}

}  // namespace

Experiment jellyfish_experiment() {
  return {"jellyfish", "2D jellyfish slice swimming in a grid fluid (the resolved built-in scene; `jellysim simulate`), or the "
          "shell bell in 3D water (tank.geometry = \"3d\", scenes/jellyfish-3d.toml)",
          "scenes/jellyfish.toml", prepare_jellyfish};
}

}  // namespace jellysim::experiments
