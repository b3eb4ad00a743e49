#include "jellysim/elastic/spring_assembly.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <numbers>

#include "jellysim/core/errors.hpp"
#include "jellysim/core/memory.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/io/vtk_fields.hpp"
#include "jellysim/render/plot.hpp"

namespace jellysim::experiments {

namespace {


std::string frame_id(std::size_t k) { return std::to_string(1000000 + k).substr(1); }

/// The tracers for ParaView: per point its `id` and the fluid's `velocity` there (m/s).
io::VtkPolyData tracer_data(const jellyfish::SwimSimulation& sim) {
  io::VtkPolyData d;
  d.points_m = sim.tracers().positions();
  io::VtkArray id{"id", 1, {}, true}, velocity{"velocity", 3, {}, false};
  const fluid::Velocity& u = sim.flow().velocity;
  for (std::size_t k = 0; k < d.points_m.size(); ++k) {
    id.values.push_back(static_cast<double>(k));
    velocity.values.insert(velocity.values.end(), {u.u.sample(d.points_m[k]), u.v.sample(d.points_m[k]), 0.0});
  }
  d.point_data = {std::move(id), std::move(velocity)};
  return d;
}

/// Every marker and spring of the coupled body for ParaView. Points: `kind` (0 a marker, 1 pinned,
/// 2 a target point on a prescribed path: elastic::PointKind), `velocity` (m/s), `force` (the
/// springs' force on the point, N per metre of depth). Springs: `muscle` (1 for a subumbrellar
/// muscle) and `strain` (length / rest length − 1; 0 for a zero rest length).
io::VtkPolyData body_data(const jellyfish::SwimSimulation& sim) {
  const elastic::Body& b = sim.body();
  io::VtkPolyData d;
  d.points_m = b.points.position;
  std::vector<Vec2> force(b.points.size());
  elastic::add_spring_forces(b, b.points.position, force);
  io::VtkArray kind{"kind", 1, {}, true}, velocity{"velocity", 3, {}, false}, f{"force", 3, {}, false};
  for (std::size_t p = 0; p < b.points.size(); ++p) {
    kind.values.push_back(static_cast<double>(b.points.kind[p]));
    velocity.values.insert(velocity.values.end(), {b.points.velocity[p].x, b.points.velocity[p].y, 0.0});
    f.values.insert(f.values.end(), {force[p].x, force[p].y, 0.0});
  }
  io::VtkArray muscle{"muscle", 1, std::vector<double>(b.linear.size(), 0.0), true}, strain{"strain", 1, {}, false};
  for (std::size_t j = 0; j < sim.jellyfish_count(); ++j)
    for (int s : sim.jellyfish(j).layout().muscle_springs) muscle.values[static_cast<std::size_t>(s)] = 1.0;
  for (std::size_t s = 0; s < b.linear.size(); ++s) {
    d.lines.push_back({b.linear.i[s], b.linear.j[s]});
    const double rest = b.linear.rest_length[s];
    const double length = norm(b.points.position[static_cast<std::size_t>(b.linear.j[s])] -
                               b.points.position[static_cast<std::size_t>(b.linear.i[s])]);
    strain.values.push_back(rest > 0.0 ? length / rest - 1.0 : 0.0);
  }
  d.point_data = {std::move(kind), std::move(velocity), std::move(f)};
  // Without springs (an IB2d structure of a .vertex file alone) the points are the cells: no
  // spring arrays then.
  if (!d.lines.empty()) d.cell_data = {std::move(muscle), std::move(strain)};
  return d;
}

/// What one frame's files need, captured from the simulation (on its thread) so that the writer
/// thread can write them while the simulation computes the next frame.
struct FrameSnapshot {
  std::size_t index = 0;
  double time_s = 0.0;
  std::optional<fluid::FlowState> flow;          ///< the field (VTK) and the picture's background
  io::VtkPolyData tracers, body;                 ///< VTK only
  std::optional<render::FieldPicture> picture;   ///< its state is `flow`, set by the writer
};

/// Writes the per-frame files and keeps the .pvd entries, on a writer thread (issue 34: outputs
/// off the simulation's critical path). The files and their order are those of writing them in
/// the loop; an error is reported by the next frame's write() or by flush().
class FrameFiles {
 public:
  FrameFiles(const io::OutputDir& out, const SwimOutputOptions& o) : out_(out), frames_(out.subdirectory("frames")), options_(o) {}

