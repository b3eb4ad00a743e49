#include "sph_common.hpp"

#include "jellysim/core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace jellysim::experiments::sph_common {

namespace {
const std::vector<std::string> kErrorControls = {"embedded", "step-doubling"};
const std::vector<std::string> kStates = {"crystalline", "thermalised"};
}  // namespace

void check_time(const sph::RunSettings& s) {
  if (s.time.dt > s.time.duration) {
    throw InputError("field 'time.dt' = " + io::format_double(s.time.dt) + " is out of range (0, duration = " +
                     io::format_double(s.time.duration) + "]");
  }
}

sph::RunSettings read_run_settings(const io::Config& c) {
  sph::RunSettings s;
  // Every integrator; backward Euler runs Jacobian-free (ode::JacobianFreeBackwardEuler).
  s.time.integrator = c.choice("time.integrator", ode::integrator_names());
  s.time.dt = c.number("time.dt", io::Range::positive());
  s.time.adaptive = c.boolean("time.adaptive");
  s.time.tolerances.atol = c.number("time.atol", io::Range::positive());
  s.time.tolerances.rtol = c.number("time.rtol", io::Range::non_negative());
  s.time.tolerances.dt_min = 1e-10;
  s.time.duration = c.number("duration", io::Range::positive());
  s.time.frame_interval = c.number("time.frame_interval", io::Range::positive());
  s.error_control = c.choice("time.error_control", kErrorControls);
  s.thin_boundary_limit = c.boolean("time.thin_boundary_limit");
  s.max_speed = c.number("output.max_speed", io::Range::positive());
  check_time(s);
  return s;
}

elastic::BarSpec read_bar(const io::Config& c) {
  elastic::BarSpec b;
  b.length = c.number("bar.length", io::Range::positive());
  b.width = c.number("bar.width", io::Range::positive());
  b.segments = static_cast<int>(c.integer("bar.segments", 1, 1000));
  b.point_mass = c.number("bar.point_mass", io::Range::positive());
  b.stiffness = c.number("bar.stiffness", io::Range::positive());
  b.pivot = c.vec2("bar.pivot");
  b.gravity = c.vec2("bar.gravity");
  return b;
}

void read_collision(const io::Config& c, sph::Scene& scene) {
  scene.collision.separation_m = c.number("collision.separation", io::Range{0.0, 1.0, true, false});
  scene.collision.trap_radius_m = c.number("collision.trap_radius", io::Range::closed(0.0, 1.0));
  scene.threads = static_cast<int>(c.integer("run.threads", 0, 64));  // 0: one per core
}

sph::SphParameters read_fluid_parameters(const io::Config& c) {
  sph::SphParameters p;
  p.smoothing_radius_m = c.number("fluid.smoothing_radius", io::Range::positive());
  p.rest_density = c.number("fluid.rest_density", io::Range::positive());
  p.gas_constant = c.number("fluid.gas_constant", io::Range::non_negative());
  p.viscosity = c.number("fluid.viscosity", io::Range::non_negative());
  return p;
}

sph::LarvaSpec read_larva(const io::Config& c) {
  sph::LarvaSpec s;
  s.centre = c.vec2("larva.centre");
  s.length_m = c.number("larva.length", io::Range::positive());
  s.height_m = c.number("larva.height", io::Range::positive());
  s.segments = static_cast<int>(c.integer("larva.segments", 2, 1000));
  s.point_mass_kg = c.number("larva.point_mass", io::Range::positive());
  s.stiffness = c.number("larva.stiffness", io::Range::positive());
  s.muscle_stiffness = c.number("larva.muscle_stiffness", io::Range::non_negative());
  s.contraction = c.number("larva.contraction", io::Range::closed(0.0, 0.9));
  s.frequency_hz = c.number("larva.frequency", io::Range::non_negative());
  s.wave_cells = c.number("larva.wave_cells", io::Range::closed(-10.0, 10.0));
  return s;
}

namespace {

/// True when x lies within `margin` of the larva's rest rectangle.
bool near_larva(const sph::LarvaSpec& l, Vec2 x, double margin) {
  return std::abs(x.x - l.centre.x) < 0.5 * l.length_m + margin && std::abs(x.y - l.centre.y) < 0.5 * l.height_m + margin;
}

}  // namespace

