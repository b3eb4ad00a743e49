#include "experiments/jellyfish_runs.hpp"

#include <cmath>
#include <numbers>

#include "io/errors.hpp"
#include "io/vtk_fields.hpp"
#include "render/plot.hpp"

namespace jellysim::experiments {

namespace {

using io::write_via_temporary;

constexpr double kDegree = std::numbers::pi / 180.0;

fluid::BoundaryType read_boundary(const std::string& name) {
  return *fluid::boundary_type_from_string(name);
}

std::string frame_id(std::size_t k) { return std::to_string(1000000 + k).substr(1); }

/// Writes the per-frame files and keeps the .pvd entries.
class FrameFiles {
 public:
  FrameFiles(const io::OutputDir& out, const SwimOutputOptions& o) : out_(out), frames_(out.file("frames")), options_(o) {}

  void write(const jellyfish::SwimSimulation& sim, std::size_t index) {
    const std::string id = frame_id(index);
    if (options_.vtk) {
      const std::string field = "field_" + id + ".vti", tracers = "tracers_" + id + ".vtp", body = "body_" + id + ".vtp";
      write_via_temporary(frames_, field, [&](const auto& p) { io::write_flow_vti(p, sim.flow()); });
      write_via_temporary(frames_, tracers, [&](const auto& p) { io::write_points_vtp(p, sim.tracers().positions()); });
      const elastic::Body& b = sim.jellyfish().body();
      std::vector<std::array<int, 2>> lines;
      for (std::size_t s = 0; s < b.linear.size(); ++s) lines.push_back({b.linear.i[s], b.linear.j[s]});
      write_via_temporary(frames_, body, [&](const auto& p) { io::write_lines_vtp(p, b.points.position, lines); });
      entries_.push_back({sim.time_s(), "frames/" + field, 0});
      entries_.push_back({sim.time_s(), "frames/" + tracers, 1});
      entries_.push_back({sim.time_s(), "frames/" + body, 2});
      write_via_temporary(out_, "jellyfish.pvd", [&](const auto& p) { io::write_pvd(p, entries_); });
    }
    if (options_.pictures && index % static_cast<std::size_t>(options_.picture_every) == 0) {
      render::FieldPictureOptions po;
      po.quantity = options_.quantity;
      po.arrows = options_.quantity == render::FieldQuantity::speed;
      const render::FieldPicture picture = swim_picture(sim, options_.zoom_diameters);
      write_via_temporary(frames_, "slice_" + id + ".png", [&](const auto& p) { render::write_field_png(picture, po, p); });
    }
  }

 private:
  const io::OutputDir& out_;
  io::OutputDir frames_;
  SwimOutputOptions options_;
  std::vector<io::PvdEntry> entries_;
};

}  // namespace

jellyfish::SwimSettings read_swim_settings(const io::Config& c) {
  jellyfish::SwimSettings s;
  s.duration_s = c.number("duration", io::Range::positive());
  s.frame_interval_s = c.number("output.frame_interval", io::Range::positive());
  if (s.frame_interval_s > s.duration_s)
    throw InputError("field 'output.frame_interval' = " + io::format_double(s.frame_interval_s) +
                     " is out of range (0, duration = " + io::format_double(s.duration_s) + "]");

  jellyfish::TankSpec& t = s.tank;
  t.width_m = c.number("tank.width", io::Range::positive());
  t.height_m = c.number("tank.height", io::Range::positive());
  const auto cells = c.integers("tank.cells", 4, 4096);
  if (cells.size() != 2) throw InputError("field 'tank.cells' must have two entries [nx, ny], each in [4, 4096]");
  t.cells_x = static_cast<int>(cells[0]);
  t.cells_y = static_cast<int>(cells[1]);
  t.solver = c.choice("tank.solver", {"semi-lagrangian", "eulerian"});
  t.pressure_solver = c.choice("tank.pressure_solver", {"multigrid", "sor"});
  t.pressure_tolerance = c.number("tank.pressure_tolerance", io::Range{0.0, 1e-2, true, false});
  t.viscosity_m2_per_s = c.number("tank.viscosity", io::Range::non_negative());
  t.density_kg_per_m3 = c.number("tank.density", io::Range::positive());
  const auto sides = c.choices("tank.boundaries", {"no-slip", "free-slip", "outflow", "inflow", "periodic"});
  if (sides.size() != 4)
    throw InputError("field 'tank.boundaries' must list four sides [west, east, south, north]");
  const Vec2 inflow = c.vec2("tank.inflow_velocity");
  fluid::BoundaryCondition* b[4] = {&t.boundaries.west, &t.boundaries.east, &t.boundaries.south, &t.boundaries.north};
  for (int k = 0; k < 4; ++k) {
    b[k]->type = read_boundary(sides[static_cast<std::size_t>(k)]);
    b[k]->velocity_m_per_s = b[k]->type == fluid::BoundaryType::inflow ? inflow : Vec2{};
  }
  try {
    t.boundaries.validate();
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("field 'tank.boundaries': ") + e.what());
  }
  t.tracers_per_side = static_cast<int>(c.integer("tank.tracers_per_side", 0, 1000));

