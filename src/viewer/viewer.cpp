#include "jellysim/viewer/viewer.hpp"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "jellysim/geometry/marine_snow.hpp"
#include "jellysim/geometry/obstacle_mesh.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/scene/live_parameters.hpp"
#include "jellysim/viewer/field_image.hpp"
#include "input_script.hpp"
#include "live_params.hpp"
#include "mesh_view.hpp"
#include "pacing.hpp"
#include "platform.hpp"
#include "recorder.hpp"
#include "scene_panel.hpp"

namespace jellysim::viewer {

namespace {

constexpr float kControlsWidth = 330.0f;
constexpr long kWarmupFrames = 10;  ///< frames left out of the run's fps and sim-rate figures

double wall_now() {
  using clock = std::chrono::steady_clock;
  static const clock::time_point start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}

Vec2 centroid(const std::vector<Vec2>& points) {
  Vec2 c{};
  for (Vec2 p : points) c = Vec2{c.x + p.x, c.y + p.y};
  const double n = points.empty() ? 1.0 : static_cast<double>(points.size());
  return Vec2{c.x / n, c.y / n};
}

nlohmann::json vec_json(Vec2 v) { return nlohmann::json::array({v.x, v.y}); }

/// Whole-run figures (after the warm-up frames).
struct RunTotals {
  long frames = 0;
  long steps = 0;
  long behind_frames = 0;
  double measured_wall_s = 0.0;  ///< wall time of the frames after the warm-up
  double measured_frames = 0;
  double running_wall_s = 0.0;   ///< of those, the wall time while not paused
  double running_sim_s = 0.0;    ///< simulated time advanced in those frames
  // Where the frame time goes (all frames, seconds in all).
  double stepping_s = 0.0, field_s = 0.0, mesh_build_s = 0.0, mesh_draw_s = 0.0, present_s = 0.0;
};

class Viewer {
 public:
  Viewer(const jellyfish::SwimSettings& settings, const ViewerOptions& options)
      : settings_(settings),
        options_(options),
        events_(parse_input_script(options.script_text, options.script_source)),
        sim_(std::make_unique<jellyfish::SwimSimulation>(settings)),
        params_(LiveParams::from(settings, options.geometry.noise, options.speed)),
        pacer_({options.speed, options.min_fps, 0.002, 0.2}, wall_now),
        paused_(options.start_paused),
        field_(options.field) {
    check_script_parameters();
    rebuild_mesh_builders();
  }

  int run();

 private:
  void check_script_parameters() const;
  void rebuild_mesh_builders();
  void rebuild_obstacle_mesh();
  void rebuild_snow_mesh();
  void frame(double gap_s);
  MouseState scripted_mouse();
  void apply_event(const InputEvent& e);
  void handle_key(const std::string& key);
  void step_simulation(double gap_s);
  void single_step();
  void reset();
  void record_timeline(const InputEvent& e);
  void draw_controls();
  void draw_status();
  void draw_jellyfish_controls();
  void draw_views();
  void capture_if_needed(bool last_frame);
  void write_stats() const;
  nlohmann::json state_json() const;
  void set_param(const std::string& name, int index, double value);