  void write(const jellyfish::SwimSimulation& sim, std::size_t index) {
    auto snapshot = std::make_shared<FrameSnapshot>(capture(sim, index));
    writer_.submit([this, snapshot] { write_snapshot(*snapshot); });
  }

  /// Waits until every frame so far is on disk (before a checkpoint, and at the end of the run);
  /// rethrows a write's error.
  void flush() { writer_.drain(); }

  /// A run resumed from a checkpoint: the frames written before it are in the .pvd collection.
  void continue_after(const std::vector<double>& frame_times) {
    if (!options_.vtk) return;
    for (std::size_t k = 0; k < frame_times.size(); ++k) add_pvd_entries(frame_times[k], frame_id(k));
  }

 private:
  bool draws_picture(std::size_t index) const {
    return options_.pictures && index % static_cast<std::size_t>(options_.picture_every) == 0;
  }

  /// On the simulation's thread: copies of what the files show.
  FrameSnapshot capture(const jellyfish::SwimSimulation& sim, std::size_t index) const {
    FrameSnapshot s;
    s.index = index;
    s.time_s = sim.time_s();
    if (options_.vtk || draws_picture(index)) s.flow = sim.flow();
    if (options_.vtk) {
      s.tracers = tracer_data(sim);
      s.body = body_data(sim);
    }
    if (draws_picture(index)) {
      s.picture = swim_picture(sim, options_.zoom_diameters);
      s.picture->state = nullptr;  // the snapshot's copy, once it has its place
    }
    return s;
  }

  /// On the writer's thread.
  void write_snapshot(FrameSnapshot& s) {
    const std::string id = frame_id(s.index);
    if (options_.vtk) {
      io::write_streamed(frames_, field_file(id), [&](std::ostream& o) { io::write_flow_vti(o, *s.flow); });
      io::write_streamed(frames_, tracers_file(id), [&](std::ostream& o) { io::write_polydata_vtp(o, s.tracers); });
      io::write_streamed(frames_, body_file(id), [&](std::ostream& o) { io::write_polydata_vtp(o, s.body); });
      add_pvd_entries(s.time_s, id);
      io::write_streamed(out_, "jellyfish.pvd", [&](std::ostream& o) { io::write_pvd(o, entries_); });
    }
    if (s.picture) {
      render::FieldPictureOptions po;
      po.quantity = options_.quantity;
      po.arrows = options_.quantity == render::FieldQuantity::speed;
      s.picture->state = &*s.flow;
      frames_.write_text("slice_" + id + ".png", render::field_png(*s.picture, po));
    }
  }

  static std::string field_file(const std::string& id) { return "field_" + id + ".vti"; }
  static std::string tracers_file(const std::string& id) { return "tracers_" + id + ".vtp"; }
  static std::string body_file(const std::string& id) { return "body_" + id + ".vtp"; }
  void add_pvd_entries(double t, const std::string& id) {
    entries_.push_back({t, "frames/" + field_file(id), 0, "field"});
    entries_.push_back({t, "frames/" + tracers_file(id), 1, "tracers"});
    entries_.push_back({t, "frames/" + body_file(id), 2, "body"});
  }