  jellyfish::JellyfishSpec& j = s.jellyfish;
  j.aperture_centre_m = c.vec2("jellyfish.position");
  if (!(j.aperture_centre_m.x > 0 && j.aperture_centre_m.x < t.width_m && j.aperture_centre_m.y > 0 &&
        j.aperture_centre_m.y < t.height_m))
    throw InputError("field 'jellyfish.position' = [" + io::format_double(j.aperture_centre_m.x) + ", " +
                     io::format_double(j.aperture_centre_m.y) + "] is outside the tank [0, " +
                     io::format_double(t.width_m) + "] x [0, " + io::format_double(t.height_m) + "]");
  j.tilt_rad = c.number("jellyfish.tilt_deg", io::Range::closed(-360, 360)) * kDegree;
  j.diameter_m = c.number("jellyfish.diameter", io::Range::positive());
  j.height_m = c.number("jellyfish.height", io::Range::positive());
  j.tentacle_length_m = c.number("jellyfish.tentacle_length", io::Range::non_negative());
  j.thickness_m = c.number("jellyfish.thickness", io::Range::positive());
  j.model = c.choice("jellyfish.model", {"angular", "mesh"}) == "mesh" ? jellyfish::UmbrellaModel::mesh
                                                                       : jellyfish::UmbrellaModel::angular;
  const double spacing = c.number("jellyfish.spacing", io::Range::non_negative());
  j.max_spacing_m = spacing > 0 ? spacing : jellyfish::peskin_spacing(t);
  j.min_segments_per_side = static_cast<int>(c.integer("jellyfish.min_segments_per_side", 2, 1000));
  j.bell_modulus_pa = c.number("jellyfish.bell_modulus", io::Range::positive());
  j.muscle_modulus_pa = c.number("jellyfish.muscle_modulus", io::Range::non_negative());
  j.bending_factor = c.number("jellyfish.bending_factor", io::Range::non_negative());
  j.tentacle_volume_fraction = c.number("jellyfish.tentacle_volume_fraction", io::Range::positive());
  j.tentacle_bending_factor = c.number("jellyfish.tentacle_bending_factor", io::Range::non_negative());
  j.frequency_hz = c.number("jellyfish.frequency", io::Range{0.0, 100.0, true, false});
  j.gamma = c.number("jellyfish.gamma", io::Range{0.0, 1.0, true, false});
  j.profile.shape = *jellyfish::contraction_shape_from_string(
      c.choice("jellyfish.contraction", jellyfish::contraction_shape_names()));
  j.profile.contract_fraction = c.number("jellyfish.contract_fraction", io::Range{0.0, 1.0, true, true});
  j.aperture_expansion_exponent = c.number("jellyfish.aperture_expansion_exponent", io::Range::closed(1.0, 10.0));
  j.neural_delay_s = c.number("jellyfish.neural_delay", io::Range::non_negative());
  j.closed_loop = c.boolean("jellyfish.controller");
  j.controller_alpha = c.number("jellyfish.controller_alpha", io::Range::positive());
  j.profile.trochoid_skew = c.number("jellyfish.trochoid_skew", io::Range{0.0, 1.0, false, true});
  j.phase_cycles = c.number("jellyfish.phase", io::Range::closed(-1000, 1000));

