#include "jellysim/scene/live_parameters.hpp"

#include <sstream>

#include "jellysim/core/errors.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/render_settings.hpp"

namespace jellysim::scene {

const ParameterTable& viewer_controls() {
  static const ParameterTable table(
      "viewer", "",
      {{"view.speed", Type::number, "1.0", "", config::Range{0.0, 10.0, true, false}, {}, 0,
        "simulated seconds wanted per wall second (`jellysim view --speed`)", Slider{0.05, 4.0, true}},
       {"view.stiffness", Type::number, "1.0", "", config::Range{0.0, 100.0, true, false}, {}, 0,
        "factor on every spring constant of one jellyfish (bell, muscle and tentacles)", Slider{0.25, 4.0, true}}});
  return table;
}

const std::vector<LiveParameter>& live_parameters() {
  static const std::vector<LiveParameter> list{
      {"frequency", &jellyfish_scene().at("jellyfish.frequency"), true},
      {"gamma", &jellyfish_scene().at("jellyfish.gamma"), true},
      {"stiffness", &viewer_controls().at("view.stiffness"), true},
      {"viscosity", &jellyfish_scene().at("tank.viscosity"), false},
      {"speed", &viewer_controls().at("view.speed"), false},
      {"noise.structural", &render_parameters().at("render.noise.structural_weight"), false},
      {"noise.compression", &render_parameters().at("render.noise.compression_weight"), false},
      {"noise.unstructured", &render_parameters().at("render.noise.unstructured_weight"), false},
  };
  return list;
}

const LiveParameter& live_parameter(std::string_view name) {
  std::string known;
  for (const LiveParameter& p : live_parameters()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw InputError("unknown parameter '" + std::string(name) + "' (known: " + known + ")");
}

std::string check_live_value(const LiveParameter& p, double value) {
  if (p.parameter->range.contains(value)) return "";
  std::ostringstream why;
  why << p.name << " must be in " << p.parameter->range.describe() << ", got " << value;
  return why.str();
}

std::string live_parameters_markdown() {
  std::ostringstream s;
  s << "| name | parameter | unit | allowed | slider | description |\n|---|---|---|---|---|---|\n";
  for (const LiveParameter& l : live_parameters()) {
    const Parameter& p = *l.parameter;
    s << "| `" << l.name << (l.per_jellyfish ? " INDEX" : "") << "` | `" << p.key << "` | " << p.unit << " | "
      << allowed_values(p) << " | " << p.slider.min << " – " << p.slider.max << (p.slider.logarithmic ? " (log)" : "")
      << " | " << p.description << " |\n";
  }
  return s.str();
}

}  // namespace jellysim::scene