  const io::OutputDir& out_;
  io::OutputDir frames_;
  SwimOutputOptions options_;
  std::vector<io::PvdEntry> entries_;  ///< the writer's (and continue_after's, before any frame)
  SerialWorker writer_{2};             ///< last: drained before the members its jobs use go
};

/// Recorded slice frames in a checkpoint (both directions).
void archive_frames(core::StateArchive& a, const std::string& name, std::vector<jellyfish::SliceFrame>& frames) {
  const core::StateArchive::Scope scope(a, name);
  a.length("count", frames);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const core::StateArchive::Scope frame(a, std::to_string(f));
    jellyfish::SliceFrame& s = frames[f];
    a.value("time", s.time_s);
    a.vector("umbrella", s.umbrella);
    a.nested("tentacles", s.tentacles);
    a.vector("muscles", s.muscles);
    a.value("thickness", s.thickness_m);
    a.value("axis", s.axis);
  }
}

/// What run_swim has recorded so far, in a checkpoint (both directions; metrics and stats are
/// computed at the end).
void archive_recording(core::StateArchive& a, SwimRecording& rec) {
  const core::StateArchive::Scope scope(a, "recording");
  a.vector("frame_times", rec.frame_times);
  archive_frames(a, "frames", rec.frames);
  for (std::size_t k = 0; k < rec.others.size(); ++k) archive_frames(a, "jellyfish_" + std::to_string(k + 2), rec.others[k]);
  a.nested("obstacle_forces", rec.obstacle_forces);
  if (a.is_restoring()) rec.obstacle_outlines.resize(rec.obstacle_forces.size());
  for (std::size_t f = 0; f < rec.obstacle_outlines.size(); ++f)
    a.nested("obstacle_outlines_" + std::to_string(f), rec.obstacle_outlines[f]);
  a.nested("structure_centroids", rec.structure_centroids);
  a.nested("tracers", rec.tracers);
}

/// The files the scene read besides the scene file (IB2d structures'), in scene order.
std::vector<std::string> scene_inputs(const jellyfish::SwimSettings& settings) {
  std::vector<std::string> files;
  for (const jellyfish::Ib2dObjectSpec& st : settings.structures) files.insert(files.end(), st.files.begin(), st.files.end());
  return files;
}

/// A resumed run reads the files its scene read when it was checkpointed, no more and no fewer:
/// else its bodies are not those of the checkpoint (InputError naming the file).
void check_scene_inputs(const io::Checkpoint& c, const jellyfish::SwimSettings& settings) {
  const std::vector<std::string> now = scene_inputs(settings);
  const std::string resuming = "--resume: the checkpointed run ('" + c.file.string() + "') read ";
  for (const std::string& file : c.inputs)
    if (std::find(now.begin(), now.end(), file) == now.end())
      throw InputError(resuming + "the scene's file '" + file + "', which is missing now: restore it to resume");
  for (const std::string& file : now)
    if (std::find(c.inputs.begin(), c.inputs.end(), file) == c.inputs.end())
      throw InputError(resuming + "no file '" + file + "', which the scene reads now: remove it to resume");
}

/// The most bytes a checkpoint's state can hold for `settings`: what the run holds in memory
/// (its estimate, an upper bound) with a margin, plus the tracers (not in the estimate).
double most_state_bytes(const jellyfish::SwimSettings& settings) {
  const double tracers = static_cast<double>(settings.tank.tracers_per_side) * settings.tank.tracers_per_side;
  return 2.0 * jellyfish::estimate_memory(settings).bytes + 64.0 * tracers;
}

/// A resumed run: the simulation and the recording as the checkpoint has them, once the scene's
/// files and the state's size are known to be this run's.
void restore_checkpoint(const io::Checkpoint& c, const jellyfish::SwimSettings& settings, jellyfish::SwimSimulation& sim,
                        SwimRecording& rec) {
  check_scene_inputs(c, settings);
  core::StateArchive state = core::StateArchive::restoring(io::read_checkpoint_state(c, most_state_bytes(settings)));
  sim.restore_state(state);
  archive_recording(state, rec);
  state.check_all_read();
}

}  // namespace

double next_checkpoint_time(double t, double every) { return (std::floor(t / every + 1e-9) + 1.0) * every; }

SwimOutputOptions read_output_options(const config::Config& c) {
  const scene::Reader r(c, scene::jellyfish_scene());
  SwimOutputOptions o;
  o.pictures = r.boolean("output.pictures");
  o.picture_every = static_cast<int>(r.integer("output.picture_every"));
  o.quantity = r.choice("output.picture_quantity") == "speed" ? render::FieldQuantity::speed
                                                             : render::FieldQuantity::vorticity;
  o.zoom_diameters = scene::read_picture_zoom(c);
  o.vtk = r.boolean("output.vtk");
  return o;
}

