// Lid-driven cavity, thesis §8.1.3 and Figure 8.7, compared with Ghia, Ghia & Shin (1982).
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/scene/study_scenes.hpp"
#include "jellysim/studies/driven_cavity.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/io/vtk_fields.hpp"
#include "jellysim/render/field_picture.hpp"
#include "jellysim/render/plot.hpp"

namespace jellysim::experiments {
namespace {


using scene::CavityScene;
using scene::read_cavity_scene;

void write_profile_csv(const io::OutputDir& out, const std::string& name, const char* position, const char* velocity,
                       const studies::CentrelineProfile& p) {
  io::CsvWriter csv({position, velocity});
  for (std::size_t i = 0; i < p.position_m.size(); ++i) csv.row({p.position_m[i], p.velocity_m_per_s[i]});
  out.write_text(name, csv.text());
}

void write_ghia_csv(const io::OutputDir& out, const studies::GhiaComparison& g) {
  io::CsvWriter csv({"profile", "position", "reference", "computed", "difference"});
  for (std::size_t i = 0; i < g.reference_u.size(); ++i) {
    const auto& r = g.reference_u[i];
    csv.row("u", {r.position, r.velocity, r.velocity + g.u_error[i], g.u_error[i]});
  }
  for (std::size_t i = 0; i < g.reference_v.size(); ++i) {
    const auto& r = g.reference_v[i];
    csv.row("v", {r.position, r.velocity, r.velocity + g.v_error[i], g.v_error[i]});
  }
  out.write_text("ghia_comparison.csv", csv.text());
}

/// Writes each frame's field (.vti) and tracers (.vtp) into frames/ and remembers them for the .pvd.
class VtkFrameWriter {
 public:
  explicit VtkFrameWriter(const io::OutputDir& out) : out_(out), frames_(out.subdirectory("frames")) {}

  void operator()(double t, const fluid::FlowState& state, const std::vector<Vec2>& tracers) {
    const std::string id = std::to_string(1000000 + entries_.size() / 2).substr(1);
    const std::string field = "field_" + id + ".vti", points = "tracers_" + id + ".vtp";
    io::write_streamed(frames_, field, [&](std::ostream& o) { io::write_flow_vti(o, state); });
    io::write_streamed(frames_, points, [&](std::ostream& o) { io::write_points_vtp(o, tracers); });
    entries_.push_back({t, "frames/" + field, 0, "field"});
    entries_.push_back({t, "frames/" + points, 1, "tracers"});
  }
  /// The ParaView time series of every frame written so far.
  void write_series() const {
    if (!entries_.empty()) io::write_streamed(out_, "cavity.pvd", [&](std::ostream& o) { io::write_pvd(o, entries_); });
  }