LarvaScene build_larva_scene(const io::Config& c, double gas_constant) {
  LarvaScene r;
  sph::Scene& s = r.scene;
  const Vec2 lo = c.vec2("box.min"), hi = c.vec2("box.max");
  if (!(hi.x > lo.x && hi.y > lo.y)) throw InputError("field 'box.max' must exceed 'box.min' in both coordinates");
  s.sph = read_fluid_parameters(c);
  s.sph.gas_constant = gas_constant;
  s.walls = sph::box_walls(lo, hi);
  const auto count = static_cast<std::size_t>(c.integer("fluid.particles", 1, 200000));
  const double fixed_mass = c.number("fluid.mass", io::Range::non_negative());
  const double tolerance = c.number("fluid.mass_tolerance", io::Range{0.0, 0.5, true, true});
  const std::string state = c.choice("fluid.state", kStates);
  const double noise = c.number("fluid.noise", io::Range::non_negative());
  const double velocity_ratio = c.number("fluid.velocity_ratio", io::Range::non_negative());
  const auto seed = static_cast<std::uint64_t>(c.integer("fluid.seed", 0, 1LL << 62));
  s.particle_gravity = c.vec2("fluid.gravity");
  const sph::LarvaSpec larva_spec = read_larva(c);
  read_collision(c, s);
  sph::Larva larva;
  try {
    larva = sph::make_larva(larva_spec);
    const double margin = 0.25 * s.sph.smoothing_radius_m;
    s.position = sph::triangular_lattice_with_count(lo, hi, count, [&](Vec2 x) { return near_larva(larva_spec, x, margin); });
    const double area = (hi.x - lo.x) * (hi.y - lo.y) - larva_spec.length_m * larva_spec.height_m;
    r.mass = sph::find_particle_mass(s.position, area, s.sph, s.walls, tolerance);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  if (fixed_mass > 0.0) r.mass.mass_kg = fixed_mass;
  s.velocity.assign(s.position.size(), Vec2{});
  if (state == "thermalised") sph::thermalise(s.position, s.velocity, noise, velocity_ratio, seed);
  s.mass.assign(s.position.size(), r.mass.mass_kg);
  s.fluid_count = s.position.size();
  larva.body.gravity = c.vec2("larva.gravity");
  s.body = larva.body;
  s.outline = larva.outline;
  s.muscles = larva.muscles;
  return r;
}

Frame snapshot(double t, const sph::Scene& scene) {
  return {t, scene.position, scene.velocity, scene.body.points.position, scene.body.points.velocity};
}

void write_frames_csv(const io::OutputDir& out, const std::vector<Frame>& frames) {
  io::CsvWriter csv({"frame", "t", "object", "index", "x", "y", "vx", "vy"});
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const Frame& fr = frames[f];
    for (std::size_t i = 0; i < fr.particles.size(); ++i) {
      csv.row({static_cast<double>(f), fr.t, 0.0, static_cast<double>(i), fr.particles[i].x, fr.particles[i].y,
               fr.particle_velocities[i].x, fr.particle_velocities[i].y});
    }
    for (std::size_t i = 0; i < fr.body.size(); ++i) {
      csv.row({static_cast<double>(f), fr.t, 1.0, static_cast<double>(i), fr.body[i].x, fr.body[i].y,
               fr.body_velocities[i].x, fr.body_velocities[i].y});
    }
  }
  out.write_text("frames.csv", csv.text());
}

namespace {

render::Drawing draw(const sph::Scene& scene, const Frame& f, const DrawOptions& o) {
  render::Drawing d;
  d.caption = "t = " + io::format_double(std::round(f.t * 100.0) / 100.0);
  d.segments = o.decor;
  const elastic::Body& b = scene.body;
  for (std::size_t k = 0; k < b.linear.size(); ++k) {
    d.segments.push_back({f.body[static_cast<std::size_t>(b.linear.i[k])], f.body[static_cast<std::size_t>(b.linear.j[k])]});
  }
  for (std::size_t i = 0; i < f.body.size(); ++i) {
    if (b.points.kind[i] != elastic::PointKind::Free) d.marked_points.push_back(f.body[i]);
    if (o.velocity_scale_s > 0.0) d.segments.push_back({f.body[i], f.body[i] + f.body_velocities[i] * o.velocity_scale_s});
  }
  d.points = f.particles;
  return d;
}

}  // namespace

void write_strip(const io::OutputDir& out, const std::string& name, const std::string& title,
                 const sph::Scene& scene, const std::vector<Frame>& frames, double t0, double t1, int count,
                 const DrawOptions& options) {
  std::vector<std::size_t> chosen;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].t >= t0 - 1e-9 && frames[f].t <= t1 + 1e-9) chosen.push_back(f);
  }
  if (chosen.empty()) return;
  std::vector<render::Drawing> panels;
  const std::size_t shown = std::min<std::size_t>(chosen.size(), static_cast<std::size_t>(count));
  for (std::size_t k = 0; k < shown; ++k) {
    const std::size_t pick = shown == 1 ? 0 : k * (chosen.size() - 1) / (shown - 1);
    panels.push_back(draw(scene, frames[chosen[pick]], options));
  }
  const auto tmp = out.temporary_for(name);
  render::write_drawing_strip_png(panels, std::min<int>(static_cast<int>(shown), 4), title, tmp);
  out.commit(tmp, name);
}

std::vector<std::array<Vec2, 2>> box_segments(Vec2 lo, Vec2 hi) {
  return {{lo, Vec2{hi.x, lo.y}}, {Vec2{hi.x, lo.y}, hi}, {hi, Vec2{lo.x, hi.y}}, {Vec2{lo.x, hi.y}, lo}};
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

nlohmann::ordered_json run_figures(const sph::RunResult& r, double wall_seconds, double cpu_seconds) {
  nlohmann::ordered_json j;
  j["simulated_seconds"] = r.statistics.simulated_seconds;
  j["wall_seconds"] = wall_seconds;
  j["cpu_seconds"] = cpu_seconds;
  j["steps"] = r.statistics.steps;
  j["rejected_steps"] = r.statistics.rejected_steps;
  j["function_evaluations"] = r.statistics.function_evaluations;
  j["edge_collisions"] = r.collisions.edge_collisions;
  j["trapped_particles"] = r.collisions.trapped;
  j["wall_collisions"] = r.collisions.wall_collisions;
  if (std::isfinite(r.boundary_width_m)) j["boundary_width"] = r.boundary_width_m;
  j["threads"] = r.threads;
  j["parallel_evaluations"] = r.parallel_evaluations;  // of function_evaluations (SPH ones), see docs/sph.md
  j["neighbour_list_rebuilds"] = r.list_rebuilds;  // SPH evaluations that searched the grid, see docs/sph.md
  return j;
}

Experiment make_experiment(std::string name, std::string description, std::string definition_path,
                           std::function<std::function<Outcome(const io::OutputDir&)>(const Context&)> prepare) {
  Experiment e;
  e.name = std::move(name);
  e.description = std::move(description);
  e.definition_path = std::move(definition_path);
  e.prepare = std::move(prepare);
  return e;
}

}  // namespace jellysim::experiments::sph_common
