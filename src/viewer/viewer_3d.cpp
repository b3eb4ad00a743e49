#include "jellysim/viewer/viewer_3d.hpp"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "jellysim/core/errors.hpp"
#include "jellysim/geometry/surface_geometry.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/swim3d/swimmer_3d.hpp"
#include "jellysim/viewer/field_image.hpp"
#include "mesh_view.hpp"
#include "pacing.hpp"
#include "platform.hpp"
#include "recorder.hpp"

namespace jellysim::viewer {

namespace {

constexpr float kControlsWidth = 330.0f;

double wall_now() {
  using clock = std::chrono::steady_clock;
  static const clock::time_point start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}

/// The bell's topology for the surface builder, with one frame: the present positions.
geometry::SurfaceFrames surface_holder(const swim3d::Swimmer3d& sim) {
  geometry::SurfaceFrames f;
  f.thickness_m = sim.spec().bell.slice.thickness_m;
  for (const auto& t : sim.bell().surface().mesh.triangles)
    f.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]), static_cast<std::uint32_t>(t[2])});
  return f;
}

/// The markers' positions as the holder's one frame (the surface's vertices, then each rod).
void copy_positions(const swim3d::Swimmer3d& sim, geometry::SurfaceFrames& f) {
  f.time_s.clear(), f.surface.clear(), f.tentacles.clear();
  geometry::append_surface_frame(f, sim.time_s(), sim.markers().position, sim.bell().surface().mesh.vertices.size(),
                                 sim.bell().tentacles());
}

class Viewer3d {
 public:
  Viewer3d(const scene::Swim3dSettings& settings, const ViewerOptions& options)
      : settings_(settings), options_(options), paused_(options.start_paused), field_(options.field) {
    reset();
  }
  int run();

 private:
  void reset();
  void handle_key(const std::string& key);
  void step_simulation();
  void draw_controls();
  void draw_views();
  void frame(double gap_s);
  void capture(bool last_frame);
  void write_stats() const;

  scene::Swim3dSettings settings_;
  ViewerOptions options_;
  std::unique_ptr<swim3d::Swimmer3d> sim_;
  geometry::SurfaceFrames holder_;
  std::unique_ptr<geometry::SurfaceGeometryBuilder> builder_;
  geometry::FrameGeometry mesh_;
  bool paused_ = false, step_requested_ = false, quit_ = false, screenshot_requested_ = false;
  FieldShown field_;
  std::string failure_, message_;
  long frame_index_ = 0, steps_ = 0;
  double stepping_s_ = 0.0, ms_per_step_ = 0.0;
  RateMeter meter_{3.0};
  OrbitCamera camera_;
  std::unique_ptr<Window> window_;
  std::unique_ptr<MeshView> mesh_view_;
  std::unique_ptr<gl::Texture> field_texture_;
  Recorder recorder_;
  render::RgbImage last_capture_;
};

void Viewer3d::reset() {
  sim_ = std::make_unique<swim3d::Swimmer3d>(settings_.spec);
  holder_ = surface_holder(*sim_);
  copy_positions(*sim_, holder_);
  builder_ = std::make_unique<geometry::SurfaceGeometryBuilder>(holder_, options_.geometry);
  builder_->build(0, mesh_);
  failure_.clear();
}

void Viewer3d::handle_key(const std::string& key) {
  if (key == "space") paused_ = !paused_;
  else if (key == "s" || key == "right") step_requested_ = true;
  else if (key == "tab") field_ = field_ == FieldShown::speed ? FieldShown::vorticity : FieldShown::speed;
  else if (key == "r") reset(), message_ = "reset to t = 0";
  else if (key == "p") screenshot_requested_ = true;
  else if (key == "q" || key == "escape") quit_ = true;
}

// Coupled steps until this frame's share of wall time is spent (at least one): a step of the 3D
// water takes tens to hundreds of milliseconds, so the picture updates step by step.
void Viewer3d::step_simulation() {
  if (!failure_.empty() || (paused_ && !step_requested_)) return;
  const bool single = paused_;
  step_requested_ = false;
  const double budget = options_.target_fps > 0 ? 1.0 / options_.target_fps : 0.0, start = wall_now();
  try {
    do {
      const double t0 = wall_now();
      sim_->step_toward_frame();
      ++steps_;
      ms_per_step_ = 1e3 * (wall_now() - t0);
    } while (!single && wall_now() - start + 1e-3 * ms_per_step_ < budget);
  } catch (const std::runtime_error& e) {
    failure_ = e.what();
    paused_ = true;
  }
  stepping_s_ += wall_now() - start;
  copy_positions(*sim_, holder_);
  builder_->build(0, mesh_);
}