render::FieldPicture swim_picture(const jellyfish::SwimSimulation& sim, double zoom_diameters) {
  render::FieldPicture p;
  p.state = &sim.flow();
  p.tracers_m = sim.tracers().positions();
  for (std::size_t j = 0; j < sim.jellyfish_count(); ++j) {
    const jellyfish::Jellyfish& jelly = sim.jellyfish(j);
    const elastic::Body& b = jelly.body();
    const auto& muscles = jelly.layout().muscle_springs;
    const auto& hoops = jelly.layout().hoop_springs;  // a ring jellyfish's: not drawn (they close each ring)
    for (std::size_t s = jelly.first_linear_spring(); s < jelly.first_linear_spring() + jelly.linear_spring_count(); ++s) {
      if (std::find(hoops.begin(), hoops.end(), static_cast<int>(s)) != hoops.end()) continue;
      const std::array<Vec2, 2> seg{b.points.position[static_cast<std::size_t>(b.linear.i[s])],
                                    b.points.position[static_cast<std::size_t>(b.linear.j[s])]};
      const bool muscle = std::find(muscles.begin(), muscles.end(), static_cast<int>(s)) != muscles.end();
      (muscle ? p.thin_segments_m : p.segments_m).push_back(seg);
    }
  }
  for (std::size_t o = 0; o < sim.obstacle_count(); ++o) {
    const std::vector<Vec2> outline = sim.obstacle_outline(o);
    for (std::size_t k = 0; k < outline.size(); ++k) p.segments_m.push_back({outline[k], outline[(k + 1) % outline.size()]});
  }
  // IB2d structures: their springs (scheduled ones, the muscles, thin); targets' tethers not drawn.
  for (std::size_t k = 0; k < sim.structure_count(); ++k) {
    const jellyfish::Ib2dParts& parts = sim.structure(k);
    const jellyfish::Ib2dObjectSpec& spec = sim.settings().structures[k];
    const elastic::Body& b = sim.body();
    for (std::size_t r = 0; r < parts.spring.size(); ++r) {
      if (parts.spring[r] < 0) continue;
      const std::size_t s = static_cast<std::size_t>(parts.spring[r]);
      const std::array<Vec2, 2> seg{b.points.position[static_cast<std::size_t>(b.linear.i[s])],
                                    b.points.position[static_cast<std::size_t>(b.linear.j[s])]};
      const bool scheduled = std::any_of(spec.schedules.begin(), spec.schedules.end(), [&](const auto& sc) {
        return static_cast<int>(r) >= sc.first && static_cast<int>(r) <= sc.last;
      });
      (scheduled ? p.thin_segments_m : p.segments_m).push_back(seg);
    }
  }
  char caption[64];
  std::snprintf(caption, sizeof caption, "t = %.2f s", sim.time_s());
  p.caption = caption;
  // One jellyfish alone: follow it; a busier tank: show all of it.
  if (zoom_diameters > 0 && sim.jellyfish_count() == 1 && sim.obstacle_count() == 0) {
    const jellyfish::BellShape bell = jellyfish::measure_bell(sim.jellyfish().umbrella_points());
    const double half = 0.5 * zoom_diameters * sim.settings().jellyfish().diameter_m;
    p.view_m = std::array<Vec2, 2>{bell.centroid - Vec2{half, half}, bell.centroid + Vec2{half, half}};
  }
  return p;
}

void write_vorticity_panels(const io::OutputDir& out, const std::string& name,
                            const std::vector<render::FieldPicture>& panels) {
  render::FieldPictureOptions po;
  po.quantity = render::FieldQuantity::vorticity;
  po.arrows = false;
  po.colour_range_max = 10.0;  // 1/s: the same scale in every panel
  if (!panels.empty()) out.write_text(name, render::field_panels_png(panels, static_cast<int>(panels.size()), po));
}

