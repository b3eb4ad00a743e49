// Swinging elastic bar, thesis Figure 8.1 (§8.1.1): also the main job until the jellyfish exists.
#include "jellysim/elastic/bar.hpp"
#include "jellysim/elastic/elastic_system.hpp"
#include "jellysim/elastic/forces.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "sph_common.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

namespace jellysim::experiments {
namespace {

struct BarScene {
  elastic::BarSpec bar;
  double modulus = 0.0, cross_section = 0.0;
  sim::TimeSettings time;
  int strip_frames = 12;
  double max_speed = 1000.0;
};

BarScene read_bar_scene(const config::Config& c) {
  const scene::Reader r(c, scene::particle_scene_rules());
  BarScene s;
  s.bar = scene::read_bar(c);
  s.modulus = r.number("bar.modulus");
  s.cross_section = r.number("bar.cross_section");
  if (s.modulus > 0.0 && s.cross_section <= 0.0) {
    throw InputError("field 'bar.cross_section' = 0 is out of range (0, inf) when bar.modulus > 0");
  }
  s.bar.angular_stiffness = r.number("bar.angular_stiffness");
  s.bar.angle_rad = r.number("bar.angle_deg") * std::numbers::pi / 180.0;
  s.bar.drag = r.number("bar.drag");
  s.time = scene::read_time_settings(c);
  s.strip_frames = scene::read_strip_output(c).frames;
  s.max_speed = r.number("output.max_speed");
  return s;
}

elastic::Body build_bar(const BarScene& s) {
  elastic::Body body;
  try {
    body = elastic::make_bar(s.bar);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  if (s.modulus > 0.0) {  // eq. 7.1 per spring: longer (diagonal) springs are softer
    for (std::size_t k = 0; k < body.linear.size(); ++k) {
      body.linear.stiffness[k] =
          elastic::linear_stiffness_from_modulus(s.modulus, s.cross_section, body.linear.rest_length[k]);
    }
  }
  return body;
}

/// States recorded at the output frame times.
struct Recording {
  std::vector<double> times;
  std::vector<std::vector<Vec2>> positions;
  std::vector<elastic::Energy> energies;
};

/// Returns a problem description if some point moves faster than max_speed.
std::string check_speeds(const elastic::Body& body, double max_speed) {
  for (std::size_t i = 0; i < body.points.size(); ++i) {
    const double speed = norm(body.points.velocity[i]);
    if (!(speed <= max_speed)) {
      return "point " + std::to_string(i) + " moves at " + io::format_double(speed) + " > output.max_speed = " +
             io::format_double(max_speed);
    }
  }
  return {};
}

render::Drawing draw_bar(const elastic::Body& body, const std::vector<Vec2>& x, double t) {
  render::Drawing d;
  d.caption = "t = " + io::format_double(std::round(t * 100.0) / 100.0);
  for (std::size_t k = 0; k < body.linear.size(); ++k) {
    d.segments.push_back({x[static_cast<std::size_t>(body.linear.i[k])], x[static_cast<std::size_t>(body.linear.j[k])]});
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    (body.points.kind[i] == elastic::PointKind::Free ? d.points : d.marked_points).push_back(x[i]);
  }
  return d;
}

void write_frames_csv(const io::OutputDir& out, const Recording& rec) {
  io::CsvWriter csv({"frame", "t", "point", "x", "y"});
  for (std::size_t f = 0; f < rec.times.size(); ++f) {
    for (std::size_t i = 0; i < rec.positions[f].size(); ++i) {
      csv.row({static_cast<double>(f), rec.times[f], static_cast<double>(i), rec.positions[f][i].x, rec.positions[f][i].y});
    }
  }
  out.write_text("frames.csv", csv.text());
}

void write_energy_outputs(const io::OutputDir& out, const Recording& rec, const std::string& integrator) {
  io::CsvWriter csv({"t", "kinetic", "elastic", "gravity", "total"});
  render::ChartSpec chart;
  chart.title = "Swinging bar energy, ";
  chart.title += integrator;
  chart.x_label = "t";
  chart.x_unit = "s";
  chart.y_label = "energy";
  chart.y_unit = "J";
  for (std::string name : {"kinetic", "elastic", "gravity", "total"}) {
    chart.series.emplace_back();
    chart.series.back().label = std::move(name);
  }
  for (std::size_t f = 0; f < rec.times.size(); ++f) {
    const elastic::Energy& e = rec.energies[f];
    csv.row({rec.times[f], e.kinetic, e.elastic, e.gravity, e.total()});
    const double values[4] = {e.kinetic, e.elastic, e.gravity, e.total()};
    for (int s = 0; s < 4; ++s) {
      chart.series[static_cast<std::size_t>(s)].x.push_back(rec.times[f]);
      chart.series[static_cast<std::size_t>(s)].y.push_back(values[s]);
    }
  }
  out.write_text("energy.csv", csv.text());
  out.write_text("energy.png", render::chart_png(chart));
}

void write_strip(const io::OutputDir& out, const elastic::Body& body, const Recording& rec, int strip_frames) {
  std::vector<render::Drawing> panels;
  const std::size_t n = rec.times.size();
  const std::size_t shown = std::min<std::size_t>(n, static_cast<std::size_t>(strip_frames));
  for (std::size_t k = 0; k < shown; ++k) {
    const std::size_t f = shown == 1 ? 0 : k * (n - 1) / (shown - 1);
    panels.push_back(draw_bar(body, rec.positions[f], rec.times[f]));
  }
  out.write_text("swinging_bar.png", render::drawing_strip_png(panels, std::min<int>(static_cast<int>(shown), 6), "swinging bar"));
}

nlohmann::ordered_json key_figures(const Recording& rec, const sim::RunStatistics& stats, double wall_seconds,
                                   const elastic::Body& body) {
  nlohmann::ordered_json j;
  j["simulated_seconds"] = stats.simulated_seconds;
  j["wall_seconds"] = wall_seconds;
  j["steps"] = stats.steps;
  j["rejected_steps"] = stats.rejected_steps;
  j["function_evaluations"] = stats.function_evaluations;
  j["frames"] = rec.times.size();
  j["points"] = body.points.size();
  j["linear_springs"] = body.linear.size();
  j["angular_springs"] = body.angular.size();
  if (!rec.energies.empty()) {
    const double e0 = rec.energies.front().total(), e1 = rec.energies.back().total();
    j["energy_initial"] = e0;
    j["energy_final"] = e1;
    double lowest = rec.positions.front().front().y;
    for (const auto& frame : rec.positions)
      for (Vec2 p : frame) lowest = std::min(lowest, p.y);
    j["lowest_point_y"] = lowest;
  }
  return j;
}

std::function<Outcome(const io::OutputDir&)> prepare_swinging_bar(const Context& ctx) {
  const BarScene scene = read_bar_scene(ctx.config);
  auto body = std::make_shared<elastic::Body>(build_bar(scene));
  return [scene, body, ctx](const io::OutputDir& out) {
    const auto start = std::chrono::steady_clock::now();
    elastic::ElasticSystem system(*body);
    ode::Vector y = system.pack_state();
    Recording rec;
    elastic::Body state = *body;  // scratch copy to evaluate energies of recorded states
    auto on_frame = [&](double t, const ode::Vector& yf) -> std::string {
      elastic::ElasticSystem::unpack_state(yf, t, state);
      if (std::string problem = sim::check_finite(yf); !problem.empty()) return problem;
      rec.times.push_back(t);
      rec.positions.push_back(state.points.position);
      rec.energies.push_back(elastic::energy(state));
      return check_speeds(state, scene.max_speed);
    };
    const sim::RunOutcome result = sim::integrate(system, y, scene.time, on_frame, ctx.progress);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_frames_csv(out, rec);
    if (!rec.times.empty()) {
      write_energy_outputs(out, rec, scene.time.integrator);
      write_strip(out, *body, rec, scene.strip_frames);
    }
    write_summary(out, "swinging-bar", ctx.config, key_figures(rec, result.statistics, wall, *body), result.failure);
    return Outcome{result.failure};
  };
}

}  // namespace

Experiment swinging_bar_experiment() {
  Experiment e = sph_common::make_bar_experiment("swinging-bar",
                                                 "Thesis Figure 8.1: an elastic strand swinging from one pinned corner",
                                                 "scenes/swinging-bar.toml", prepare_swinging_bar);
  e.shorthands.clear();  // no particles: no run.threads, so no --threads
  return e;
}

}  // namespace jellysim::experiments