  jellyfish::SwimSettings settings_;
  ViewerOptions options_;
  std::vector<InputEvent> events_;
  std::size_t next_event_ = 0;
  std::unique_ptr<jellyfish::SwimSimulation> sim_;
  LiveParams params_;
  Pacer pacer_;
  RateMeter meter_;
  bool paused_ = false;
  bool step_requested_ = false;
  bool quit_ = false;
  bool screenshot_requested_ = false;
  bool record_toggle_requested_ = false;
  FieldShown field_;
  SceneDrawOptions draw_options_;
  std::string failure_;
  std::string message_;
  long frame_index_ = 0;
  FrameSteps last_steps_;
  double other_work_s_ = 0.02;
  double frame_stepping_s_ = 0.0;  ///< smoothed wall time of a frame's drawing (all but the steps)
  RunTotals totals_;
  MouseState script_mouse_;
  bool have_script_mouse_ = false;
  std::vector<std::pair<const InputEvent*, bool>> pending_timeline_;
  nlohmann::json timeline_ = nlohmann::json::array();
  std::vector<geometry::GeometryBuilder> builders_;
  std::vector<geometry::FrameGeometry> meshes_;
  bool meshes_dirty_ = true;
  std::unique_ptr<geometry::ObstaclePrisms> prisms_;  ///< for the current obstacles' outline sizes
  std::vector<std::size_t> prism_points_;
  geometry::Mesh obstacle_mesh_;
  std::unique_ptr<geometry::MarineSnow> snow_;  ///< the tracers near the jellyfish at the start (or a reset)
  geometry::Mesh snow_mesh_;
  OrbitCamera camera_;
  ScenePanel scene_;
  std::unique_ptr<Window> window_;
  std::unique_ptr<MeshView> mesh_view_;
  std::unique_ptr<gl::Texture> field_texture_;
  Recorder recorder_;
  render::RgbImage last_capture_;
  std::string renderer_;
};

void Viewer::check_script_parameters() const {
  for (const InputEvent& e : events_) {
    if (e.kind != EventKind::set) continue;
    const std::string why = check_param(e.name, e.index, e.value, sim_->jellyfish_count());
    if (!why.empty()) throw InputError(options_.script_source + ": '" + e.text + "': " + why);
  }
}

// The obstacles as prisms (geometry/obstacle_mesh.hpp); the caps are triangulated again only when
// the obstacles or their marker counts change. An outline that cannot be drawn leaves them out.
// Marine snow (geometry/marine_snow.hpp): the tracers revolved about the first jellyfish's axis,
// those that start near the jellyfish (their box grown by twice its size on every side).
void Viewer::rebuild_snow_mesh() {
  using geometry::Vec3;
  snow_mesh_ = {};
  const std::vector<Vec2>& tracers = sim_->tracers().positions();
  if (tracers.empty() || meshes_.empty()) return;
  if (!snow_) {
    const geometry::Bounds b = geometry::bounds(meshes_.front().mesh);
    Vec3 lo = b.min, hi = b.max;
    for (const auto& m : meshes_) {
      const geometry::Bounds bm = geometry::bounds(m.mesh);
      lo = {std::min(lo.x, bm.min.x), std::min(lo.y, bm.min.y), std::min(lo.z, bm.min.z)};
      hi = {std::max(hi.x, bm.max.x), std::max(hi.y, bm.max.y), std::max(hi.z, bm.max.z)};
    }
    const Vec3 margin = 2.0 * (hi - lo);
    const jellyfish::SliceFrame first = sim_->jellyfish(0).slice_frame(sim_->time_s());
    const double axis_x = 0.5 * (first.umbrella.front().x + first.umbrella.back().x);
    snow_ = std::make_unique<geometry::MarineSnow>(tracers, axis_x, std::array<Vec3, 2>{lo - margin, hi + margin},
                                                   0.0003);
  }
  snow_->append(tracers, snow_mesh_);
}

void Viewer::rebuild_obstacle_mesh() {
  std::vector<std::vector<Vec2>> outlines;
  std::vector<std::size_t> points;
  for (std::size_t o = 0; o < sim_->obstacle_count(); ++o) {
    outlines.push_back(sim_->obstacle_outline(o));
    points.push_back(outlines.back().size());
  }
  obstacle_mesh_ = {};
  if (outlines.empty()) return;
  if (!prisms_ || points != prism_points_) {
    prism_points_ = points;
    try {
      prisms_ = std::make_unique<geometry::ObstaclePrisms>(outlines, options_.obstacle_depth_m);
    } catch (const std::invalid_argument&) {
      prisms_.reset();
    }
  }
  if (!prisms_) return;
  try {
    prisms_->append(outlines, obstacle_mesh_);
  } catch (const std::invalid_argument&) {
    obstacle_mesh_ = {};
  }
}

void Viewer::rebuild_mesh_builders() {
  builders_.clear();
  for (std::size_t i = 0; i < sim_->jellyfish_count(); ++i) {
    geometry::GeometrySettings g = options_.geometry;
    g.noise = params_.noise;
    g.noise.seed = static_cast<std::uint64_t>(sim_->jellyfish(i).spec().noise_seed);
    const double length = geometry::resolve_noise_length(g.noise, sim_->jellyfish(i).slice_frame(0.0));
    builders_.emplace_back(g, length);
  }
  meshes_dirty_ = true;
}

void Viewer::set_param(const std::string& name, int index, double value) {
  apply_param(name, index, value, params_, *sim_);
  if (name == "speed") pacer_.settings().speed = value;
  if (name.starts_with("noise.")) rebuild_mesh_builders();
}

// ---- input ----------------------------------------------------------------------------------

MouseState Viewer::scripted_mouse() {
  MouseState m = script_mouse_;
  pending_timeline_.clear();
  while (next_event_ < events_.size() && events_[next_event_].frame <= frame_index_) {
    const InputEvent& e = events_[next_event_++];
    if (e.kind == EventKind::press || e.kind == EventKind::move || e.kind == EventKind::release) {
      m.x = e.x;
      m.y = e.y;
      if (e.kind != EventKind::move) m.down[e.button] = e.kind == EventKind::press;
      have_script_mouse_ = true;
    } else {
      apply_event(e);
    }
    pending_timeline_.emplace_back(&e, true);
  }
  script_mouse_ = m;
  return m;
}

void Viewer::apply_event(const InputEvent& e) {
  switch (e.kind) {
    case EventKind::pause: handle_key("space"); break;
    case EventKind::step: handle_key("s"); break;
    case EventKind::key: handle_key(e.name); break;
    case EventKind::set: set_param(e.name, e.index, e.value); break;
    default: break;
  }
}

void Viewer::handle_key(const std::string& key) {
  if (key == "space") {
    paused_ = !paused_;
  } else if (key == "s" || key == "right") {
    step_requested_ = true;
  } else if (key == "r") {
    reset();
  } else if (key == "tab") {
    field_ = field_ == FieldShown::speed ? FieldShown::vorticity : FieldShown::speed;
  } else if (key == "p") {
    screenshot_requested_ = true;
  } else if (key == "v") {
    record_toggle_requested_ = true;
  } else if (key == "c") {
    const std::size_t i = scene_.selected();
    if (i < params_.jellyfish.size()) {
      params_.jellyfish[i].steer_target_m.reset();
      sim_->set_steer_target(i, std::nullopt);
    }
  } else if (key == "q" || key == "escape") {
    quit_ = true;
  }
}

// ---- simulation -----------------------------------------------------------------------------

void Viewer::step_simulation(double gap_s) {
  last_steps_ = {};
  if (!failure_.empty()) return;
  if (paused_) {
    pacer_.reset_debt();
    if (step_requested_) single_step();
    step_requested_ = false;
    return;
  }
  step_requested_ = false;
  last_steps_ = pacer_.advance(gap_s, other_work_s_, [this](double max_dt) {
    const jellyfish::SwimStep s = sim_->step(max_dt);
    return PacedStep{s.dt_s, s.failure};
  });
  if (last_steps_.steps > 0) meshes_dirty_ = true;
  if (!last_steps_.failure.empty()) {
    failure_ = last_steps_.failure;
    paused_ = true;
  }
}

void Viewer::single_step() {
  const jellyfish::SwimStep s = sim_->step();
  last_steps_.steps = 1;
  last_steps_.simulated_s = s.dt_s;
  meshes_dirty_ = true;
  if (!s.failure.empty()) failure_ = s.failure;
}

void Viewer::reset() {
  sim_ = std::make_unique<jellyfish::SwimSimulation>(settings_);
  apply_all(params_, *sim_);
  snow_.reset();
  failure_.clear();
  pacer_.reset_debt();
  meshes_dirty_ = true;
  message_ = "reset to t = 0 (parameters kept)";
}

void Viewer::record_timeline(const InputEvent& e) {
  nlohmann::json entry = state_json();
  entry["frame"] = frame_index_;
  entry["event"] = e.text;
  timeline_.push_back(std::move(entry));
}

// ---- user interface -------------------------------------------------------------------------

void Viewer::draw_status() {
  ImGui::Text("t = %.3f s   steps %ld", sim_->time_s(), sim_->steps());
  ImGui::Text("%.1f frames/s   sim rate %.2f (target %.2f)", meter_.fps(), meter_.sim_rate(), params_.speed);
  ImGui::Text("steps this frame %d", last_steps_.steps);
  if (!failure_.empty()) {
    ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "Simulation stopped:");
    ImGui::TextWrapped("%s", failure_.c_str());
  } else if (paused_) {
    ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "PAUSED");
  } else if (meter_.behind_fraction() > 0.5) {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "Cannot keep up: %.2fx real time", meter_.sim_rate());
  } else {
    ImGui::TextColored(ImVec4(0.4f, 1, 0.5f, 1), "Real time");
  }
  if (sim_->mirror_symmetric()) {
    ImGui::TextDisabled("mirror symmetry: kept");
  } else if (!sim_->mirror_symmetry_note().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("mirror symmetry: %s", sim_->mirror_symmetry_note().c_str());
    ImGui::PopStyleColor();
  }
  if (recorder_.active()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "REC %d frames", recorder_.frames());
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
}

