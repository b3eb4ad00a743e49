// SPH fluids with spring-mass bodies, thesis §8.1.2: `sph-stream` (Figure 8.4), `mosquito-larva`
// (Figure 8.5) and `integrator-cost` (Figure 8.6).
#include "sph_common.hpp"
#include "jellysim/core/errors.hpp"

#include <chrono>
#include <cmath>
#include <memory>

namespace jellysim::experiments {
namespace {

using namespace sph_common;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void write_chart(const io::OutputDir& out, const std::string& name, const render::ChartSpec& chart) {
  out.write_text(name, render::chart_png(chart));
}

// ---- sph-stream (Figure 8.4) ---------------------------------------------------------------------

struct StreamSetup {
  sph::Scene scene;
  sph::RunSettings run;
  Vec2 lo, hi;
  int strip_frames = 12;
};

StreamSetup read_stream(const config::Config& c) {
  StreamSetup s;
  try {
    s.scene.body = elastic::make_bar(read_bar(c));
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  s.scene.outline = sph::strip_outline(read_bar(c).segments);
  read_collision(c, s.scene);
  s.scene.sph = read_fluid_parameters(c);
  s.scene.particle_gravity = scene::Reader(c, scene::particle_scene_rules()).vec2("fluid.gravity");
  const scene::Box box = scene::read_box(c);
  s.lo = box.min;
  s.hi = box.max;
  s.scene.walls = sph::box_walls(s.lo, s.hi);
  s.run = scene::read_particle_run_settings(c);
  s.run.emitter = scene::read_emitter(c, box);
  s.strip_frames = scene::read_strip_output(c).frames;
  return s;
}

std::function<Outcome(const io::OutputDir&)> prepare_sph_stream(const Context& ctx) {
  auto setup = std::make_shared<StreamSetup>(read_stream(ctx.config));
  return [setup, ctx](const io::OutputDir& out) {
    const auto start = Clock::now();
    const double cpu0 = cpu_seconds();
    std::vector<Frame> frames;
    const sph::RunResult r = sph::run(setup->scene, setup->run, [&](double t, const sph::Scene& s, const sph::CoupledSystem&) {
      frames.push_back(snapshot(t, s));
      return std::string();
    }, ctx.progress);
    const double wall = seconds_since(start), cpu = cpu_seconds() - cpu0;  // the run only, not the outputs
    write_frames_csv(out, frames);
    DrawOptions d;
    d.decor = box_segments(setup->lo, setup->hi);
    write_strip(out, "sph_stream.png", "SPH stream onto the bar", setup->scene, frames, 0.0, setup->run.time.duration,
                setup->strip_frames, d);
    nlohmann::ordered_json f = run_figures(r, wall, cpu);
    f["particles"] = setup->scene.position.size();
    f["frames_per_wall_second"] = wall > 0.0 ? static_cast<double>(frames.size()) / wall : 0.0;
    write_summary(out, "sph-stream", ctx.config, f, r.failure);
    return Outcome{r.failure};
  };
}

// ---- mosquito-larva (Figure 8.5) -----------------------------------------------------------------

struct LarvaSetup {
  LarvaScene larva;
  sph::RunSettings run;
  Vec2 lo, hi;
  int strip_frames = 12;
  double strip_start = 0.0, velocity_scale = 0.0;
};

LarvaSetup read_larva_setup(const config::Config& c) {
  LarvaSetup s;
  s.larva = build_larva_scene(c);
  s.run = scene::read_particle_run_settings(c);
  const scene::Box box = scene::read_box(c);
  s.lo = box.min;
  s.hi = box.max;
  const scene::StripOutput strip = scene::read_strip_output(c);
  s.strip_frames = strip.frames;
  s.strip_start = strip.start_s;
  s.velocity_scale = strip.velocity_scale_s;
  return s;
}

Vec2 body_centre(const std::vector<Vec2>& x) {
  Vec2 c{};
  for (Vec2 p : x) c += p;
  return x.empty() ? c : c / static_cast<double>(x.size());
}

std::function<Outcome(const io::OutputDir&)> prepare_mosquito_larva(const Context& ctx) {
  auto setup = std::make_shared<LarvaSetup>(read_larva_setup(ctx.config));
  return [setup, ctx](const io::OutputDir& out) {
    sph::Scene& scene = setup->larva.scene;
    const Vec2 c0 = body_centre(scene.body.points.position);
    std::vector<Frame> frames;
    const auto start = Clock::now();
    const double cpu0 = cpu_seconds();
    const sph::RunResult r = sph::run(scene, setup->run, [&](double t, const sph::Scene& s, const sph::CoupledSystem&) {
      frames.push_back(snapshot(t, s));
      return std::string();
    }, ctx.progress);
    const double wall = seconds_since(start), cpu = cpu_seconds() - cpu0;  // the run only, not the outputs
    write_frames_csv(out, frames);
    DrawOptions d;
    d.decor = box_segments(setup->lo, setup->hi);
    d.velocity_scale_s = setup->velocity_scale;
    const double t0 = std::min(setup->strip_start, setup->run.time.duration);
    const double t1 = std::min(t0 + setup->strip_frames * setup->run.time.frame_interval, setup->run.time.duration);
    write_strip(out, "mosquito_larva.png", "mosquito larva in SPH fluid", scene, frames, t0, t1, setup->strip_frames, d);
    nlohmann::ordered_json f = run_figures(r, wall, cpu);
    f["fluid_particles"] = scene.fluid_count;
    f["particle_mass"] = setup->larva.mass.mass_kg;
    f["particle_mass_eq_5_21"] = setup->larva.mass.initial_guess_kg;
    f["mass_bisection_iterations"] = setup->larva.mass.iterations;
    const Vec2 c1 = body_centre(scene.body.points.position);
    f["larva_displacement"] = {c1.x - c0.x, c1.y - c0.y};
    write_summary(out, "mosquito-larva", ctx.config, f, r.failure);
    return Outcome{r.failure};
  };
}

// ---- integrator-cost (Figure 8.6) ----------------------------------------------------------------

struct CostSetup {
  config::Config config;
  sph::RunSettings run;
  std::vector<double> gas_constants;
  std::vector<std::string> integrators, controls;
};

CostSetup read_cost(const config::Config& c) {
  CostSetup s{c, scene::read_particle_run_settings(c), {}, {}, {}};
  scene::CostStudy study = scene::read_cost_study(c);
  s.gas_constants = std::move(study.gas_constants);
  s.integrators = std::move(study.integrators);
  s.controls = std::move(study.error_controls);
  s.run.time.adaptive = true;
  for (double k : s.gas_constants) build_larva_scene(c, k);  // validates every configuration up front
  return s;
}

struct CostRow {
  std::string integrator, control;
  double gas_constant = 0.0, wall_seconds = 0.0, cpu_seconds = 0.0;
  sph::RunResult result;
};

std::vector<CostRow> run_cost_study(const CostSetup& s, const sim::ProgressCallback& progress) {
  std::vector<CostRow> rows;
  for (const std::string& method : s.integrators) {
    const bool embedded = ode::make_integrator(method)->has_embedded_pair();
    for (const std::string& control : s.controls) {
      if (control == "embedded" && !embedded) continue;  // FE, PC and BE have no pair: step doubling only
      for (double kappa : s.gas_constants) {
        LarvaScene larva = build_larva_scene(s.config, kappa);
        sph::RunSettings rs = s.run;
        rs.time.integrator = method;
        rs.error_control = control;
        rs.time.frame_interval = rs.time.duration;
        const auto start = Clock::now();
        const double cpu0 = cpu_seconds();
        CostRow row{method, control, kappa, 0.0, 0.0, {}};
        row.result = sph::run(larva.scene, rs, [](double, const sph::Scene&, const sph::CoupledSystem&) { return std::string(); },
                              progress);
        row.wall_seconds = seconds_since(start);
        row.cpu_seconds = cpu_seconds() - cpu0;
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

std::string short_name(const std::string& method, const std::string& control) {
  const std::string m = method == "forward-euler" ? "FE" : method == "predictor-corrector" ? "PC"
                        : method == "dopri5" ? "DP" : method == "rk2" ? "RK2" : method == "backward-euler" ? "BE" : method;
  return m + (control == "embedded" ? " EP" : " SD");
}

void write_cost(const io::OutputDir& out, const std::vector<CostRow>& rows, double duration) {
  io::CsvWriter csv({"integrator", "error_control", "gas_constant", "steps", "rejected_steps", "function_evaluations",
                     "simulated_seconds", "completed"});
  nlohmann::ordered_json timings = nlohmann::ordered_json::array();
  render::ChartSpec chart;
  chart.title = "CPU time to simulate " + io::format_double(duration) + " s of the mosquito larva";
  chart.x_label = "gas constant kappa_p";
  chart.y_label = "CPU time";
  chart.y_unit = "s";
  chart.log_x = chart.log_y = true;
  for (const CostRow& r : rows) {
    const auto& st = r.result.statistics;
    csv.row({r.integrator, r.control}, {r.gas_constant, static_cast<double>(st.steps),
                                        static_cast<double>(st.rejected_steps), static_cast<double>(st.function_evaluations),
                                        st.simulated_seconds, r.result.failed ? 0.0 : 1.0});
    timings.push_back({{"integrator", r.integrator}, {"error_control", r.control}, {"gas_constant", r.gas_constant},
                       {"cpu_seconds", r.cpu_seconds}, {"wall_seconds", r.wall_seconds}});
    const std::string label = short_name(r.integrator, r.control);
    if (chart.series.empty() || chart.series.back().label != label) {
      chart.series.emplace_back();
      chart.series.back().label = label;
      chart.series.back().markers = true;
      chart.series.back().dashed = r.control == "step-doubling";
    }
    if (!r.result.failed) {
      chart.series.back().x.push_back(r.gas_constant);
      chart.series.back().y.push_back(r.cpu_seconds);
    }
  }
  out.write_text("integrator_cost.csv", csv.text());
  write_timings(out, {{"runs", timings}});
  write_chart(out, "integrator_cost.png", chart);
}

std::function<Outcome(const io::OutputDir&)> prepare_integrator_cost(const Context& ctx) {
  auto setup = std::make_shared<CostSetup>(read_cost(ctx.config));
  return [setup, ctx](const io::OutputDir& out) {
    const auto start = Clock::now();
    const std::vector<CostRow> rows = run_cost_study(*setup, {});
    write_cost(out, rows, setup->run.time.duration);
    nlohmann::ordered_json f, seconds = nlohmann::ordered_json::object();
    int failed = 0;
    for (const CostRow& r : rows) {
      seconds[short_name(r.integrator, r.control) + "@" + io::format_double(r.gas_constant)] =
          r.result.failed ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.cpu_seconds);
      failed += r.result.failed;
    }
    f["wall_seconds"] = seconds_since(start);
    f["runs"] = rows.size();
    f["failed_runs"] = failed;
    f["run_cpu_seconds"] = seconds;
    write_summary(out, "integrator-cost", ctx.config, f, "");
    return Outcome{};
  };
}

}  // namespace

Experiment sph_stream_experiment() {
  return make_bar_experiment("sph-stream",
                         "Thesis Figure 8.4: a stream of SPH particles falls onto the Figure 8.1 bar",
                         "experiments/sph-stream.toml", prepare_sph_stream);
}

Experiment mosquito_larva_experiment() {
  return make_experiment("mosquito-larva",
                         "Thesis Figure 8.5: a contracting spring-mass larva in 625 SPH particles",
                         "experiments/mosquito-larva.toml", prepare_mosquito_larva);
}

Experiment integrator_cost_experiment() {
  return make_experiment("integrator-cost",
                         "Thesis Figure 8.6: run time of the larva scene versus the gas constant, per integrator",
                         "experiments/integrator-cost.toml", prepare_integrator_cost);
}

}  // namespace jellysim::experiments
