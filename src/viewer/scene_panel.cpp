#include "scene_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <limits>
#include <span>

#include "jellysim/jellyfish/obstacle.hpp"

namespace jellysim::viewer {

namespace {

constexpr double kGrabRadiusPx = 12.0;
constexpr double kMaxStirSpeed = 0.25;   ///< m/s, well inside the stability limit
constexpr double kStirRadiusCells = 2.5;

ImVec2 im(Vec2 p) { return ImVec2(static_cast<float>(p.x), static_cast<float>(p.y)); }

double distance_to_points(Vec2 p, std::span<const Vec2> points) {
  double best = std::numeric_limits<double>::infinity();
  for (Vec2 q : points) best = std::min(best, std::hypot(q.x - p.x, q.y - p.y));
  return best;
}

/// The jellyfish with a marker within `radius_m` of p (nearest first), if any.
std::optional<std::size_t> jellyfish_at(Vec2 p, double radius_m, const jellyfish::SwimSimulation& sim) {
  std::optional<std::size_t> hit;
  double best = radius_m;
  for (std::size_t i = 0; i < sim.jellyfish_count(); ++i) {
    const jellyfish::Jellyfish& j = sim.jellyfish(i);
    const double d = distance_to_points(p, std::span(j.body().points.position).subspan(j.first_point(), j.point_count()));
    if (d <= best) {
      best = d;
      hit = i;
    }
  }
  return hit;
}

std::optional<std::size_t> obstacle_at(Vec2 p, double radius_m, const jellyfish::SwimSimulation& sim) {
  for (std::size_t k = 0; k < sim.obstacle_count(); ++k) {
    const std::vector<Vec2> outline = sim.obstacle_outline(k);
    if (jellyfish::point_in_polygon(p, outline) || distance_to_points(p, outline) <= radius_m) return k;
  }
  return std::nullopt;
}

void draw_body_springs(const PanelMapping& map, const jellyfish::Jellyfish& j, ImDrawList* list, bool selected) {
  const elastic::Body& body = j.body();
  const auto& pos = body.points.position;
  std::vector<bool> is_muscle(body.linear.size(), false);
  for (int s : j.layout().muscle_springs) is_muscle[static_cast<std::size_t>(s)] = true;
  std::vector<bool> is_hoop(body.linear.size(), false);  // a ring jellyfish's hoops close each ring: not drawn
  for (int s : j.layout().hoop_springs) is_hoop[static_cast<std::size_t>(s)] = true;
  const ImU32 spring = selected ? IM_COL32(255, 255, 255, 255) : IM_COL32(230, 235, 240, 230);
  const ImU32 muscle = IM_COL32(kMuscleColour[0], kMuscleColour[1], kMuscleColour[2], 220);
  const std::size_t first = j.first_linear_spring();
  for (std::size_t s = first; s < first + j.linear_spring_count(); ++s) {
    if (is_hoop[s]) continue;
    const Vec2 a = pos[static_cast<std::size_t>(body.linear.i[s])];
    const Vec2 b = pos[static_cast<std::size_t>(body.linear.j[s])];
    list->AddLine(im(map.to_screen(a)), im(map.to_screen(b)), is_muscle[s] ? muscle : spring,
                  is_muscle[s] ? 1.0f : 2.0f);
  }
}

void draw_cross(ImDrawList* list, Vec2 c, ImU32 colour) {
  constexpr float r = 6.0f;
  const ImVec2 p = im(c);
  list->AddLine(ImVec2(p.x - r, p.y - r), ImVec2(p.x + r, p.y + r), colour, 2.0f);
  list->AddLine(ImVec2(p.x - r, p.y + r), ImVec2(p.x + r, p.y - r), colour, 2.0f);
}

/// The field's colour bar in the panel's top-right corner: the map from its top value (range, 1/s
/// or m/s) to its bottom one (−range for vorticity, 0 for speed), labelled, over a dark backing.
void draw_colour_bar(ImDrawList* list, ImVec2 top_left, ImVec2 bottom_right, FieldShown shown, double range) {
  const float height = std::min(140.0f, 0.35f * (bottom_right.y - top_left.y));
  const float x1 = bottom_right.x - 8.0f, x0 = x1 - 10.0f, y0 = top_left.y + 10.0f, y1 = y0 + height;
  const bool vorticity = shown == FieldShown::vorticity;
  const std::string unit = vorticity ? " 1/s" : " m/s";
  const auto label = [&](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.3g", v);
    return (v == 0.0 ? std::string("0") : std::string(text)) + unit;
  };
  const float text_w = ImGui::CalcTextSize(label(-range).c_str()).x;
  list->AddRectFilled(ImVec2(x0 - text_w - 10.0f, y0 - 6.0f), ImVec2(x1 + 4.0f, y1 + 6.0f), IM_COL32(0, 0, 0, 150), 3.0f);
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {  // top: +range
    const double s_top = 1.0 - static_cast<double>(k) / kSteps, s_bottom = 1.0 - static_cast<double>(k + 1) / kSteps;
    const auto top = field_colour(shown, vorticity ? 2.0 * s_top - 1.0 : s_top);
    const auto bottom = field_colour(shown, vorticity ? 2.0 * s_bottom - 1.0 : s_bottom);
    const float ya = y0 + height * static_cast<float>(k) / kSteps, yb = y0 + height * static_cast<float>(k + 1) / kSteps;
    const ImU32 a = IM_COL32(top[0], top[1], top[2], 255), b = IM_COL32(bottom[0], bottom[1], bottom[2], 255);
    list->AddRectFilledMultiColor(ImVec2(x0, ya), ImVec2(x1, yb), a, a, b, b);
  }
  const ImU32 white = IM_COL32(235, 235, 235, 255);
  const float line_h = ImGui::GetTextLineHeight();
  const auto put = [&](double v, float y) {
    const std::string text = label(v);
    list->AddText(ImVec2(x0 - 4.0f - ImGui::CalcTextSize(text.c_str()).x, y - 0.5f * line_h), white, text.c_str());
  };
  put(range, y0);
  put(vorticity ? 0.0 : 0.5 * range, 0.5f * (y0 + y1));
  put(vorticity ? -range : 0.0, y1);
}

}  // namespace

PanelMapping PanelMapping::fit(const fluid::MacGrid& tank, double x, double y, double w, double h) {
  PanelMapping m;
  m.scale_px_per_m = std::min(w / tank.width_m, h / tank.height_m);
  m.left_px = x + 0.5 * (w - tank.width_m * m.scale_px_per_m);
  m.top_px = y + 0.5 * (h - tank.height_m * m.scale_px_per_m);
  m.origin_m = tank.origin_m;
  m.height_m = tank.height_m;
  return m;
}

Vec2 PanelMapping::to_screen(Vec2 p) const {
  return {left_px + (p.x - origin_m.x) * scale_px_per_m, top_px + (height_m - (p.y - origin_m.y)) * scale_px_per_m};
}

Vec2 PanelMapping::to_tank(Vec2 p) const {
  return {origin_m.x + (p.x - left_px) / scale_px_per_m, origin_m.y + height_m - (p.y - top_px) / scale_px_per_m};
}

bool PanelMapping::inside(Vec2 p_px, const fluid::MacGrid& tank) const {
  const Vec2 m = to_tank(p_px);
  return m.x >= tank.origin_m.x && m.x <= tank.origin_m.x + tank.width_m && m.y >= tank.origin_m.y &&
         m.y <= tank.origin_m.y + tank.height_m;
}

void ScenePanel::press(const PanelMapping& map, Vec2 at_m, const jellyfish::SwimSimulation& sim) {
  const double radius_m = kGrabRadiusPx / map.scale_px_per_m;
  grab_ = Grab{Grab::Kind::water, 0, at_m};
  if (auto j = jellyfish_at(at_m, radius_m, sim)) {
    grab_.kind = Grab::Kind::jellyfish;
    grab_.index = *j;
    selected_ = *j;
  } else if (auto k = obstacle_at(at_m, radius_m, sim)) {
    grab_.kind = Grab::Kind::obstacle;
    grab_.index = *k;
  }
}

bool ScenePanel::interact(const PanelMapping& map, const MouseState& mouse, bool mouse_free, double frame_dt_s,
                          jellyfish::SwimSimulation& sim, LiveParams& params) {
  const fluid::MacGrid& tank = sim.flow().grid;
  const Vec2 at_px{mouse.x, mouse.y};
  const Vec2 at_m = tank.clamp_to_domain(map.to_tank(at_px));
  const bool over = mouse_free && mouse.x >= 0 && map.inside(at_px, tank);
  bool changed = false;
  if (mouse.down[0] && !was_down_[0] && over) press(map, at_m, sim);
  if (grab_.kind != Grab::Kind::none) {
    const Vec2 delta{at_m.x - grab_.last_m.x, at_m.y - grab_.last_m.y};
    if (grab_.kind == Grab::Kind::jellyfish && (delta.x != 0.0 || delta.y != 0.0)) {
      sim.move_jellyfish(grab_.index, delta);
      changed = true;
    } else if (grab_.kind == Grab::Kind::obstacle && (delta.x != 0.0 || delta.y != 0.0)) {
      sim.move_obstacle(grab_.index, delta);
      changed = true;
    } else if (grab_.kind == Grab::Kind::water && (delta.x != 0.0 || delta.y != 0.0)) {
      const double dt = std::max(frame_dt_s, 1.0 / 60.0);
      Vec2 du{delta.x / dt, delta.y / dt};
      const double speed = std::hypot(du.x, du.y);
      if (speed > kMaxStirSpeed) du = Vec2{du.x * kMaxStirSpeed / speed, du.y * kMaxStirSpeed / speed};
      sim.stir(at_m, du, kStirRadiusCells * tank.dx());
      changed = true;
    }
    grab_.last_m = at_m;
    if (!mouse.down[0]) grab_.kind = Grab::Kind::none;
  }
  // A ring jellyfish (axisymmetric tank) swims along the axis: it has no steering.
  if (mouse.down[1] && !was_down_[1] && over && selected_ < sim.jellyfish_count() && !sim.world().axisymmetric()) {
    params.jellyfish[selected_].steer_target_m = at_m;
    sim.set_steer_target(selected_, at_m);
    changed = true;
  }
  was_down_[0] = mouse.down[0];
  was_down_[1] = mouse.down[1];
  return changed;
}

void ScenePanel::draw(const PanelMapping& map, unsigned field_texture, const jellyfish::SwimSimulation& sim,
                      const LiveParams& params, const SceneDrawOptions& options) const {
  ImDrawList* list = ImGui::GetBackgroundDrawList();
  const fluid::MacGrid& tank = sim.flow().grid;
  const Vec2 lo = map.to_screen(tank.origin_m);
  const Vec2 hi = map.to_screen({tank.origin_m.x + tank.width_m, tank.origin_m.y + tank.height_m});
  const ImVec2 top_left(static_cast<float>(lo.x), static_cast<float>(hi.y));
  const ImVec2 bottom_right(static_cast<float>(hi.x), static_cast<float>(lo.y));
  list->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(field_texture)), top_left, bottom_right,
                 ImVec2(0, 1), ImVec2(1, 0));
  list->PushClipRect(top_left, bottom_right, true);
  if (options.tracers) {
    for (Vec2 p : sim.tracers().positions()) {
      const ImVec2 s = im(map.to_screen(p));
      list->AddRectFilled(ImVec2(s.x - 1, s.y - 1), ImVec2(s.x + 1, s.y + 1),
                          IM_COL32(kTracerColour[0], kTracerColour[1], kTracerColour[2], 170));
    }
  }
  for (std::size_t k = 0; k < sim.obstacle_count(); ++k) {
    std::vector<ImVec2> outline;
    for (Vec2 p : sim.obstacle_outline(k)) outline.push_back(im(map.to_screen(p)));
    list->AddPolyline(outline.data(), static_cast<int>(outline.size()), IM_COL32(255, 210, 80, 255),
                      ImDrawFlags_Closed, 2.5f);
  }
  for (std::size_t i = 0; i < sim.jellyfish_count(); ++i) {
    if (options.springs) draw_body_springs(map, sim.jellyfish(i), list, i == selected_);
    if (i < params.jellyfish.size() && params.jellyfish[i].steer_target_m) {
      draw_cross(list, map.to_screen(*params.jellyfish[i].steer_target_m), IM_COL32(120, 255, 120, 255));
    }
  }
  if (options.field_range > 0.0) draw_colour_bar(list, top_left, bottom_right, options.field, options.field_range);
  list->PopClipRect();
  list->AddRect(top_left, bottom_right, IM_COL32(200, 200, 200, 255));
}

}  // namespace jellysim::viewer