SwimRecording run_swim(const jellyfish::SwimSettings& settings, const SwimOutputOptions& options,
                       const io::OutputDir* out, const sim::ProgressCallback& progress,
                       const Checkpointing* checkpoints) {
  SwimRecording rec;
  const bool frame_files = out && (options.vtk || options.pictures);
  // Tracers are drawn in the pictures, written to the VTK files and become the animation's marine
  // snow, and nothing else reads them: without those outputs they are not advected (about 8 % of a
  // default run's time).
  jellyfish::SwimSettings run_settings = settings;
  if (!frame_files && !options.record_tracers) run_settings.tank.tracers_per_side = 0;
  const auto owner = [&] {
    const core::MemoryStage building("building the simulation (" + std::to_string(settings.tank.cells_x) + " x " +
                                     std::to_string(settings.tank.cells_y) + " fluid cells)");
    return std::make_unique<jellyfish::SwimSimulation>(run_settings);
  }();
  jellyfish::SwimSimulation& sim = *owner;
  std::unique_ptr<FrameFiles> files;
  if (frame_files) files = std::make_unique<FrameFiles>(*out, options);
  rec.others.resize(sim.jellyfish_count() > 1 ? sim.jellyfish_count() - 1 : 0);
  std::size_t frame = 0;
  if (checkpoints && checkpoints->resume) {
    restore_checkpoint(checkpoints->how, settings, sim, rec);
    frame = rec.frame_times.size();
    if (files) files->continue_after(rec.frame_times);
  }
  const double every = out && checkpoints ? checkpoints->how.every_s : 0.0;
  double next_checkpoint = every > 0 ? next_checkpoint_time(sim.time_s(), every) : INFINITY;
  // A checkpoint at a frame: the simulation, then what has been recorded up to that frame.
  auto write_checkpoint = [&](const jellyfish::SwimSimulation& s) {
    if (files) files->flush();  // a resumed run finds every frame before the checkpoint on disk
    core::StateArchive state = core::StateArchive::saving();
    s.save_state(state);
    archive_recording(state, rec);
    io::Checkpoint c = checkpoints->how;
    c.inputs = scene_inputs(settings);
    c.state = state.take_entries();
    io::write_checkpoint(*out, c);
    next_checkpoint = next_checkpoint_time(s.time_s(), every);
  };
  rec.stats = sim.run(
      [&](const jellyfish::SwimSimulation& s) -> std::string {
        if (files) files->write(s, frame);
        ++frame;
        jellyfish::record_frame(s, options.record_tracers, rec);
        // Never a checkpoint of a state that failed (run() draws it as a last frame).
        if (s.time_s() >= next_checkpoint * (1.0 - 1e-12) && s.check().empty()) write_checkpoint(s);
        return {};
      },
      progress, static_cast<std::int64_t>(frame),
      options.stop_when ? std::function<bool()>([&] { return options.stop_when(rec); }) : std::function<bool()>());
  if (files) files->flush();  // every frame on disk (or a write's error) before the run's own files
  if (every > 0 && rec.stats.failure.empty()) {  // the run is whole
    if (checkpoints->keep_when_whole) write_checkpoint(sim);
    else out->remove(io::kCheckpointName);
  }
  // A metric that is not finite is a divergence too, even where the state stayed finite.
  const std::string divergence = jellyfish::compute_school_metrics(settings, rec);
  if (rec.stats.failure.empty()) rec.stats.failure = divergence;
  return rec;
}

void write_metrics_csv(const io::OutputDir& out, const std::vector<jellyfish::MetricsRow>& rows,
                       const std::string& name) {
  io::CsvWriter csv({"t", "position", "velocity", "acceleration", "volume", "aperture_area", "volume_ratio",
                     "aperture_ratio", "thrust", "lateral", "daniel_velocity", "daniel_position"});
  for (const auto& r : rows)
    csv.row({r.t, r.position, r.velocity, r.acceleration, r.volume, r.aperture_area, r.volume_ratio, r.aperture_ratio,
             r.thrust, r.lateral, r.daniel_velocity, r.daniel_position});
  out.write_text(name, csv.text());
}

void write_scene_extras(const io::OutputDir& out, const SwimRecording& rec) {
  for (std::size_t k = 0; k < rec.other_metrics.size(); ++k)
    write_metrics_csv(out, rec.other_metrics[k], "metrics_jellyfish_" + std::to_string(k + 2) + ".csv");
  if (!rec.obstacle_forces.empty() && !rec.obstacle_forces.front().empty()) {
    io::CsvWriter csv({"t", "obstacle", "force_x", "force_y"});
    for (std::size_t f = 0; f < rec.obstacle_forces.size(); ++f)
      for (std::size_t o = 0; o < rec.obstacle_forces[f].size(); ++o)
        csv.row({rec.frame_times[f], static_cast<double>(o), rec.obstacle_forces[f][o].x, rec.obstacle_forces[f][o].y});
    out.write_text("obstacles.csv", csv.text());
  }
  if (!rec.structure_centroids.empty() && !rec.structure_centroids.front().empty()) {
    io::CsvWriter csv({"t", "structure", "centroid_x", "centroid_y"});
    for (std::size_t f = 0; f < rec.structure_centroids.size(); ++f)
      for (std::size_t k = 0; k < rec.structure_centroids[f].size(); ++k)
        csv.row({rec.frame_times[f], static_cast<double>(k), rec.structure_centroids[f][k].x, rec.structure_centroids[f][k].y});
    out.write_text("structures.csv", csv.text());
  }
}