 private:
  const io::OutputDir& out_;
  io::OutputDir frames_;
  std::vector<io::PvdEntry> entries_;
};

void write_pictures(const io::OutputDir& out, const studies::DrivenCavityResult& r, const std::string& caption) {
  render::FieldPicture picture;
  picture.state = &r.final_state;
  picture.caption = caption;
  picture.tracers_m = r.final_tracers_m;
  render::FieldPictureOptions options;
  out.write_text("cavity_speed.png", render::field_png(picture, options));
  options.quantity = render::FieldQuantity::vorticity;
  options.arrows = false;
  out.write_text("cavity_vorticity.png", render::field_png(picture, options));
  io::write_streamed(out, "cavity.vti", [&](std::ostream& o) { io::write_flow_vti(o, r.final_state); });
}

void write_figure_8_7(const io::OutputDir& out, const std::vector<studies::CavityFigurePanel>& panels) {
  std::vector<render::FieldPicture> pictures;
  for (const auto& p : panels) {
    render::FieldPicture picture;
    picture.state = &p.result.final_state;
    picture.caption = p.solver + ", nu = " + io::format_double(p.viscosity_m2_per_s);
    pictures.push_back(std::move(picture));
  }
  const int columns = static_cast<int>(panels.size() / 2 > 0 ? panels.size() / 2 : 1);
  render::FieldPictureOptions options;
  options.panel_px = 360;
  out.write_text("figure_8_7.png", render::field_panels_png(pictures, columns, options));
}

nlohmann::ordered_json key_figures(const studies::DrivenCavityResult& r, double tolerance) {
  nlohmann::ordered_json j;
  j["simulated_seconds"] = r.simulated_time_s;
  j["wall_seconds"] = r.wall_time_s;
  j["steps"] = r.steps;
  j["steady"] = r.steady;
  j["final_change_rate"] = r.final_change_rate;
  j["steady_tolerance"] = tolerance;
  // Which ended the run: the change rate fell below the tolerance, or the time limit came first.
  j["stopped_by"] = r.steady ? "steady_tolerance" : "max_time";
  j["viscosity"] = r.viscosity_m2_per_s;
  j["max_divergence_per_s"] = r.max_divergence_per_s;
  // The primary vortex: the stream function's minimum (ψ = 0 on the walls, ψ < 0 for the
  // clockwise vortex), and Ghia et al.'s Table V where they tabulate this Re.
  j["vortex_centre_x"] = r.primary_vortex.centre_m.x;
  j["vortex_centre_y"] = r.primary_vortex.centre_m.y;
  j["psi_min"] = r.primary_vortex.stream_function_m2_per_s;
  if (r.ghia) {
    j["ghia_max_abs_u_error"] = r.ghia->max_abs_u_error;
    j["ghia_max_abs_v_error"] = r.ghia->max_abs_v_error;
    j["ghia_vortex_centre_x"] = r.ghia->reference_vortex.x;
    j["ghia_vortex_centre_y"] = r.ghia->reference_vortex.y;
    j["ghia_psi_min"] = r.ghia->reference_vortex.stream_function;
  }
  j["messages"] = r.messages;
  return j;
}

/// convergence.csv (t, change_rate: max|Δu|/Δt · L/U² after each step) and convergence.png.
void write_convergence(const io::OutputDir& out, const studies::DrivenCavityResult& r, double tolerance) {
  io::CsvWriter csv({"t", "change_rate"});
  render::Series rate{"change rate max|du|/dt L/U^2", {}, {}};
  for (const auto& [t, c] : r.history) {
    csv.row({t, c});
    rate.x.push_back(t);
    rate.y.push_back(c);
  }
  out.write_text("convergence.csv", csv.text());
  render::ChartSpec chart;
  chart.title = "Driven cavity: convergence to a steady state";
  chart.x_label = "t";
  chart.x_unit = "s";
  chart.y_label = "change rate";
  chart.log_y = true;
  chart.series.push_back(std::move(rate));
  if (tolerance > 0.0 && !r.history.empty())
    chart.series.push_back({"steady tolerance", {r.history.front()[0], r.history.back()[0]}, {tolerance, tolerance},
                            false, true, true});
  out.write_text("convergence.png", render::chart_png(chart));
}

std::function<Outcome(const io::OutputDir&)> prepare_driven_cavity(const Context& ctx) {
  const CavityScene scene = read_cavity_scene(ctx.config);
  return [scene, ctx](const io::OutputDir& out) {
    studies::DrivenCavitySettings cavity = scene.cavity;
    std::shared_ptr<VtkFrameWriter> frames;
    if (cavity.frame_interval_s > 0.0) {
      frames = std::make_shared<VtkFrameWriter>(out);
      cavity.on_frame = [frames](double t, const fluid::FlowState& s, const std::vector<Vec2>& p) { (*frames)(t, s, p); };
    }
    const studies::DrivenCavityResult r = studies::run_driven_cavity(cavity);
    if (frames) frames->write_series();
    write_profile_csv(out, "centerline_u.csv", "y", "u", r.centreline_u);
    write_profile_csv(out, "centerline_v.csv", "x", "v", r.centreline_v);
    if (r.ghia) write_ghia_csv(out, *r.ghia);
    write_convergence(out, r, cavity.steady_tolerance);
    write_pictures(out, r, scene.cavity.solver + ", Re = " + io::format_double(scene.cavity.reynolds));
    if (scene.figure_enabled) write_figure_8_7(out, studies::run_cavity_figure_8_7(scene.figure));
    // Not reaching a steady state is reported (summary "steady": false), not treated as a failure.
    write_summary(out, "driven-cavity", ctx.config, key_figures(r, cavity.steady_tolerance), "");
    return Outcome{};
  };
}

}  // namespace

Experiment driven_cavity_experiment() {
  Experiment e{"driven-cavity", "Lid-driven cavity against Ghia et al. (1982) and thesis Figure 8.7 (§8.1.3)",
               "experiments/driven-cavity.toml", prepare_driven_cavity};
  e.shorthands = {"solver", "re", "grid", "steady-tolerance"};
  return e;
}

}  // namespace jellysim::experiments
