// `jellysim simulate` on a 3D scene (tank.geometry = "3d"; issue 40 part 4, docs/three-d.md "The 3D
// scene"): the shell bell in 3D water (swim3d::Swimmer3d) frame by frame, with metrics.csv (the
// bell's centroid, velocity, axis, heading, tilt and cavity volume per frame), summary.json (the
// swimming per cycle, the grid, the cost) and, with output.vtk, the flow of every frame
// (frames/field_NNNNNN.vti and jellyfish.pvd, named as the 2D run's), the markers with their
// velocities and forces (frames/bell_NNNNNN.vtp, the series' second part) and the bell's surface
// (frames/bell_NNNNNN.obj). A failure (the flow no longer
// finite, GMRES not converging) or SIGINT/SIGTERM ends the run with the frames recorded so far
// written and the time and step in the summary's failure, as the 2D run does (docs/architecture.md).
#include "jellyfish_3d.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "jellysim/core/errors.hpp"
#include "jellysim/core/interrupt.hpp"
#include "jellysim/core/memory.hpp"
#include "jellysim/io/mesh_files.hpp"
#include "jellysim/io/vtk_fields.hpp"
#include "jellysim/render/animation_outputs.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/scene/render_settings.hpp"

namespace jellysim::experiments {
namespace {

/// The bell's surface at the markers' positions (the shell's vertices come first), with
/// area-weighted vertex normals, as one mesh part "bell" for the OBJ writer.
geometry::Mesh bell_surface(const shell::TriangleMesh& surface, const ib3d::Markers3d& markers) {
  geometry::Mesh m;
  for (std::size_t i = 0; i < surface.vertices.size(); ++i)
    m.positions.push_back({markers.position[i][0], markers.position[i][1], markers.position[i][2]});
  m.normals.assign(m.positions.size(), geometry::Vec3{});
  for (const std::array<int, 3>& t : surface.triangles) {
    const auto corner = [&](int k) { return static_cast<std::size_t>(t[static_cast<std::size_t>(k)]); };
    const geometry::Vec3 n = geometry::cross(m.positions[corner(1)] - m.positions[corner(0)],
                                             m.positions[corner(2)] - m.positions[corner(0)]);
    for (int k = 0; k < 3; ++k) {
      m.normals[corner(k)] += n;
      m.indices.push_back(static_cast<std::uint32_t>(corner(k)));
    }
  }
  for (geometry::Vec3& n : m.normals) n = geometry::normalized(n);
  m.parts.push_back({"bell", 0, static_cast<std::uint32_t>(m.indices.size())});
  return m;
}

/// The swimmer's markers for ParaView: the bell's surface triangles and the tentacles' polylines
/// over every marker, with each marker's velocity (m/s) and the force it gave the water (N).
io::VtkSurface3d bell_polydata(const swim3d::Swimmer3d& swimmer) {
  const ib3d::Markers3d& m = swimmer.markers();
  io::VtkSurface3d d;
  d.points_m = m.position;
  d.triangles = swimmer.bell().surface().mesh.triangles;
  for (const std::vector<int>& rod : swimmer.bell().tentacles())
    if (rod.size() >= 2) d.polylines.push_back(rod);
  io::VtkArray velocity{"velocity", 3, {}}, force{"force", 3, {}};
  for (std::size_t k = 0; k < m.size(); ++k) {
    velocity.values.insert(velocity.values.end(), m.velocity[k].begin(), m.velocity[k].end());
    force.values.insert(force.values.end(), m.force[k].begin(), m.force[k].end());
  }
  d.point_data = {std::move(velocity), std::move(force)};
  return d;
}

/// A frame's number in file names: six digits, 000042.
std::string frame_id(std::size_t k) {
  char id[24];
  std::snprintf(id, sizeof id, "%06zu", k);
  return id;
}

/// The flow and the bell of each frame for ParaView (output.vtk): frames/field_NNNNNN.vti, the
/// solved part of the tank (the quarter or half tank's cells), and frames/bell_NNNNNN.vtp, every
/// marker (the whole bell and its tentacles), the two parts ("field", "bell") of the time series
/// jellyfish.pvd; and frames/bell_NNNNNN.obj, the bell's surface (a numbered file series).
class FrameFiles3d {
 public:
  explicit FrameFiles3d(const io::OutputDir& out) : out_(out), frames_(out.subdirectory("frames")) {}

