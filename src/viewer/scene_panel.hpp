#pragma once
// The 2D panel: the tank's fluid (a texture), tracers, each jellyfish's springs (muscles in red),
// obstacle outlines and steering targets, drawn through ImGui's background draw list; and what the
// mouse does there: drag a jellyfish or an obstacle, stir the water, set a steering target.
#include <optional>

#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/viewer/field_image.hpp"
#include "live_params.hpp"
#include "platform.hpp"

namespace jellysim::viewer {

/// Maps tank metres to window pixels (y down) inside a panel rectangle, keeping the aspect.
struct PanelMapping {
  double left_px = 0, top_px = 0, scale_px_per_m = 1;
  Vec2 origin_m{};
  double height_m = 1;
  static PanelMapping fit(const fluid::MacGrid& tank, double x, double y, double w, double h);
  Vec2 to_screen(Vec2 p_m) const;
  Vec2 to_tank(Vec2 p_px) const;
  bool inside(Vec2 p_px, const fluid::MacGrid& tank) const;
};

struct SceneDrawOptions {
  bool tracers = true;
  bool springs = true;
  FieldShown field = FieldShown::vorticity;  ///< the map the colour bar shows
  double field_range = 0.0;                  ///< its range (FieldImage::range); ≤ 0: no colour bar
};

/// What the mouse is holding.
struct Grab {
  enum class Kind { none, jellyfish, obstacle, water } kind = Kind::none;
  std::size_t index = 0;
  Vec2 last_m{};
};

class ScenePanel {
 public:
  /// Applies this frame's mouse to the simulation (`mouse_free`: ImGui does not want the mouse).
  /// Returns true when the state changed (a drag or a steering target).
  bool interact(const PanelMapping& map, const MouseState& mouse, bool mouse_free, double frame_dt_s,
                jellyfish::SwimSimulation& sim, LiveParams& params);
  /// Draws the panel (field texture id from the caller) into ImGui's background list.
  void draw(const PanelMapping& map, unsigned field_texture, const jellyfish::SwimSimulation& sim,
            const LiveParams& params, const SceneDrawOptions& options) const;
  std::size_t selected() const { return selected_; }
  void select(std::size_t jellyfish) { selected_ = jellyfish; }
  const Grab& grab() const { return grab_; }

 private:
  void press(const PanelMapping& map, Vec2 at_m, const jellyfish::SwimSimulation& sim);
  Grab grab_;
  bool was_down_[2] = {false, false};
  std::size_t selected_ = 0;
};

}  // namespace jellysim::viewer
