// Particle fluids and collisions, thesis §8.1.1-8.1.2: `bar-hits-wall` (Figure 8.2),
// `bar-hits-particle` (Figure 8.3), `sph-stream` (Figure 8.4), `mosquito-larva` (Figure 8.5) and
// `integrator-cost` (Figure 8.6).
#include "sph_common.hpp"
#include "jellysim/core/errors.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

namespace jellysim::experiments {
namespace {

using namespace sph_common;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// The Figure 8.1 bar as a scene body with its outline.
sph::Scene bar_scene(const config::Config& c) {
  sph::Scene s;
  try {
    s.body = elastic::make_bar(read_bar(c));
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  s.outline = sph::strip_outline(read_bar(c).segments);
  read_collision(c, s);
  return s;
}

// ---- bar-hits-wall (Figure 8.2) ----------------------------------------------------------------

std::function<Outcome(const io::OutputDir&)> prepare_bar_hits_wall(const Context& ctx) {
  auto scene = std::make_shared<sph::Scene>(bar_scene(ctx.config));
  const double gap = scene::read_wall_gap(ctx.config);
  double lowest_face = 0.0;
  for (Vec2 p : scene->body.points.position) lowest_face = std::min(lowest_face, p.y);
  const double floor = lowest_face - gap;
  scene->walls = {sph::Wall{{0.0, floor}, {0.0, 1.0}, false}};
  const sph::RunSettings rs = scene::read_particle_run_settings(ctx.config);
  const scene::StripOutput o = scene::read_strip_output(ctx.config);  // strip_window around the first contact
  return [scene, rs, o, floor, ctx](const io::OutputDir& out) {
    const auto start = Clock::now();
    const double cpu0 = cpu_seconds();
    std::vector<Frame> frames;
    double lowest = std::numeric_limits<double>::infinity(), contact = -1.0;
    const sph::RunResult r = sph::run(*scene, rs, [&](double t, const sph::Scene& s, const sph::CoupledSystem&) {
      frames.push_back(snapshot(t, s));
      for (Vec2 p : s.body.points.position) {
        lowest = std::min(lowest, p.y);
        if (contact < 0.0 && p.y < floor + 1e-3) contact = t;
      }
      return std::string();
    }, ctx.progress);
    const double wall = seconds_since(start), cpu = cpu_seconds() - cpu0;  // the run only, not the outputs
    write_frames_csv(out, frames);
    const double centre = contact >= 0.0 ? contact : rs.time.duration / 2.0;
    DrawOptions d;
    d.decor = {{Vec2{-0.55, floor}, Vec2{0.55, floor}}};
    write_strip(out, "bar_hits_wall.png", "bar hits a static wall", *scene, frames, centre - 0.5 * o.window_s,
                centre + 0.5 * o.window_s, o.frames, d);
    nlohmann::ordered_json f = run_figures(r, wall, cpu);
    f["floor_y"] = floor;
    f["lowest_point_y"] = lowest;
    f["first_contact_time"] = contact;
    write_summary(out, "bar-hits-wall", ctx.config, f, r.failure);
    return Outcome{r.failure};
  };
}

// ---- bar-hits-particle (Figure 8.3) ------------------------------------------------------------

std::function<Outcome(const io::OutputDir&)> prepare_bar_hits_particle(const Context& ctx) {
  auto scene = std::make_shared<sph::Scene>(bar_scene(ctx.config));
  const scene::PointParticle particle = scene::read_point_particle(ctx.config);
  const Vec2 v0 = particle.velocity;
  scene->position = {particle.position};
  scene->velocity = {v0};
  scene->mass = {particle.mass_kg};
  scene->particle_gravity = particle.gravity;
  const sph::RunSettings rs = scene::read_particle_run_settings(ctx.config);
  const scene::StripOutput o = scene::read_strip_output(ctx.config);  // strip_window around the first contact
  return [scene, rs, o, v0, ctx](const io::OutputDir& out) {
    const auto start = Clock::now();
    const double cpu0 = cpu_seconds();
    std::vector<Frame> frames;
    double contact = -1.0;
    Vec2 before{}, after{};
    const Vec2 g = scene->particle_gravity;
    const sph::RunResult r = sph::run(*scene, rs, [&](double t, const sph::Scene& s, const sph::CoupledSystem&) {
      frames.push_back(snapshot(t, s));
      // Until the first collision the particle flies ballistically: v = v0 + g t.
      const Vec2 ballistic = v0 + g * t;
      if (contact < 0.0 && norm(s.velocity[0] - ballistic) > 1e-9 * (1.0 + norm(ballistic))) {
        contact = t;
        after = s.velocity[0];
        before = ballistic;
      }
      return std::string();
    }, ctx.progress);
    const double wall = seconds_since(start), cpu = cpu_seconds() - cpu0;  // the run only, not the outputs
    write_frames_csv(out, frames);
    const double centre = contact >= 0.0 ? contact : rs.time.duration / 2.0;
    write_strip(out, "bar_hits_particle.png", "bar hits a point mass", *scene, frames, centre - 0.5 * o.window_s,
                centre + 0.5 * o.window_s, o.frames, {});
    nlohmann::ordered_json f = run_figures(r, wall, cpu);
    f["first_collision_time"] = contact;
    f["particle_velocity_before"] = {before.x, before.y};
    f["particle_velocity_after"] = {after.x, after.y};
    write_summary(out, "bar-hits-particle", ctx.config, f, r.failure);
    return Outcome{r.failure};
  };
}

}  // namespace

Experiment bar_hits_wall_experiment() {
  return make_bar_experiment("bar-hits-wall",
                         "Thesis Figure 8.2: the Figure 8.1 bar swings onto a static wall 0.45 below it",
                         "experiments/bar-hits-wall.toml", prepare_bar_hits_wall);
}

Experiment bar_hits_particle_experiment() {
  return make_bar_experiment("bar-hits-particle",
                         "Thesis Figure 8.3: the Figure 8.1 bar collides with a moving point mass",
                         "experiments/bar-hits-particle.toml", prepare_bar_hits_particle);
}

}  // namespace jellysim::experiments