  void write(const swim3d::Swimmer3d& swimmer, std::size_t index) {
    const std::string id = frame_id(index);
    const std::string field = "field_" + id + ".vti";
    io::write_streamed(frames_, field, [&](std::ostream& o) { io::write_flow_vti(o, swimmer.fluid().state()); });
    entries_.push_back({swimmer.time_s(), "frames/" + field, 0, "field"});
    const std::string bell = "bell_" + id + ".vtp";
    io::write_streamed(frames_, bell, [&](std::ostream& o) { io::write_surface_vtp(o, bell_polydata(swimmer)); });
    entries_.push_back({swimmer.time_s(), "frames/" + bell, 1, "bell"});
    io::write_streamed(out_, "jellyfish.pvd", [&](std::ostream& o) { io::write_pvd(o, entries_); });
    const std::string comment = "the bell at t = " + io::format_double(swimmer.time_s()) + " s";
    frames_.write_text("bell_" + id + ".obj",
                       io::obj_text(bell_surface(swimmer.bell().surface().mesh, swimmer.markers()), comment));
  }
  /// A resumed run: the frames written before its checkpoint are in the .pvd collection.
  void continue_after(const std::vector<swim3d::Frame3d>& frames) {
    for (std::size_t k = 0; k < frames.size(); ++k) {
      entries_.push_back({frames[k].time_s, "frames/field_" + frame_id(k) + ".vti", 0, "field"});
      entries_.push_back({frames[k].time_s, "frames/bell_" + frame_id(k) + ".vtp", 1, "bell"});
    }
  }

