#include "jellysim/scene/particle_scenes.hpp"

#include <cmath>
#include <stdexcept>

#include "jellysim/core/errors.hpp"

namespace jellysim::scene {
namespace {

using config::Range;

/// A rule: the default is each scene's (value left empty).
Parameter rule(std::string key, Type type, std::string unit, Range range, std::string description,
               std::vector<std::string> choices = {}) {
  return {std::move(key), type, "", std::move(unit), range, std::move(choices), 0, std::move(description)};
}

/// The time loop, the outputs, the elastic bar and collisions.
std::vector<Parameter> time_output_and_bar_rules() {
  const Range positive = Range::positive(), non_negative = Range::non_negative();
  return {
      rule("duration", Type::number, "s", positive, "simulated time"),
      rule("time.integrator", Type::choice, "", {}, "time integrator (docs/integrators.md)", ode::integrator_names()),
      rule("time.dt", Type::number, "s", positive, "step; the first step when adaptive; at most the duration"),
      rule("time.adaptive", Type::boolean, "", {}, "step-size control by the error estimate"),
      rule("time.atol", Type::number, "", positive, "absolute error tolerance of adaptive steps"),
      rule("time.rtol", Type::number, "", non_negative, "relative error tolerance of adaptive steps"),
      rule("time.error_control", Type::choice, "", {}, "embedded (the method's pair, else step doubling) or step-doubling",
           {"embedded", "step-doubling"}),
      rule("time.thin_boundary_limit", Type::boolean, "", {}, "cap the step by eq. 5.31 (particles against a thin body)"),
      rule("time.frame_interval", Type::number, "s", positive, "time between recorded frames"),
      rule("output.max_speed", Type::number, "m/s", positive, "a point or particle faster than this stops the run"),
      rule("output.strip_frames", Type::integer, "", Range::closed(1, 64), "panels in the frame strip (NAME.png)"),
      rule("output.strip_window", Type::number, "s", positive, "bar collisions: time around the first contact shown in the strip"),
      rule("output.strip_start", Type::number, "s", non_negative, "mosquito larva: first frame shown in the strip"),
      rule("output.velocity_scale", Type::number, "s", non_negative,
           "mosquito larva: length of the drawn body-point velocity vectors per m/s"),
      rule("bar.length", Type::number, "m", positive, "bar length (Figure 8.1: 0.45)"),
      rule("bar.width", Type::number, "m", positive, "bar width"),
      rule("bar.segments", Type::integer, "", Range::closed(1, 10000), "cells along the bar"),
      rule("bar.point_mass", Type::number, "kg", positive, "mass of every point"),
      rule("bar.stiffness", Type::number, "N/m", positive, "κ_l of every linear spring"),
      rule("bar.modulus", Type::number, "Pa", non_negative, "if > 0: κ_l from eq. 7.1 with cross_section instead of stiffness"),
      rule("bar.cross_section", Type::number, "m²", non_negative, "cross-section for bar.modulus"),
      rule("bar.angular_stiffness", Type::number, "N·m", non_negative, "κ_θ of the springs along each row; 0: none"),
      rule("bar.angle_deg", Type::number, "°", Range::closed(-360.0, 360.0), "bar direction; 0: horizontal along +x"),
      rule("bar.pivot", Type::vec2, "m", {}, "the pinned top-left corner"),
      rule("bar.gravity", Type::vec2, "m/s²", {}, "gravity on the bar's points"),
      rule("bar.drag", Type::number, "kg/s", non_negative, "κ_d of eq. 2.17"),
      rule("collision.separation", Type::number, "m", Range{0.0, 1.0, true, false},
           "distance outside an edge at which a pushed-out point is placed"),
      rule("collision.trap_radius", Type::number, "m", Range::closed(0.0, 1.0),
           "a second boundary this close makes a colliding particle trapped (0: off)"),
      rule("run.threads", Type::integer, "", Range::closed(0, 64), "threads of the SPH loops; 0: one per core"),
  };
}

/// The SPH fluid box (thesis ch. 5).
std::vector<Parameter> fluid_rules() {
  const Range positive = Range::positive(), non_negative = Range::non_negative();
  return {
      rule("box.min", Type::vec2, "m", {}, "lower-left corner of the fluid box"),
      rule("box.max", Type::vec2, "m", {}, "upper-right corner of the fluid box (above and right of box.min)"),
      rule("fluid.smoothing_radius", Type::number, "m", positive, "SPH smoothing radius h"),
      rule("fluid.rest_density", Type::number, "kg/m²", positive, "ρ_0 (2D)"),
      rule("fluid.gas_constant", Type::number, "m²/s²", non_negative, "k of the equation of state"),
      rule("fluid.viscosity", Type::number, "", non_negative, "μ of the viscosity force"),
      rule("fluid.particles", Type::integer, "", Range::closed(1, 200000), "particle count"),
      rule("fluid.mass", Type::number, "kg", non_negative, "particle mass; 0: found so the fluid is at its rest density"),
      rule("fluid.mass_tolerance", Type::number, "", Range{0.0, 0.5, true, true}, "relative tolerance of that search"),
      rule("fluid.state", Type::choice, "", {}, "initial state", {"crystalline", "thermalised"}),
      rule("fluid.noise", Type::number, "", non_negative, "thermalised: position noise, in particle spacings"),
      rule("fluid.velocity_ratio", Type::number, "", non_negative, "thermalised: velocity noise"),
      rule("fluid.seed", Type::integer, "", Range::closed(0, 4611686018427387904.0), "thermalised: random seed"),
      rule("fluid.gravity", Type::vec2, "m/s²", {}, "gravity on the particles"),
  };
}

/// The mosquito larva, the walls, particles and emitter, and the studies.
std::vector<Parameter> larva_and_probe_rules() {
  const Range positive = Range::positive(), non_negative = Range::non_negative();
  return {
      rule("larva.centre", Type::vec2, "m", {}, "centre of the larva at rest"),
      rule("larva.length", Type::number, "m", positive, "larva length"),
      rule("larva.height", Type::number, "m", positive, "larva height"),
      rule("larva.segments", Type::integer, "", Range::closed(2, 1000), "segments along the larva"),
      rule("larva.point_mass", Type::number, "kg", positive, "mass of every point"),
      rule("larva.stiffness", Type::number, "N/m", positive, "κ_l of the body springs"),
      rule("larva.muscle_stiffness", Type::number, "N/m", non_negative, "κ_l of the muscles"),
      rule("larva.contraction", Type::number, "", Range::closed(0.0, 0.9), "muscle contraction (fraction of the rest length)"),
      rule("larva.frequency", Type::number, "Hz", non_negative, "wriggles per second"),
      rule("larva.wave_cells", Type::number, "", Range::closed(-10.0, 10.0), "phase shift along the body, in segments"),
      rule("larva.gravity", Type::vec2, "m/s²", {}, "gravity on the larva's points"),
      rule("wall.gap", Type::number, "m", positive, "bar-hits-wall: distance of the static boundary below the bar's lower face"),
      rule("particle.position", Type::vec2, "m", {}, "bar-hits-particle: the point mass's start, relative to bar.pivot"),
      rule("particle.velocity", Type::vec2, "m/s", {}, "bar-hits-particle: the point mass's initial velocity"),
      rule("particle.mass", Type::number, "kg", positive, "bar-hits-particle: mass of the point"),
      rule("particle.gravity", Type::vec2, "m/s²", {}, "bar-hits-particle: gravity on the point"),
      rule("emitter.interval", Type::number, "s", positive, "sph-stream: time between released particles"),
      rule("emitter.offset", Type::vec2, "m", {}, "sph-stream: the emitter, from the top-left corner of the box (inside it)"),
      rule("emitter.velocity", Type::vec2, "m/s", {}, "sph-stream: velocity of a released particle"),
      rule("emitter.mass", Type::number, "kg", positive, "sph-stream: mass of a released particle"),
      rule("emitter.max_count", Type::integer, "", Range::closed(0, 100000), "sph-stream: particles released at most"),
      rule("study.gas_constants", Type::numbers, "m²/s²", positive, "integrator-cost: the gas constants κ_p run"),
      rule("study.integrators", Type::choices, "", {}, "integrator-cost: the integrators compared", ode::integrator_names()),
      rule("study.error_controls", Type::choices, "", {},
           "integrator-cost: the error controls compared (embedded only for methods with a pair)",
           {"embedded", "step-doubling"}),
  };
}

ParameterTable make_rules() {
  std::vector<Parameter> p;
  for (auto section : {time_output_and_bar_rules, fluid_rules, larva_and_probe_rules})
    for (Parameter& q : section()) p.push_back(std::move(q));
  return ParameterTable("particle", "", std::move(p));
}

}  // namespace

const ParameterTable& particle_scene_rules() {
  static const ParameterTable table = make_rules();
  return table;
}

sim::TimeSettings read_time_settings(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  sim::TimeSettings t;
  t.integrator = r.choice("time.integrator");
  t.dt = r.number("time.dt");
  t.adaptive = r.boolean("time.adaptive");
  t.tolerances.atol = r.number("time.atol");
  t.tolerances.rtol = r.number("time.rtol");
  t.duration = r.number("duration");
  t.frame_interval = r.number("time.frame_interval");
  if (t.dt > t.duration)
    throw InputError("field 'time.dt' = " + config::format_number(t.dt) + " is out of range (0, duration = " +
                     config::format_number(t.duration) + "]");
  return t;
}

sph::RunSettings read_particle_run_settings(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  sph::RunSettings s;
  s.time = read_time_settings(c);
  s.time.tolerances.dt_min = 1e-10;
  s.error_control = r.choice("time.error_control");
  s.thin_boundary_limit = r.boolean("time.thin_boundary_limit");
  s.max_speed = r.number("output.max_speed");
  return s;
}

elastic::BarSpec read_bar(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  elastic::BarSpec b;
  b.length = r.number("bar.length");
  b.width = r.number("bar.width");
  b.segments = static_cast<int>(r.integer("bar.segments"));
  b.point_mass = r.number("bar.point_mass");
  b.stiffness = r.number("bar.stiffness");
  b.pivot = r.vec2("bar.pivot");
  b.gravity = r.vec2("bar.gravity");
  return b;
}

void read_collision(const config::Config& c, sph::Scene& scene) {
  const Reader r(c, particle_scene_rules());
  scene.collision.separation_m = r.number("collision.separation");
  scene.collision.trap_radius_m = r.number("collision.trap_radius");
  scene.threads = static_cast<int>(r.integer("run.threads"));
}

sph::SphParameters read_fluid_parameters(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  sph::SphParameters p;
  p.smoothing_radius_m = r.number("fluid.smoothing_radius");
  p.rest_density = r.number("fluid.rest_density");
  p.gas_constant = r.number("fluid.gas_constant");
  p.viscosity = r.number("fluid.viscosity");
  return p;
}

sph::LarvaSpec read_larva(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  sph::LarvaSpec s;
  s.centre = r.vec2("larva.centre");
  s.length_m = r.number("larva.length");
  s.height_m = r.number("larva.height");
  s.segments = static_cast<int>(r.integer("larva.segments"));
  s.point_mass_kg = r.number("larva.point_mass");
  s.stiffness = r.number("larva.stiffness");
  s.muscle_stiffness = r.number("larva.muscle_stiffness");
  s.contraction = r.number("larva.contraction");
  s.frequency_hz = r.number("larva.frequency");
  s.wave_cells = r.number("larva.wave_cells");
  return s;
}

namespace {

/// True when x lies within `margin` of the larva's rest rectangle.
bool near_larva(const sph::LarvaSpec& l, Vec2 x, double margin) {
  return std::abs(x.x - l.centre.x) < 0.5 * l.length_m + margin && std::abs(x.y - l.centre.y) < 0.5 * l.height_m + margin;
}

}  // namespace

Box read_box(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  const Box b{r.vec2("box.min"), r.vec2("box.max")};
  if (!(b.max.x > b.min.x && b.max.y > b.min.y))
    throw InputError("field 'box.max' must exceed 'box.min' in both coordinates");
  return b;
}

StripOutput read_strip_output(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  StripOutput o;
  o.frames = static_cast<int>(r.integer("output.strip_frames"));
  if (c.has("output.strip_window")) o.window_s = r.number("output.strip_window");
  if (c.has("output.strip_start")) o.start_s = r.number("output.strip_start");
  if (c.has("output.velocity_scale")) o.velocity_scale_s = r.number("output.velocity_scale");
  return o;
}

double read_wall_gap(const config::Config& c) { return Reader(c, particle_scene_rules()).number("wall.gap"); }

PointParticle read_point_particle(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  PointParticle p;
  const Vec2 pivot = r.vec2("bar.pivot");
  p.position = pivot + r.vec2("particle.position");
  p.velocity = r.vec2("particle.velocity");
  p.mass_kg = r.number("particle.mass");
  p.gravity = r.vec2("particle.gravity");
  return p;
}

sph::Emitter read_emitter(const config::Config& c, const Box& box) {
  const Reader r(c, particle_scene_rules());
  sph::Emitter e;
  e.interval_s = r.number("emitter.interval");
  e.position = Vec2{box.min.x, box.max.y} + r.vec2("emitter.offset");  // from the top-left corner
  e.velocity = r.vec2("emitter.velocity");
  e.mass_kg = r.number("emitter.mass");
  e.max_count = static_cast<std::size_t>(r.integer("emitter.max_count"));
  const Vec2 x = e.position;
  if (!(x.x > box.min.x && x.x < box.max.x && x.y > box.min.y && x.y < box.max.y))
    throw InputError("field 'emitter.offset' puts the emitter outside the box");
  return e;
}

CostStudy read_cost_study(const config::Config& c) {
  const Reader r(c, particle_scene_rules());
  CostStudy s;
  s.gas_constants = r.numbers("study.gas_constants");
  s.integrators = r.choices("study.integrators");
  s.error_controls = r.choices("study.error_controls");
  return s;
}

LarvaScene build_larva_scene(const config::Config& c) {
  return build_larva_scene(c, Reader(c, particle_scene_rules()).number("fluid.gas_constant"));
}

LarvaScene build_larva_scene(const config::Config& c, double gas_constant) {
  LarvaScene r;
  sph::Scene& s = r.scene;
  const Reader rd(c, particle_scene_rules());
  const Box box = read_box(c);
  const Vec2 lo = box.min, hi = box.max;
  s.sph = read_fluid_parameters(c);
  s.sph.gas_constant = gas_constant;
  s.walls = sph::box_walls(lo, hi);
  const auto count = static_cast<std::size_t>(rd.integer("fluid.particles"));
  const double fixed_mass = rd.number("fluid.mass");
  const double tolerance = rd.number("fluid.mass_tolerance");
  const std::string state = rd.choice("fluid.state");
  const double noise = rd.number("fluid.noise");
  const double velocity_ratio = rd.number("fluid.velocity_ratio");
  const auto seed = static_cast<std::uint64_t>(rd.integer("fluid.seed"));
  s.particle_gravity = rd.vec2("fluid.gravity");
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
  larva.body.gravity = rd.vec2("larva.gravity");
  s.body = larva.body;
  s.outline = larva.outline;
  s.muscles = larva.muscles;
  return r;
}

}  // namespace jellysim::scene