/// A slider over the live parameter `name`'s slider range (scene/live_parameters.hpp).
bool live_slider(const char* label, const char* name, float* value, const char* format = "%.3f") {
  const scene::Slider& s = scene::live_parameter(name).parameter->slider;
  return ImGui::SliderFloat(label, value, static_cast<float>(s.min), static_cast<float>(s.max), format,
                            s.logarithmic ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None);
}

void Viewer::draw_jellyfish_controls() {
  if (sim_->jellyfish_count() == 0) return;
  int selected = static_cast<int>(scene_.selected());
  if (sim_->jellyfish_count() > 1 &&
      ImGui::SliderInt("jellyfish", &selected, 0, static_cast<int>(sim_->jellyfish_count()) - 1)) {
    scene_.select(static_cast<std::size_t>(selected));
  }
  const auto i = scene_.selected();
  JellyfishParams& j = params_.jellyfish[i];
  float frequency = static_cast<float>(j.frequency_hz), gamma = static_cast<float>(j.gamma),
        stiffness = static_cast<float>(j.stiffness_scale);
  const int index = static_cast<int>(i);
  if (live_slider("frequency (Hz)", "frequency", &frequency)) set_param("frequency", index, frequency);
  if (live_slider("gamma", "gamma", &gamma)) set_param("gamma", index, gamma);
  if (live_slider("stiffness x", "stiffness", &stiffness, "%.2f")) set_param("stiffness", index, stiffness);
  if (j.steer_target_m) {
    ImGui::Text("steering to (%.3f, %.3f)", j.steer_target_m->x, j.steer_target_m->y);
    ImGui::SameLine();
    if (ImGui::SmallButton("stop")) handle_key("c");
  }
}

