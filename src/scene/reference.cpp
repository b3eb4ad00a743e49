#include "jellysim/scene/reference.hpp"

#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/live_parameters.hpp"
#include "jellysim/scene/objects.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellysim/scene/study_scenes.hpp"

namespace jellysim::scene {
namespace {

/// A table's page without its "Top level" section when that is empty (a table of rules for
/// sections only).
std::string without_empty_top_level(std::string page) {
  const std::string empty =
      "\n### Top level\n\n| key | default | unit | allowed | description |\n|---|---|---|---|---|\n";
  if (page.starts_with(empty + "\n###")) page.erase(0, empty.size());
  return page;
}


/// The experiments' own sections and the viewer's live parameters (parameters_reference's second half).
std::string experiments_reference() {
  std::string page;
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
  page += "\n## Integrator order (`jellysim experiment integrator-order`; experiments/integrator-order.toml)\n";
  page += integrator_order_scene().reference_markdown();
  page +=
      "\n## Figure 8.19's stages (`jellysim experiment stages`; experiments/stages.toml)\n\n"
      "The [render] section starts from the 3D rendering defaults above; the figure changes these.\n";
  page += stages_scene().reference_markdown();
  page +=
      "\n## Jellyfish studies (`structural-instability`, `numerical-instability`, `frequency-sweep`, `sweep`, "
      "`fluidless`, `coupling-stability`, `steering`)\n\n"
      "These extend the jellyfish scene (every field above applies) with fields of their own, which\n"
      "follow these rules; each study sets its own defaults (`jellysim scenes NAME`).\n";
  page += without_empty_top_level(jellyfish_study_rules().reference_markdown());
  page +=
      "\n## Hoover-Miller bell (`jellysim experiment hoover-miller`; experiments/hoover-miller.toml)\n\n"
      "Extends the jellyfish scene (its tank, coupling and one [[objects]] entry of type ib2d) with these\n"
      "top-level fields; the default of each is in the definition file (docs/ib2d.md).\n";
  page += hoover_miller_rules().reference_markdown();
  page +=
      "\n## Axisymmetric versus planar water (`jellysim experiment axisymmetric-vs-planar`; "
      "experiments/axisymmetric-vs-planar.toml)\n\n"
      "Extends the jellyfish scene (one jellyfish, no [[objects]]) with this field; its default is in the\n"
      "definition file.\n";
  page += axisymmetric_vs_planar_rules().reference_markdown();
  page +=
      "\n## Elastic-bar and particle-fluid scenes (`swinging-bar`, `bar-hits-wall`, `bar-hits-particle`, "
      "`sph-stream`, `mosquito-larva`, `integrator-cost`)\n\n"
      "The sections these scenes share, and the fields of one experiment alone (its [output] strip,\n"
      "[wall], [particle], [emitter], [study]), follow one set of rules (type, unit, allowed values);\n"
      "each scene sets its own defaults (`jellysim scenes NAME`).\n";
  page += particle_scene_rules().reference_markdown();
  page +=
      "\n## The viewer's live parameters (`jellysim view`: sliders and scripted `set NAME [INDEX] VALUE`)\n\n"
      "Each is a parameter above (or one of the viewer's own controls) and allows the same values; the\n"
      "slider offers the part of that range shown here. docs/viewer.md describes the viewer.\n\n";
  page += live_parameters_markdown();
  return page;
}

}  // namespace

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
      "(`jellysim scenes NAME` prints them). [[objects]] tables follow this section (docs/scenes.md).\n";
  page += jellyfish_scene().reference_markdown();
  page +=
      "\n## [[objects]] of the jellyfish scene (docs/scenes.md)\n\n"
      "More things in the tank, one [[objects]] table each, of the `type` given; an object has only its\n"
      "type's fields (another is refused, naming the allowed). A field without a default is required,\n"
      "or optional without effect when absent, as its description says.\n";
  page += objects_reference_markdown();
  page +=
      "\n## 3D rendering (`jellysim run`, `experiment stages`; the [render] section)\n\n"
      "The pipeline of §7.2–7.4: image and mesh sizes, camera, style, which files are written, and the\n"
      "noise of §7.3. The main job starts from these; `experiment stages` sets obj and ply to true.\n";
  page += render_parameters().reference_markdown();
  page += experiments_reference();
  return page;
}

}  // namespace jellysim::scene