void write_slices_csv(const io::OutputDir& out, const std::vector<jellyfish::SliceFrame>& frames,
                      const std::string& name) {
  io::CsvWriter csv({"part", "frame", "t", "index", "x", "y"});  // text cells come first in each row
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto& fr = frames[f];
    for (std::size_t i = 0; i < fr.umbrella.size(); ++i)
      csv.row({"umbrella"}, {static_cast<double>(f), fr.time_s, static_cast<double>(i), fr.umbrella[i].x, fr.umbrella[i].y});
    for (std::size_t k = 0; k < fr.tentacles.size(); ++k)
      for (std::size_t i = 0; i < fr.tentacles[k].size(); ++i)
        csv.row({"tentacle_" + std::to_string(k)},
                {static_cast<double>(f), fr.time_s, static_cast<double>(i), fr.tentacles[k][i].x, fr.tentacles[k][i].y});
  }
  out.write_text(name, csv.text());
}

void write_swim_plots(const io::OutputDir& out, const std::vector<jellyfish::MetricsRow>& rows,
                      const std::string& title) {
  auto series = [&](const std::string& label, auto get) {
    render::Series s;
    s.label = label;
    for (const auto& r : rows) {
      s.x.push_back(r.t);
      s.y.push_back(get(r));
    }
    return s;
  };
  auto chart = [&](const std::string& name, const std::string& chart_title, const std::string& quantity,
                   const std::string& unit, std::vector<render::Series> list) {
    // A run that diverged may leave a quantity with no finite value (its failure says why): no chart.
    const auto finite = [](const render::Series& s) {
      for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k)
        if (std::isfinite(s.x[k]) && std::isfinite(s.y[k])) return true;
      return false;
    };
    if (std::none_of(list.begin(), list.end(), finite)) return;
    render::ChartSpec c;
    c.title = chart_title;
    c.x_label = "t";
    c.x_unit = "s";
    c.y_label = quantity;
    c.y_unit = unit;
    c.series = std::move(list);
    out.write_text(name, render::chart_png(c));
  };
  chart("position.png", title + ": position (Fig. 8.15)", "bell centroid travelled", "m",
        {series("bell centroid", [](const auto& r) { return r.position; }),
         series("Daniel's model (eq. 6.5)", [](const auto& r) { return r.daniel_position; })});
  chart("velocity.png", title + ": velocity (Fig. 8.16)", "velocity", "m/s",
        {series("bell centroid", [](const auto& r) { return r.velocity; }),
         series("Daniel's model (eq. 6.5)", [](const auto& r) { return r.daniel_velocity; })});
  chart("acceleration.png", title + ": acceleration (Fig. 8.17)", "acceleration", "m/s²",
        {series("bell centroid", [](const auto& r) { return r.acceleration; })});
  chart("morphology.png", title + ": morphology (Fig. 8.18)", "ratio to rest", "",
        {series("volume V/V0", [](const auto& r) { return r.volume_ratio; }),
         series("aperture A/A0", [](const auto& r) { return r.aperture_ratio; })});
}