 private:
  const io::OutputDir& out_;
  io::OutputDir frames_;
  std::vector<io::PvdEntry> entries_;
};

/// "simulation diverged at t = … s (step N): why", the 2D run's words (sim/time_stepping.cpp).
std::string diverged(const swim3d::Swimmer3d& s, const std::string& why) {
  std::ostringstream m;
  m << "simulation diverged at t = " << s.time_s() << " s (step " << s.timings().steps << "): " << why;
  return m.str();
}

/// The first of a frame's figures that is not finite, named, or "".
std::string non_finite(const swim3d::Frame3d& f) {
  for (std::size_t d = 0; d < 3; ++d) {
    if (!std::isfinite(f.centroid[d])) return "the bell's centroid is not finite";
    if (!std::isfinite(f.velocity[d])) return "the bell's velocity is not finite";
    if (!std::isfinite(f.axis[d])) return "the bell's axis is not finite";
  }
  return std::isfinite(f.cavity_volume_m3) ? "" : "the cavity's volume is not finite";
}

/// The next frame, or the failure that stopped the run before it (SIGINT/SIGTERM between two
/// coupled steps; a step that threw; a figure that is not finite).
std::optional<swim3d::Frame3d> next_frame(swim3d::Swimmer3d& swimmer, std::string& failure) {
  try {
    do {  // step by step, so that SIGINT/SIGTERM stops the run within a step, not a frame
      if (const int signal = core::interrupt_signal()) {
        failure = "interrupted by " + core::signal_name(signal) + " at t = " + std::to_string(swimmer.time_s()) +
                  " s (step " + std::to_string(swimmer.timings().steps) + ")";
        return std::nullopt;
      }
    } while (!swimmer.step_toward_frame());
    swim3d::Frame3d f = swimmer.frame();
    if (const std::string why = non_finite(f); !why.empty()) {
      failure = diverged(swimmer, why);
      return std::nullopt;
    }
    return f;
  } catch (const std::runtime_error& e) {
    failure = diverged(swimmer, e.what());
    return std::nullopt;
  }
}

/// Recorded frames in a checkpoint (both directions).
void archive_frames_3d(core::StateArchive& a, std::vector<swim3d::Frame3d>& frames) {
  const core::StateArchive::Scope scope(a, "recording");
  a.length("count", frames);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const core::StateArchive::Scope frame(a, std::to_string(f));
    swim3d::Frame3d& s = frames[f];
    a.value("time", s.time_s);
    a.vector("points", s.points);
    a.value("centroid", s.centroid);
    a.value("velocity", s.velocity);
    a.value("axis", s.axis);
    a.value("heading", s.heading_deg);
    a.value("tilt", s.tilt_deg);
    a.value("volume", s.cavity_volume_m3);
    a.value("steps", s.steps);
    a.value("krylov_iterations", s.krylov_iterations);
  }
}

/// The most bytes a 3D checkpoint's state can hold: twice the water's estimate, the markers' four
/// arrays and every frame's points, with room for the entries' names.
double most_state_bytes_3d(const scene::Swim3dSettings& s, std::size_t markers) {
  const double per_frame = 24.0 * static_cast<double>(markers) + 1024.0;
  return 2.0 * (s.estimated_memory_bytes + 96.0 * static_cast<double>(markers) +
                static_cast<double>(s.frames + 1) * per_frame) + 65536.0;
}

/// Checkpoints of a 3D run (issue 23's file and rules, as run_swim's): written at the first frame
/// at or after every `every_s`, holding the swimmer and the frames so far.
class Checkpoints3d {
 public:
  Checkpoints3d(const Checkpointing* c, const io::OutputDir& out)
      : c_(c), out_(out), every_(c ? c->how.every_s : 0.0), next_(every_ > 0 ? next_checkpoint_time(0.0, every_) : 0.0) {}
  /// A resumed run: the swimmer and the frames as the checkpoint has them.
  void restore(swim3d::Swimmer3d& swimmer, const scene::Swim3dSettings& settings, std::vector<swim3d::Frame3d>& frames) {
    if (!c_ || !c_->resume) return;
    core::StateArchive state = core::StateArchive::restoring(
        io::read_checkpoint_state(c_->how, most_state_bytes_3d(settings, swimmer.markers().size())));
    swimmer.archive(state);
    archive_frames_3d(state, frames);
    state.check_all_read();
    next_ = next_checkpoint_time(swimmer.time_s(), every_);
  }
  /// After a frame is recorded: a checkpoint when one is due.
  void after_frame(swim3d::Swimmer3d& swimmer, std::vector<swim3d::Frame3d>& frames) {
    if (every_ > 0 && swimmer.time_s() >= next_ * (1.0 - 1e-12)) write(swimmer, frames);
  }
  /// At the end of a whole run: the run's end kept (`run` renders next) or the checkpoint removed.
  void finish(swim3d::Swimmer3d& swimmer, std::vector<swim3d::Frame3d>& frames) {
    if (every_ <= 0) return;
    if (c_->keep_when_whole) write(swimmer, frames);
    else out_.remove(io::kCheckpointName);
  }

 private:
  void write(swim3d::Swimmer3d& swimmer, std::vector<swim3d::Frame3d>& frames) {
    core::StateArchive state = core::StateArchive::saving();
    swimmer.archive(state);
    archive_frames_3d(state, frames);
    io::Checkpoint c = c_->how;
    c.inputs.clear();  // the 3D scene reads no files besides itself
    c.state = state.take_entries();
    io::write_checkpoint(out_, c);
    next_ = next_checkpoint_time(swimmer.time_s(), every_);
  }