void Viewer3d::draw_controls() {
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - kControlsWidth, 0));
  ImGui::SetNextWindowSize(ImVec2(kControlsWidth, io.DisplaySize.y));
  ImGui::Begin("jellysim 3D", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  const swim3d::BellPose pose = swim3d::bell_pose(sim_->bell(), sim_->markers().position);
  const fluid3d::Grid3d& g = sim_->fluid().state().grid;
  ImGui::Text("t = %.3f s   steps %d", sim_->time_s(), sim_->timings().steps);
  ImGui::Text("%.1f frames/s   %.0f ms a step", meter_.fps(), ms_per_step_);
  if (!failure_.empty()) {
    ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "Simulation stopped:");
    ImGui::TextWrapped("%s", failure_.c_str());
  } else if (paused_) {
    ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "PAUSED");
  } else {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "Below real time: %.3fx (3D water)", meter_.sim_rate());
  }
  ImGui::Separator();
  const auto shown_deg = [](double a) { return std::abs(a) < 0.05 ? 0.0 : a; };  // no "−0.0"
  ImGui::Text("bell: centroid %.1f mm up", 1e3 * pose.centroid[1]);
  ImGui::Text("heading %.1f deg, tilt %.1f deg", shown_deg(pose.heading_deg), shown_deg(pose.tilt_deg));
  ImGui::Text("water: %d x %d x %d cells (%s tank)", g.n(0), g.n(1), g.n(2),
              std::string(swim3d::to_string(swim3d::resolved_symmetry(sim_->spec()))).c_str());
  ImGui::Text("%zu markers; %.1f GMRES iterations a step", sim_->markers().size(),
              sim_->timings().steps > 0 ? static_cast<double>(sim_->timings().krylov_iterations) / sim_->timings().steps : 0.0);
  if (ImGui::Button(paused_ ? "Run" : "Pause")) paused_ = !paused_;
  ImGui::SameLine();
  if (ImGui::Button("Step")) step_requested_ = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset")) reset();
  ImGui::SameLine();
  if (ImGui::Button("Screenshot")) screenshot_requested_ = true;
  int shown = field_ == FieldShown::speed ? 0 : 1;
  ImGui::RadioButton("speed", &shown, 0);
  ImGui::SameLine();
  ImGui::RadioButton("vorticity (z)", &shown, 1);
  field_ = shown == 0 ? FieldShown::speed : FieldShown::vorticity;
  ImGui::TextWrapped("Left: the flow on the bell's vertical mid-plane (z = 0). Drag the jellyfish to orbit, wheel to zoom. "
                     "space pause, s step, r reset, tab field, p screenshot, q quit.");
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  ImGui::End();
}

void Viewer3d::draw_views() {
  ImGuiIO& io = ImGui::GetIO();
  const double area_w = std::max(64.0, static_cast<double>(io.DisplaySize.x - kControlsWidth));
  const double panel_w = area_w / 2.0, panel_h = io.DisplaySize.y;
  const swim3d::TankSymmetry3d sym = swim3d::resolved_symmetry(sim_->spec());
  const int k = sym == swim3d::TankSymmetry3d::none ? sim_->fluid().state().grid.n(2) / 2 : 0;  // the plane nearest z = 0
  const FieldImage image = field_image(sim_->fluid().state(), k, field_, 0.0, sym == swim3d::TankSymmetry3d::quarter);
  field_texture_->upload(image.width, image.height, image.rgba);
  const double scale = std::min((panel_w - 8) / image.width, (panel_h - 8) / image.height);
  const double w = scale * image.width, h = scale * image.height, x0 = 4 + 0.5 * (panel_w - 8 - w), y0 = 4 + 0.5 * (panel_h - 8 - h);
  ImGui::GetBackgroundDrawList()->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(field_texture_->id())),
                                           ImVec2(static_cast<float>(x0), static_cast<float>(y0)),
                                           ImVec2(static_cast<float>(x0 + w), static_cast<float>(y0 + h)), ImVec2(0, 1),
                                           ImVec2(1, 0));
  const double s = io.DisplayFramebufferScale.x * options_.render_scale;
  const GLuint texture = mesh_view_->draw({&mesh_.mesh}, camera_, static_cast<int>(panel_w * s), static_cast<int>(panel_h * s));
  ImGui::GetBackgroundDrawList()->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture)),
                                           ImVec2(static_cast<float>(panel_w), 0),
                                           ImVec2(static_cast<float>(area_w), static_cast<float>(panel_h)), ImVec2(0, 1),
                                           ImVec2(1, 0));
}