void Viewer::draw_controls() {
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - kControlsWidth, 0));
  ImGui::SetNextWindowSize(ImVec2(kControlsWidth, io.DisplaySize.y));
  ImGui::Begin("jellysim", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  draw_status();
  if (ImGui::Button(paused_ ? "Run (space)" : "Pause (space)")) handle_key("space");
  ImGui::SameLine();
  if (ImGui::Button("Step (s)")) handle_key("s");
  ImGui::SameLine();
  if (ImGui::Button("Reset (r)")) handle_key("r");
  if (ImGui::Button("Screenshot (p)")) handle_key("p");
  ImGui::SameLine();
  if (ImGui::Button(recorder_.active() ? "Stop recording (v)" : "Record (v)")) handle_key("v");
  float speed = static_cast<float>(params_.speed);
  if (live_slider("speed", "speed", &speed, "%.2fx")) set_param("speed", 0, speed);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    int shown = field_ == FieldShown::speed ? 0 : 1;
    ImGui::RadioButton("speed", &shown, 0);
    ImGui::SameLine();
    ImGui::RadioButton("vorticity (tab)", &shown, 1);
    field_ = shown == 0 ? FieldShown::speed : FieldShown::vorticity;
    ImGui::Checkbox("tracers", &draw_options_.tracers);
    ImGui::SameLine();
    ImGui::Checkbox("springs", &draw_options_.springs);
  }
  if (ImGui::CollapsingHeader("Jellyfish", ImGuiTreeNodeFlags_DefaultOpen)) draw_jellyfish_controls();
  if (ImGui::CollapsingHeader("Fluid", ImGuiTreeNodeFlags_DefaultOpen)) {
    float nu = static_cast<float>(params_.viscosity_m2_per_s);
    if (live_slider("viscosity", "viscosity", &nu, "%.2e")) set_param("viscosity", 0, nu);
  }
  if (ImGui::CollapsingHeader("3D noise weights", ImGuiTreeNodeFlags_DefaultOpen)) {
    geometry::NoiseSettings& n = params_.noise;
    float w[3] = {static_cast<float>(n.structural_weight), static_cast<float>(n.compression_weight),
                  static_cast<float>(n.unstructured_weight)};
    if (live_slider("structural", "noise.structural", &w[0])) set_param("noise.structural", 0, w[0]);
    if (live_slider("compression", "noise.compression", &w[1])) set_param("noise.compression", 0, w[1]);
    if (live_slider("unstructured", "noise.unstructured", &w[2])) set_param("noise.unstructured", 0, w[2]);
  }
  if (ImGui::CollapsingHeader("Mouse")) {
    ImGui::TextWrapped(
        "2D panel: drag a jellyfish or an obstacle to move it; drag in the water to stir; right-click sets "
        "the selected jellyfish's steering target (c clears). 3D panel: drag to orbit, wheel to zoom. "
        "q quits.");
  }
  ImGui::End();
}