  const Checkpointing* c_;
  const io::OutputDir& out_;
  double every_;
  double next_;  ///< simulated time of the next checkpoint
};

}  // namespace

/// Runs the frames, writing the flow and the bell of each when asked; progress after every frame.
Recording3d run_3d(const scene::Swim3dSettings& settings, const io::OutputDir& out,
                   const sim::ProgressCallback& progress, const Checkpointing* checkpoints) {
  const auto start = std::chrono::steady_clock::now();
  Recording3d rec;
  const auto swimmer = [&] {
    const fluid3d::Index3 n = swim3d::solved_grid(settings.spec).cells();
    const core::MemoryStage building("building the 3D simulation (" + std::to_string(n[0]) + " x " +
                                     std::to_string(n[1]) + " x " + std::to_string(n[2]) + " fluid cells)");
    return std::make_unique<swim3d::Swimmer3d>(settings.spec);
  }();
  rec.markers = swimmer->markers().size();
  for (const auto& t : swimmer->bell().surface().mesh.triangles)
    rec.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                             static_cast<std::uint32_t>(t[2])});
  rec.tentacles = swimmer->bell().tentacles();
  rec.surface_vertices = swimmer->bell().surface().mesh.vertices.size();
  std::optional<FrameFiles3d> files;
  if (settings.vtk) files.emplace(out);
  Checkpoints3d saved(checkpoints, out);
  saved.restore(*swimmer, settings, rec.frames);
  if (files) files->continue_after(rec.frames);
  const auto record = [&](swim3d::Frame3d f) {
    if (files) files->write(*swimmer, rec.frames.size());
    rec.frames.push_back(std::move(f));
    saved.after_frame(*swimmer, rec.frames);
  };
  if (rec.frames.empty()) record(swimmer->frame());
  for (auto k = static_cast<std::int64_t>(rec.frames.size()) - 1; k < settings.frames; ++k) {
    std::optional<swim3d::Frame3d> f = next_frame(*swimmer, rec.failure);
    if (!f) break;
    record(std::move(*f));
    if (progress) progress(swimmer->time_s(), settings.end_time_s(), swimmer->timings().steps);
  }
  if (rec.failure.empty()) saved.finish(*swimmer, rec.frames);
  rec.timings = swimmer->timings();
  rec.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return rec;
}

namespace {

/// metrics.csv: one row per frame (tank frame, SI units; docs/three-d.md "The 3D scene").
void write_metrics_3d(const io::OutputDir& out, const std::vector<swim3d::Frame3d>& frames) {
  io::CsvWriter csv({"t", "x", "y", "z", "velocity_x", "velocity_y", "velocity_z", "speed", "heading_deg", "tilt_deg",
                     "axis_x", "axis_y", "axis_z", "volume", "krylov_iterations"});
  for (const swim3d::Frame3d& f : frames) {
    const swim3d::Vec3& c = f.centroid;
    const swim3d::Vec3& v = f.velocity;
    const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    csv.row({f.time_s, c[0], c[1], c[2], v[0], v[1], v[2], speed, f.heading_deg, f.tilt_deg, f.axis[0], f.axis[1],
             f.axis[2], f.cavity_volume_m3, static_cast<double>(f.krylov_iterations)});
  }
  out.write_text("metrics.csv", csv.text());
}

/// A figure that may be NaN (a mean over no cycles) as JSON: null then.
nlohmann::ordered_json number_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; }

/// The grid the water was solved on (the whole tank, its half or its quarter).
nlohmann::ordered_json grid_figures(const swim3d::Swim3dSpec& spec) {
  const fluid3d::Grid3d g = swim3d::solved_grid(spec);
  return {{"tank_cells", spec.cells},
          {"tank_size_m", spec.tank_size_m},
          {"solved_cells", g.cells()},
          {"symmetry", std::string(swim3d::to_string(swim3d::resolved_symmetry(spec)))},
          {"cell_size_m", {g.h(0), g.h(1), g.h(2)}},
          {"cells_across_bell", spec.bell.slice.diameter_m / g.h(0)}};
}

