#include "sph_common.hpp"

#include "jellysim/core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace jellysim::experiments::sph_common {

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
  out.write_text(name, render::drawing_strip_png(panels, std::min<int>(static_cast<int>(shown), 4), title));
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
  e.shorthands = {"threads"};  // run.threads
  return e;
}

Experiment make_bar_experiment(std::string name, std::string description, std::string definition_path,
                               std::function<std::function<Outcome(const io::OutputDir&)>(const Context&)> prepare) {
  Experiment e = make_experiment(std::move(name), std::move(description), std::move(definition_path), std::move(prepare));
  e.base_path = kBarBasePath;
  return e;
}

}  // namespace jellysim::experiments::sph_common