void Viewer3d::frame(double gap_s) {
  for (const std::string& key : window_->poll_keys()) handle_key(key);
  const MouseState mouse = window_->real_mouse();
  window_->begin_ui(mouse, gap_s);
  ImGuiIO& io = ImGui::GetIO();
  const double area_w = std::max(64.0, static_cast<double>(io.DisplaySize.x - kControlsWidth));
  const bool over_3d = !io.WantCaptureMouse && mouse.x > area_w / 2.0 && mouse.x < area_w;
  if (over_3d && mouse.down[0]) {
    camera_.azimuth_deg -= io.MouseDelta.x * 0.4;
    camera_.elevation_deg = std::clamp(camera_.elevation_deg + io.MouseDelta.y * 0.4, -85.0, 85.0);
  }
  if (over_3d && mouse.wheel != 0.0) camera_.zoom = std::clamp(camera_.zoom * std::pow(1.15, mouse.wheel), 0.2, 20.0);
  draw_controls();
  step_simulation();
  draw_views();
  window_->render_ui();
}

void Viewer3d::capture(bool last_frame) {
  const bool at_exit = !options_.screenshot.empty() && last_frame;
  if (!recorder_.active() && !screenshot_requested_ && !at_exit) return;
  const int w = window_->width(), h = window_->height();
  last_capture_ = render::RgbImage(w, h);
  last_capture_.pixels = gl::read_screen_rgb(w, h);
  const std::string kept = keep_frame(last_capture_, recorder_, screenshot_requested_, options_.record_dir);
  if (!kept.empty()) message_ = kept;
  screenshot_requested_ = false;
}

int Viewer3d::run() {
  window_ = std::make_unique<Window>(options_.width_px, options_.height_px,
                                     "jellysim view (3D)" + (options_.scene_name.empty() ? "" : " - " + options_.scene_name),
                                     options_.vsync);
  mesh_view_ = std::make_unique<MeshView>();
  field_texture_ = std::make_unique<gl::Texture>();
  if (!options_.record_dir.empty())
    recorder_.start(options_.record_dir, window_->width(), window_->height(),
                    options_.target_fps > 0 ? options_.target_fps : 30.0, options_.record_png, options_.record_mp4);
  double last_start = wall_now() - 1.0 / 30.0;
  while (!quit_ && !window_->close_requested() && (options_.frames == 0 || frame_index_ < options_.frames)) {
    const double start = wall_now();
    frame(start - last_start);
    last_start = start;
    capture(options_.frames > 0 && frame_index_ + 1 == options_.frames);
    window_->swap();
    meter_.add(wall_now(), sim_->time_s(), true);
    ++frame_index_;
  }
  recorder_.stop();
  if (!options_.screenshot.empty() && last_capture_.width > 0) render::write_png(last_capture_, options_.screenshot);
  write_stats();
  return failure_.empty() ? 0 : 1;
}

void Viewer3d::write_stats() const {
  if (options_.stats.empty()) return;
  nlohmann::json s;
  s["frames"] = frame_index_;
  s["steps"] = steps_;
  s["simulated_s"] = sim_->time_s();
  s["sim_rate"] = stepping_s_ > 0 ? sim_->time_s() / stepping_s_ : 0.0;  // while stepping (drawing excluded)
  s["ms_per_step"] = steps_ > 0 ? 1e3 * stepping_s_ / static_cast<double>(steps_) : 0.0;
  s["markers"] = sim_->markers().size();
  s["geometry"] = "3d";
  s["failure"] = failure_;
  const swim3d::BellPose pose = swim3d::bell_pose(sim_->bell(), sim_->markers().position);
  s["state"] = {{"time_s", sim_->time_s()}, {"centroid", pose.centroid}, {"heading_deg", pose.heading_deg},
                {"tilt_deg", pose.tilt_deg}};
  io::write_file(options_.stats, s.dump(2) + "\n");
}

}  // namespace

int run_viewer_3d(const scene::Swim3dSettings& settings, const ViewerOptions& options) {
  validate(options);
  if (!options.script_text.empty())
    throw InputError("--script/--inject: the 3D viewer takes no input script (the 2D viewer's events move slices)");
  Viewer3d viewer(settings, options);
  return viewer.run();
}

}  // namespace jellysim::viewer