namespace {

// The run's cost and how it was solved (summary.json's last fields).
void add_run_figures(nlohmann::ordered_json& j, const jellyfish::SwimSettings& settings, const SwimRecording& rec) {
  j["simulated_seconds"] = rec.stats.simulated_seconds;
  j["wall_seconds"] = rec.stats.wall_seconds;
  j["realtime_factor"] = rec.stats.wall_seconds > 0 ? rec.stats.simulated_seconds / rec.stats.wall_seconds : 0.0;
  j["steps"] = rec.stats.steps;
  j["smallest_step"] = rec.stats.smallest_step_s;
  j["largest_step"] = rec.stats.largest_step_s;
  j["krylov_iterations"] = rec.stats.krylov_iterations;
  j["frames"] = rec.frame_times.size();
  // The frame grid (docs/rendering.md, "Frame rate"): the run ends on the frame nearest the duration
  // asked for, at that frame's grid time.
  j["fps"] = settings.frames_per_second > 0.0 ? settings.frames_per_second : 1.0 / settings.frame_interval_s;
  j["frame_interval"] = settings.frame_interval_s;
  j["duration"] = settings.duration_s;
  j["duration_rounded_to_frames"] = settings.frame_clock(settings.duration_s).end_time();
  j["markers"] = rec.frames.empty() ? 0 : rec.frames.front().umbrella.size();
  j["coupling"] = std::string(coupling::to_string(settings.coupling.scheme));
  j["fluid_solver"] = settings.tank.solver;
  j["symmetry"] = rec.stats.mirror_symmetric ? "mirror" : "none";
  j["half_tank"] = rec.stats.half_tank;
  if (!rec.stats.symmetry_note.empty()) j["symmetry_note"] = rec.stats.symmetry_note;
}

}  // namespace

nlohmann::ordered_json swim_figures(const jellyfish::SwimSettings& settings, const SwimRecording& rec) {
  nlohmann::ordered_json j;
  j["units"] = {{"length", "m"}, {"time", "s"}, {"velocity", "m/s"}, {"acceleration", "m/s^2"}, {"volume", "m^3"},
                {"area", "m^2"}, {"thrust", "N"}, {"modulus", "Pa"}};
  if (!settings.school.empty()) {
    const jellyfish::SwimSummary sum = jellyfish::summarize_swim(settings, rec, rec.stats.simulated_seconds);
    j["bell_height"] = settings.jellyfish().height_m;
    j["bell_diameter"] = settings.jellyfish().diameter_m;
    j["frequency"] = settings.jellyfish().frequency_hz;
    j["cycles"] = sum.cycles;
    j["distance_travelled"] = sum.distance_m;
    j["distance_in_bell_heights"] = sum.distance_m / settings.jellyfish().height_m;
    j["lateral_drift"] = sum.lateral_drift_m;
    j["mean_speed"] = sum.mean_speed_m_per_s;
    j["volume_frequency"] = sum.volume_frequency_hz;
    j["min_volume_ratio"] = sum.min_volume_ratio;
    j["min_aperture_ratio"] = sum.min_aperture_ratio;
    j["daniel_distance"] = sum.daniel_distance_m;
  }
  j["jellyfish_count"] = settings.school.size();
  if (settings.school.size() > 1) {
    nlohmann::ordered_json each = nlohmann::ordered_json::array();
    auto describe = [&](const std::vector<jellyfish::MetricsRow>& rows) {
      return nlohmann::ordered_json{{"distance_travelled", rows.empty() ? 0.0 : rows.back().position},
                                    {"lateral_drift", rows.empty() ? 0.0 : rows.back().lateral}};
    };
    each.push_back(describe(rec.metrics));
    for (const auto& rows : rec.other_metrics) each.push_back(describe(rows));
    j["school"] = each;
  }
  j["obstacle_count"] = settings.obstacles.size();
  if (!settings.obstacles.empty() && !rec.obstacle_forces.empty()) {
    // Mean force over the second half of the run (after the start-up transient).
    nlohmann::ordered_json each = nlohmann::ordered_json::array();
    const std::vector<Vec2> means = jellyfish::mean_obstacle_forces(rec, settings.obstacles.size());
    for (std::size_t o = 0; o < settings.obstacles.size(); ++o)
      each.push_back({{"name", settings.obstacles[o].name}, {"mean_force", {means[o].x, means[o].y}}});
    j["obstacles"] = each;
  }
  j["structure_count"] = settings.structures.size();
  if (!settings.structures.empty() && !rec.structure_centroids.empty()) {
    nlohmann::ordered_json each = nlohmann::ordered_json::array();
    const std::vector<Vec2> moved = jellyfish::structure_displacements(rec, settings.structures.size());
    for (std::size_t k = 0; k < settings.structures.size(); ++k)
      each.push_back({{"name", settings.structures[k].name}, {"centroid_displacement", {moved[k].x, moved[k].y}}});
    j["structures"] = each;
  }
  add_run_figures(j, settings, rec);
  return j;
}

}  // namespace jellysim::experiments