void Viewer::draw_views() {
  ImGuiIO& io = ImGui::GetIO();
  const double area_w = std::max(64.0, static_cast<double>(io.DisplaySize.x - kControlsWidth));
  const double panel_w = area_w / 2.0, panel_h = io.DisplaySize.y;
  const PanelMapping map = PanelMapping::fit(sim_->flow().grid, 4, 4, panel_w - 8, panel_h - 8);
  const double t0 = wall_now();
  const FieldImage image = field_image(sim_->flow(), field_, 0.0);
  field_texture_->upload(image.width, image.height, image.rgba);
  draw_options_.field = field_;
  draw_options_.field_range = image.range;
  scene_.draw(map, field_texture_->id(), *sim_, params_, draw_options_);
  const double t1 = wall_now();
  totals_.field_s += t1 - t0;
  if (meshes_dirty_) {
    meshes_.clear();
    for (std::size_t i = 0; i < sim_->jellyfish_count(); ++i) {
      meshes_.push_back(builders_[i].build(sim_->jellyfish(i).slice_frame(sim_->time_s())));
    }
    rebuild_obstacle_mesh();
    rebuild_snow_mesh();
    meshes_dirty_ = false;
  }
  const double t2 = wall_now();
  totals_.mesh_build_s += t2 - t1;
  std::vector<const geometry::Mesh*> meshes;
  for (const auto& m : meshes_) meshes.push_back(&m.mesh);
  const double t3 = wall_now();
  if (options_.profile) glFinish();  // the UI's share of the previous frame is done by now
  totals_.mesh_draw_s -= wall_now() - t3;
  const float fb_scale = io.DisplayFramebufferScale.x;
  const double scale = fb_scale * options_.render_scale;
  const GLuint texture = mesh_view_->draw(meshes, camera_, static_cast<int>(panel_w * scale),
                                          static_cast<int>(panel_h * scale), &obstacle_mesh_, &snow_mesh_);
  ImGui::GetBackgroundDrawList()->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture)),
                                           ImVec2(static_cast<float>(panel_w), 0),
                                           ImVec2(static_cast<float>(area_w), static_cast<float>(panel_h)),
                                           ImVec2(0, 1), ImVec2(1, 0));
  if (options_.profile) glFinish();
  totals_.mesh_draw_s += wall_now() - t2;
}

// ---- one frame ------------------------------------------------------------------------------

void Viewer::frame(double gap_s) {
  for (const std::string& key : window_->poll_keys()) handle_key(key);
  MouseState mouse = scripted_mouse();
  if (!have_script_mouse_) mouse = window_->real_mouse();
  window_->begin_ui(mouse, gap_s);
  ImGuiIO& io = ImGui::GetIO();
  const double area_w = std::max(64.0, static_cast<double>(io.DisplaySize.x - kControlsWidth));
  const PanelMapping map = PanelMapping::fit(sim_->flow().grid, 4, 4, area_w / 2.0 - 8, io.DisplaySize.y - 8);
  if (scene_.interact(map, mouse, !io.WantCaptureMouse, gap_s, *sim_, params_)) meshes_dirty_ = true;
  const bool over_3d = !io.WantCaptureMouse && mouse.x > area_w / 2.0 && mouse.x < area_w;
  if (over_3d && mouse.down[0]) {
    camera_.azimuth_deg -= io.MouseDelta.x * 0.4;
    camera_.elevation_deg = std::clamp(camera_.elevation_deg + io.MouseDelta.y * 0.4, -85.0, 85.0);
  }
  if (over_3d && mouse.wheel != 0.0) camera_.zoom = std::clamp(camera_.zoom * std::pow(1.15, mouse.wheel), 0.2, 20.0);
  draw_controls();
  for (const auto& [event, _] : pending_timeline_) record_timeline(*event);
  const double t0 = wall_now();
  step_simulation(gap_s);
  frame_stepping_s_ = wall_now() - t0;
  totals_.stepping_s += frame_stepping_s_;
  draw_views();
  const double t1 = wall_now();
  window_->render_ui();
  if (options_.profile) glFinish();
  totals_.present_s += wall_now() - t1;
}