  coupling::CouplingSettings& k = s.coupling;
  k.scheme = *coupling::scheme_from_string(c.choice("coupling.scheme", {"semi-implicit", "explicit"}));
  k.kernel = *coupling::kernel_from_string(c.choice("coupling.kernel", {"bilinear", "peskin4"}));
  k.safety_factor = c.number("coupling.safety_factor", io::Range{0.0, 1.0, true, false});
  k.max_time_step_s = c.number("coupling.max_dt", io::Range::positive());
  k.min_time_step_s = c.number("coupling.min_dt", io::Range::positive());
  k.krylov_tolerance = c.number("coupling.krylov_tolerance", io::Range{0.0, 1.0, true, true});
  k.krylov_max_iterations = static_cast<int>(c.integer("coupling.krylov_max_iterations", 1, 100000));

  s.limits.max_speed_m_per_s = c.number("stability.max_speed", io::Range::positive());
  s.limits.max_strain = c.number("stability.max_strain", io::Range::positive());
  s.limits.max_bend_rad = c.number("stability.max_bend_deg", io::Range{0.0, 180.0, true, false}) * kDegree;
  try {
    jellyfish::validate(j);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  return s;
}

SwimOutputOptions read_output_options(const io::Config& c) {
  SwimOutputOptions o;
  o.pictures = c.boolean("output.pictures");
  o.picture_every = static_cast<int>(c.integer("output.picture_every", 1, 1000000));
  o.quantity = c.choice("output.picture_quantity", {"vorticity", "speed"}) == "speed" ? render::FieldQuantity::speed
                                                                                      : render::FieldQuantity::vorticity;
  o.zoom_diameters = c.number("output.picture_zoom", io::Range::non_negative());
  o.vtk = c.boolean("output.vtk");
  return o;
}

render::FieldPicture swim_picture(const jellyfish::SwimSimulation& sim, double zoom_diameters) {
  render::FieldPicture p;
  p.state = &sim.flow();
  p.tracers_m = sim.tracers().positions();
  const elastic::Body& b = sim.jellyfish().body();
  const auto& muscles = sim.jellyfish().layout().muscle_springs;
  for (std::size_t s = 0; s < b.linear.size(); ++s) {
    const std::array<Vec2, 2> seg{b.points.position[static_cast<std::size_t>(b.linear.i[s])],
                                  b.points.position[static_cast<std::size_t>(b.linear.j[s])]};
    const bool muscle = std::find(muscles.begin(), muscles.end(), static_cast<int>(s)) != muscles.end();
    (muscle ? p.thin_segments_m : p.segments_m).push_back(seg);
  }
  char caption[64];
  std::snprintf(caption, sizeof caption, "t = %.2f s", sim.time_s());
  p.caption = caption;
  if (zoom_diameters > 0) {
    const jellyfish::BellShape bell = jellyfish::measure_bell(sim.jellyfish().umbrella_points());
    const double half = 0.5 * zoom_diameters * sim.settings().jellyfish.diameter_m;
    p.view_m = std::array<Vec2, 2>{bell.centroid - Vec2{half, half}, bell.centroid + Vec2{half, half}};
  }
  return p;
}

SwimRecording run_swim(const jellyfish::SwimSettings& settings, const SwimOutputOptions& options,
                       const io::OutputDir* out, const sim::ProgressCallback& progress) {
  SwimRecording rec;
  jellyfish::SwimSimulation sim(settings);
  std::unique_ptr<FrameFiles> files;
  if (out && (options.vtk || options.pictures)) files = std::make_unique<FrameFiles>(*out, options);
  rec.stats = sim.run(
      [&](const jellyfish::SwimSimulation& s) -> std::string {
        if (files) files->write(s, rec.frames.size());
        rec.frames.push_back(s.jellyfish().slice_frame(s.time_s()));
        return {};
      },
      progress);
  rec.metrics = jellyfish::compute_metrics(
      rec.frames, {settings.tank.density_kg_per_m3, std::max(settings.tank.viscosity_m2_per_s, 1e-9)});
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

void write_slices_csv(const io::OutputDir& out, const std::vector<jellyfish::SliceFrame>& frames) {
  io::CsvWriter csv({"frame", "t", "part", "index", "x", "y"});
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto& fr = frames[f];
    for (std::size_t i = 0; i < fr.umbrella.size(); ++i)
      csv.row({"umbrella"}, {static_cast<double>(f), fr.time_s, static_cast<double>(i), fr.umbrella[i].x, fr.umbrella[i].y});
    for (std::size_t k = 0; k < fr.tentacles.size(); ++k)
      for (std::size_t i = 0; i < fr.tentacles[k].size(); ++i)
        csv.row({"tentacle_" + std::to_string(k)},
                {static_cast<double>(f), fr.time_s, static_cast<double>(i), fr.tentacles[k][i].x, fr.tentacles[k][i].y});
  }
  out.write_text("slices.csv", csv.text());
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
  auto chart = [&](const std::string& name, const std::string& chart_title, const std::string& y_label,
                   std::vector<render::Series> list) {
    render::ChartSpec c;
    c.title = chart_title;
    c.x_label = "t (s)";
    c.y_label = y_label;
    c.series = std::move(list);
    c.legend = render::LegendCorner::TopLeft;
    write_via_temporary(out, name, [&](const auto& p) { render::write_chart_png(c, p); });
  };
  chart("position.png", title + ": position (Fig. 8.15)", "m",
        {series("bell centroid", [](const auto& r) { return r.position; }),
         series("Daniel's model (eq. 6.5)", [](const auto& r) { return r.daniel_position; })});
  chart("velocity.png", title + ": velocity (Fig. 8.16)", "m/s",
        {series("bell centroid", [](const auto& r) { return r.velocity; }),
         series("Daniel's model (eq. 6.5)", [](const auto& r) { return r.daniel_velocity; })});
  chart("acceleration.png", title + ": acceleration (Fig. 8.17)", "m/s^2",
        {series("bell centroid", [](const auto& r) { return r.acceleration; })});
  chart("morphology.png", title + ": morphology (Fig. 8.18)", "ratio to rest",
        {series("volume V/V0", [](const auto& r) { return r.volume_ratio; }),
         series("aperture A/A0", [](const auto& r) { return r.aperture_ratio; })});
}

nlohmann::ordered_json swim_figures(const jellyfish::SwimSettings& settings, const SwimRecording& rec) {
  nlohmann::ordered_json j;
  j["units"] = {{"length", "m"}, {"time", "s"}, {"velocity", "m/s"}, {"acceleration", "m/s^2"}, {"volume", "m^3"},
                {"area", "m^2"}, {"thrust", "N"}, {"modulus", "Pa"}};
  j["bell_height"] = settings.jellyfish.height_m;
  j["bell_diameter"] = settings.jellyfish.diameter_m;
  j["frequency"] = settings.jellyfish.frequency_hz;
  j["cycles"] = jellyfish::cycles(rec.stats.simulated_seconds, settings.jellyfish.frequency_hz);
  const double distance = rec.metrics.empty() ? 0.0 : rec.metrics.back().position;
  const double lateral = rec.metrics.empty() ? 0.0 : rec.metrics.back().lateral;
  j["distance_travelled"] = distance;
  j["distance_in_bell_heights"] = distance / settings.jellyfish.height_m;
  j["lateral_drift"] = lateral;
  j["mean_speed"] = rec.stats.simulated_seconds > 0 ? distance / rec.stats.simulated_seconds : 0.0;
  std::vector<double> volume;
  for (const auto& r : rec.metrics) volume.push_back(r.volume);
  j["volume_frequency"] = jellyfish::dominant_frequency(volume, settings.frame_interval_s);
  double vmin = INFINITY, amin = INFINITY;
  for (const auto& r : rec.metrics) {
    vmin = std::min(vmin, r.volume_ratio);
    amin = std::min(amin, r.aperture_ratio);
  }
  j["min_volume_ratio"] = rec.metrics.empty() ? 0.0 : vmin;
  j["min_aperture_ratio"] = rec.metrics.empty() ? 0.0 : amin;
  j["daniel_distance"] = rec.metrics.empty() ? 0.0 : rec.metrics.back().daniel_position;
  j["simulated_seconds"] = rec.stats.simulated_seconds;
  j["wall_seconds"] = rec.stats.wall_seconds;
  j["realtime_factor"] = rec.stats.wall_seconds > 0 ? rec.stats.simulated_seconds / rec.stats.wall_seconds : 0.0;
  j["steps"] = rec.stats.steps;
  j["smallest_step"] = rec.stats.smallest_step_s;
  j["largest_step"] = rec.stats.largest_step_s;
  j["krylov_iterations"] = rec.stats.krylov_iterations;
  j["frames"] = rec.frames.size();
  j["markers"] = rec.frames.empty() ? 0 : rec.frames.front().umbrella.size();
  j["coupling"] = std::string(coupling::to_string(settings.coupling.scheme));
  j["fluid_solver"] = settings.tank.solver;
  return j;
}

}  // namespace jellysim::experiments