/// The swimming per cycle (swim3d::summarize: cycles start at t = k / f).
void add_swimming_figures(nlohmann::ordered_json& j, const scene::Swim3dSettings& s, const Recording3d& rec) {
  const swim3d::SwimSummary3d sum = swim3d::summarize(rec.frames, s.spec.frames_per_cycle);
  j["distance_per_cycle_m"] = number_or_null(sum.distance_per_cycle_m);
  j["first_cycle_m"] = sum.first_cycle_m;
  j["cycle_displacements_m"] = sum.cycle_distance_m;
  j["heading_change_deg_per_cycle"] = number_or_null(sum.heading_change_deg_per_cycle);
  j["cycle_heading_changes_deg"] = sum.cycle_heading_deg;
  j["final_heading_deg"] = sum.final_heading_deg;
  j["final_tilt_deg"] = sum.final_tilt_deg;
  j["sideways_m"] = sum.sideways_m;
}

/// The run's frames and cost (wall-clock figures: summary.json only, never a CSV).
void add_cost_figures(nlohmann::ordered_json& j, const scene::Swim3dSettings& s, const Recording3d& rec) {
  const swim3d::Swim3dTimings& t = rec.timings;
  const double steps = t.steps > 0 ? static_cast<double>(t.steps) : 1.0;
  const double simulated = rec.frames.empty() ? 0.0 : rec.frames.back().time_s;
  j["simulated_seconds"] = simulated;
  j["wall_seconds"] = rec.wall_seconds;
  j["realtime_factor"] = rec.wall_seconds > 0 ? simulated / rec.wall_seconds : 0.0;
  j["frames"] = rec.frames.size();
  j["frames_per_cycle"] = s.spec.frames_per_cycle;
  j["duration"] = s.duration_s;
  j["duration_rounded_to_frames"] = s.end_time_s();
  j["steps"] = t.steps;
  j["ms_per_step"] = 1e3 * t.total_s / steps;
  j["ms_per_step_split"] = {{"transfer", 1e3 * t.transfer_s / steps},
                            {"fluid", 1e3 * t.fluid_s / steps},
                            {"krylov", 1e3 * t.krylov_s / steps}};
  j["krylov_iterations_per_step"] = static_cast<double>(t.krylov_iterations) / steps;
  j["estimated_memory_bytes"] = s.estimated_memory_bytes;
}

/// summary.json's figures (docs/three-d.md, "The 3D scene": the bell, its swimming, the grid, the cost).
nlohmann::ordered_json figures_3d(const scene::Swim3dSettings& s, const Recording3d& rec) {
  nlohmann::ordered_json j;
  j["units"] = {{"length", "m"}, {"time", "s"}, {"velocity", "m/s"}, {"volume", "m^3"}, {"angle", "deg"}};
  j["geometry"] = "3d";
  j["bell_diameter"] = s.spec.bell.slice.diameter_m;
  j["bell_height"] = s.spec.bell.slice.height_m;
  j["frequency"] = s.spec.bell.slice.frequency_hz;
  j["cycles"] = (rec.frames.empty() ? 0.0 : rec.frames.back().time_s) * s.spec.bell.slice.frequency_hz;
  j["pacemaker"] = s.spec.bell.pacemaker;
  add_swimming_figures(j, s, rec);
  j["grid"] = grid_figures(s.spec);
  j["markers"] = rec.markers;
  add_cost_figures(j, s, rec);
  return j;
}

/// The solved grid and the water's memory, before the run (a terminal's progress display only).
void print_estimate(const scene::Swim3dSettings& s) {
  const fluid3d::Index3 n = swim3d::solved_grid(s.spec).cells();
  std::cout << "3D water: " << n[0] << " x " << n[1] << " x " << n[2] << " cells solved ("
            << swim3d::to_string(swim3d::resolved_symmetry(s.spec)) << " tank), about "
            << core::format_bytes(s.estimated_memory_bytes) << "; " << s.frames << " frames\n";
}