void Viewer::capture_if_needed(bool last_frame) {
  const bool screenshot_at_exit = !options_.screenshot.empty() && (last_frame || options_.frames == 0);
  if (!recorder_.active() && !screenshot_requested_ && !screenshot_at_exit && !record_toggle_requested_) return;
  const int w = window_->width(), h = window_->height();
  last_capture_ = render::RgbImage(w, h);
  last_capture_.pixels = gl::read_screen_rgb(w, h);
  if (record_toggle_requested_) {
    record_toggle_requested_ = false;
    if (recorder_.active()) {
      recorder_.stop();
      message_ = "recording stopped: " + recorder_.dir().string();
    } else {
      const auto dir = options_.record_dir.empty() ? std::filesystem::path("out/view") : options_.record_dir;
      recorder_.start(dir, w, h, options_.target_fps > 0 ? options_.target_fps : 30.0, options_.record_png,
                      options_.record_mp4);
      message_ = "recording to " + dir.string();
    }
  }
  const std::string kept = keep_frame(last_capture_, recorder_, screenshot_requested_, options_.record_dir);
  if (!kept.empty()) message_ = kept;
  screenshot_requested_ = false;
}

int Viewer::run() {
  window_ = std::make_unique<Window>(options_.width_px, options_.height_px,
                                     "jellysim view" + (options_.scene_name.empty() ? "" : " - " + options_.scene_name),
                                     options_.vsync);
  renderer_ = window_->renderer_name();
  mesh_view_ = std::make_unique<MeshView>();
  field_texture_ = std::make_unique<gl::Texture>();
  if (!options_.record_dir.empty()) record_toggle_requested_ = true;
  const double period = options_.target_fps > 0 ? 1.0 / options_.target_fps : 0.0;
  double last_start = wall_now() - (period > 0 ? period : 1.0 / 30.0);
  while (!quit_ && !window_->close_requested() && (options_.frames == 0 || frame_index_ < options_.frames)) {
    const double start = wall_now();
    const double sim_before = sim_->time_s();
    frame(start - last_start);
    last_start = start;
    const bool last = options_.frames > 0 && frame_index_ + 1 == options_.frames;
    const double t_present = wall_now();
    capture_if_needed(last || quit_);
    window_->swap();
    totals_.present_s += wall_now() - t_present;
    const double end = wall_now();
    const double other = std::max(0.0, (end - start) - frame_stepping_s_);
    other_work_s_ = 0.9 * other_work_s_ + 0.1 * other;
    meter_.add(end, sim_->time_s(), last_steps_.behind);
    ++totals_.frames;
    totals_.steps += last_steps_.steps;
    if (last_steps_.behind) ++totals_.behind_frames;
    if (frame_index_ >= kWarmupFrames) {
      totals_.measured_frames += 1;
      const double frame_wall = end - start + std::max(0.0, period - (end - start));
      totals_.measured_wall_s += frame_wall;
      if (!paused_) {
        totals_.running_wall_s += frame_wall;
        totals_.running_sim_s += sim_->time_s() - sim_before;
      }
    }
    ++frame_index_;
    if (period > 0 && wall_now() - start < period) {
      std::this_thread::sleep_for(std::chrono::duration<double>(period - (wall_now() - start)));
    }
  }
  recorder_.stop();
  if (!options_.screenshot.empty() && last_capture_.width > 0) render::write_png(last_capture_, options_.screenshot);
  write_stats();
  return failure_.empty() ? 0 : 1;
}

// ---- statistics -----------------------------------------------------------------------------

