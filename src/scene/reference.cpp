#include "jellysim/scene/reference.hpp"

#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/live_parameters.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellysim/scene/study_scenes.hpp"

namespace jellysim::scene {

std::string parameters_reference() {
  std::string page =
      "# Scene parameters\n\n"
      "Generated from the parameter tables in `src/scene/` by `jellysim scenes --reference > docs/parameters.md`;\n"
      "the test `SceneParameters.ReferencePageIsCurrent` fails when this page is stale. The same tables\n"
      "give the built-in scene files (`jellysim scenes jellyfish`), check scene files and `--set`\n"
      "overrides (type and range; errors name the field and the allowed values, exit code 2) and set\n"
      "the ranges of the viewer's live parameters. Units are SI; an empty unit is a ratio or a name.\n"
      "Ranges: `(` and `)` exclude the bound, `[` and `]` include it.\n\n"
      "## Jellyfish scene (`jellysim simulate`, `run`, `view`, `sweep`; scenes/jellyfish.toml)\n\n"
      "A scene file lists only what it changes; everything else keeps these defaults. The jellyfish\n"
      "experiments (`jellysim experiment NAME`) start from this scene and add fields of their own\n"
      "(`jellysim scenes NAME` prints them). [[objects]] tables are described in docs/scenes.md.\n";
  page += jellyfish_scene().reference_markdown();
  page +=
      "\n## 3D rendering (`jellysim run`, `experiment stages`; the [render] section)\n\n"
      "The pipeline of §7.2–7.4: image and mesh sizes, camera, style, which files are written, and the\n"
      "noise of §7.3. The main job starts from these; `experiment stages` sets obj and ply to true.\n";
  page += render_parameters().reference_markdown();
  page +=
      "\n## Lid-driven cavity (`jellysim experiment driven-cavity`; experiments/driven-cavity.toml)\n";
  page += driven_cavity_scene().reference_markdown();
  page +=
      "\n## Oval membrane (`jellysim experiment oval-membrane`; experiments/oval-membrane.toml)\n";
  page += oval_membrane_scene().reference_markdown();
  page += "\n## Taylor-Green vortex study (`jellysim experiment taylor-green`; experiments/taylor-green.toml)\n";
  page += taylor_green_scene().reference_markdown();
  page += "\n## Fluid solver cost (`jellysim experiment solver-cost`; experiments/solver-cost.toml)\n";
  page += solver_cost_scene().reference_markdown();
  page +=
      "\n## Elastic-bar and particle-fluid scenes (`swinging-bar`, `bar-hits-wall`, `bar-hits-particle`, "
      "`sph-stream`, `mosquito-larva`, `integrator-cost`)\n\n"
      "The sections these scenes share follow one set of rules (type, unit, allowed values); each scene\n"
      "sets its own defaults (`jellysim scenes NAME`). Fields of one experiment alone (its [output]\n"
      "strip, [wall], [particle], [emitter], [study]) are described in its definition file.\n";
  page += particle_scene_rules().reference_markdown();
  page +=
      "\n## The viewer's live parameters (`jellysim view`: sliders and scripted `set NAME [INDEX] VALUE`)\n\n"
      "Each is a parameter above (or one of the viewer's own controls) and allows the same values; the\n"
      "slider offers the part of that range shown here. docs/viewer.md describes the viewer.\n\n";
  page += live_parameters_markdown();
  return page;
}

}  // namespace jellysim::scene