/// The recorded frames as the renderer's plain data (the surface's vertices, then each rod's nodes):
/// the simulated surface itself, no 2D→3D extrapolation (docs/rendering.md, "The simulated 3D surface").
geometry::SurfaceFrames surface_frames(const Recording3d& rec, double thickness_m) {
  geometry::SurfaceFrames out;
  out.thickness_m = thickness_m;
  out.triangles = rec.triangles;
  for (const swim3d::Frame3d& f : rec.frames)
    geometry::append_surface_frame(out, f.time_s, f.points, rec.surface_vertices, rec.tentacles);
  return out;
}

/// The render settings of `jellysim run` for the 3D scene: the video plays in real time, the files
/// carry the renderer's look; the slice-only features are refused.
render::PipelineSettings read_pipeline_3d(const Context& ctx, const scene::Swim3dSettings& s) {
  if (scene::read_loop_settings(ctx.config).enabled)
    throw InputError("render.loop: the seamless loop is not made for the 3D scene (tank.geometry = \"3d\") yet");
  render::PipelineSettings p = scene::read_render_settings(ctx.config);
  p.fps = s.spec.frames_per_cycle * s.spec.bell.slice.frequency_hz;
  p.look = render::export_look(p.style);
  return p;
}

}  // namespace

std::function<Outcome(const io::OutputDir&)> prepare_animation_3d(const Context& ctx) {
  const scene::Swim3dSettings settings = scene::read_swim3d_settings(ctx.config);
  const render::PipelineSettings pipeline = read_pipeline_3d(ctx, settings);
  if (ctx.progress) print_estimate(settings);
  return [settings, pipeline, ctx](const io::OutputDir& out) {
    // With checkpoints, the simulation's end stays checkpointed until the animation is whole.
    const Recording3d rec = run_3d(settings, out, ctx.progress, ctx.checkpoints.get());
    write_metrics_3d(out, rec.frames);
    nlohmann::ordered_json figures = figures_3d(settings, rec);
    std::string failure = rec.failure;
    if (rec.frames.size() > 1) {  // a picture needs two frames of the surface at least
      if (ctx.render_progress) ctx.render_progress(0, rec.frames.size());
      const render::AnimationOutputs anim = render::write_surface_animation_outputs(
          surface_frames(rec, settings.spec.bell.slice.thickness_m), pipeline, out,
          [&ctx](std::size_t done, std::size_t total) {
            if (ctx.render_progress) ctx.render_progress(done, total);
          });
      figures["animation"] = anim.figures();
      if (failure.empty() && core::interrupt_signal() != 0 && anim.frames < rec.frames.size())
        failure = "interrupted by " + core::signal_name(core::interrupt_signal()) + " while rendering, after " +
                  std::to_string(anim.frames) + " of " + std::to_string(rec.frames.size()) + " frames";
    }
    write_summary(out, "run", ctx.config, figures, failure);
    if (ctx.checkpoints && failure.empty()) out.remove(io::kCheckpointName);  // whole: nothing to resume
    return Outcome{failure};
  };
}

std::function<Outcome(const io::OutputDir&)> prepare_jellyfish_3d(const Context& ctx) {
  const scene::Swim3dSettings settings = scene::read_swim3d_settings(ctx.config);
  if (ctx.progress) print_estimate(settings);
  return [settings, ctx](const io::OutputDir& out) {
    const Recording3d rec = run_3d(settings, out, ctx.progress, ctx.checkpoints.get());
    write_metrics_3d(out, rec.frames);
    write_summary(out, "simulate", ctx.config, figures_3d(settings, rec), rec.failure);
    return Outcome{rec.failure};
  };
}

}  // namespace jellysim::experiments