nlohmann::json Viewer::state_json() const {
  nlohmann::json state;
  state["time_s"] = sim_->time_s();
  state["steps"] = sim_->steps();
  state["paused"] = paused_;
  state["mirror_symmetry"] = sim_->mirror_symmetric();
  nlohmann::json jellyfish = nlohmann::json::array();
  for (std::size_t i = 0; i < sim_->jellyfish_count(); ++i) {
    const JellyfishParams& p = params_.jellyfish[i];
    nlohmann::json j;
    j["centroid_m"] = vec_json(centroid(sim_->jellyfish(i).umbrella_points()));
    j["frequency_hz"] = p.frequency_hz;
    j["gamma"] = p.gamma;
    j["stiffness_scale"] = p.stiffness_scale;
    j["steer_target_m"] = p.steer_target_m ? vec_json(*p.steer_target_m) : nlohmann::json();
    jellyfish.push_back(j);
  }
  state["jellyfish"] = jellyfish;
  nlohmann::json obstacles = nlohmann::json::array();
  for (std::size_t k = 0; k < sim_->obstacle_count(); ++k) {
    obstacles.push_back({{"centroid_m", vec_json(centroid(sim_->obstacle_outline(k)))}});
  }
  state["obstacles"] = obstacles;
  state["viscosity"] = params_.viscosity_m2_per_s;
  state["noise"] = {{"structural", params_.noise.structural_weight},
                    {"compression", params_.noise.compression_weight},
                    {"unstructured", params_.noise.unstructured_weight}};
  return state;
}

void Viewer::write_stats() const {
  if (options_.stats.empty()) return;
  nlohmann::json s;
  s["frames"] = totals_.frames;
  s["steps"] = totals_.steps;
  s["fps"] = totals_.measured_wall_s > 0 ? totals_.measured_frames / totals_.measured_wall_s : 0.0;
  s["sim_rate"] = totals_.running_wall_s > 0 ? totals_.running_sim_s / totals_.running_wall_s : 0.0;
  s["target_speed"] = params_.speed;
  s["target_fps"] = options_.target_fps;
  s["min_fps"] = options_.min_fps;
  s["behind_frames"] = totals_.behind_frames;
  s["msaa_samples"] = mesh_view_ ? mesh_view_->samples() : 0;  // the 3D panel's multisampling
  s["steps_per_frame"] = totals_.frames > 0 ? static_cast<double>(totals_.steps) / totals_.frames : 0.0;
  s["warmup_frames"] = kWarmupFrames;
  const double per_frame_ms = totals_.frames > 0 ? 1000.0 / static_cast<double>(totals_.frames) : 0.0;
  s["profiled"] = options_.profile;
  s["ms_per_frame"] = {{"simulation_steps", totals_.stepping_s * per_frame_ms},
                       {"field_and_2d", totals_.field_s * per_frame_ms},
                       {"mesh_build", totals_.mesh_build_s * per_frame_ms},
                       {"mesh_draw", totals_.mesh_draw_s * per_frame_ms},
                       {"ui_render_readback_swap", totals_.present_s * per_frame_ms}};
  s["jellyfish_count"] = sim_->jellyfish_count();
  s["window"] = {window_ ? window_->width() : 0, window_ ? window_->height() : 0};
  s["renderer"] = renderer_;
  s["failure"] = failure_;
  s["state"] = state_json();
  s["timeline"] = timeline_;
  io::write_file(options_.stats, s.dump(2) + "\n");  // errors name the file and the reason
}

}  // namespace

void validate(const ViewerOptions& o) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw InputError(what);
  };
  require(o.width_px >= 320 && o.width_px <= 8192, "--width must be in [320, 8192] pixels");
  require(o.height_px >= 240 && o.height_px <= 8192, "--height must be in [240, 8192] pixels");
  require(o.target_fps >= 0 && o.target_fps <= 240, "--fps must be in [0, 240] (0: unpaced)");
  require(o.speed > 0 && o.speed <= 10, "--speed must be in (0, 10] simulated seconds per wall second");
  require(o.min_fps >= 1 && o.min_fps <= 240, "--min-fps must be in [1, 240]");
  require(o.render_scale > 0 && o.render_scale <= 1, "--3d-scale must be in (0, 1]");
  require(o.frames >= 0, "--frames must be ≥ 0 (0: until the window is closed)");
  geometry::validate_geometry_settings(o.geometry);
}

geometry::GeometrySettings interactive_geometry(const geometry::NoiseSettings& noise) {
  geometry::GeometrySettings g;
  g.latitude_samples = 33;
  g.disc_points = 40;
  g.tentacle_samples = 20;
  g.tentacle_count = 8;
  g.tube_sides = 4;
  g.noise = noise;
  return g;
}

int run_viewer(const jellyfish::SwimSettings& settings, const ViewerOptions& options) {
  validate(options);
  try {
    jellyfish::validate_layout(settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  Viewer viewer(settings, options);
  return viewer.run();
}

}  // namespace jellysim::viewer
