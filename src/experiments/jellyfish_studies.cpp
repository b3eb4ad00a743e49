// The chapter 8 jellyfish experiments (thesis §8.1.3–8.2.3): oval membrane (Figs 8.8/8.9),
// kinematics (Figs 8.15–8.17), morphology (Fig. 8.18), structural and numerical instability
// (Figs 8.11/8.12), the frequency sweep (Figs 8.13/8.14), the fluid-free model (§8.2.3) and the
// stable step of the explicit and semi-implicit couplings.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include "jellysim/studies/oval_membrane.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/study_scenes.hpp"
#include "jellysim/jellyfish/fluidless.hpp"
#include "jellysim/render/plot.hpp"

namespace jellysim::experiments {
namespace {


void write_chart(const io::OutputDir& out, const std::string& name, render::ChartSpec chart) {
  out.write_text(name, render::chart_png(chart));
}

// ---------------------------------------------------------------- oval membrane (Figs 8.8, 8.9)

// Shapes over time (Fig. 8.8): up to six frames, evenly spread, in a box_m square.
std::vector<render::Drawing> membrane_shapes(const studies::MembraneRun& run, double box_m) {
  std::vector<render::Drawing> panels;
  const std::size_t shown = std::min<std::size_t>(run.frames.size(), 6);
  for (std::size_t k = 0; k < shown; ++k) {
    const auto& f = run.frames[shown == 1 ? 0 : k * (run.frames.size() - 1) / (shown - 1)];
    render::Drawing d;
    d.caption = "t = " + io::format_double(std::round(f.t * 100) / 100);
    for (std::size_t i = 0; i < f.points.size(); ++i) d.segments.push_back({f.points[i], f.points[(i + 1) % f.points.size()]});
    d.marked_points = {Vec2{0, 0}, Vec2{box_m, box_m}};  // keeps the box in view
    panels.push_back(std::move(d));
  }
  return panels;
}

// The area retained A/A0 over time of a run on a cells x cells grid (Fig. 8.9).
render::Series area_ratio_series(const studies::MembraneRun& run, std::int64_t cells) {
  render::Series series;
  series.label = std::to_string(cells) + " x " + std::to_string(cells);
  for (const auto& f : run.frames) {
    series.x.push_back(f.t);
    series.y.push_back(f.area / run.frames.front().area);
  }
  return series;
}

std::function<Outcome(const io::OutputDir&)> prepare_oval_membrane(const Context& ctx) {
  const scene::MembraneScene membrane = scene::read_membrane_scene(ctx.config);
  const studies::OvalMembraneSettings base = membrane.membrane;
  const std::vector<std::int64_t> refinement = membrane.refinement_cells;
  return [base, refinement, ctx](const io::OutputDir& out) {
    const studies::MembraneRun run = studies::run_oval_membrane(base);
    io::CsvWriter area({"t", "area", "area_ratio", "aspect_ratio"});
    const double a0 = run.frames.front().area;
    for (const auto& f : run.frames) area.row({f.t, f.area, f.area / a0, f.aspect_ratio});
    out.write_text("area.csv", area.text());
    out.write_text("shapes.png", render::drawing_strip_png(membrane_shapes(run, base.box_m), 3,
                                                          "oval membrane (" + base.solver + ")"));
    // Area retained over time (Fig. 8.9) and the refinement study.
    render::ChartSpec chart;
    chart.title = "Oval membrane: area retained (" + base.solver + ")";
    chart.x_label = "t";
    chart.x_unit = "s";
    chart.y_label = "A / A0";
    if (std::find(refinement.begin(), refinement.end(), base.cells) == refinement.end()) {
      chart.series.push_back(area_ratio_series(run, base.cells));
    }
    io::CsvWriter refine({"cells", "dt", "area_lost_percent", "final_aspect_ratio"});
    nlohmann::ordered_json refine_timings = nlohmann::ordered_json::array();
    nlohmann::ordered_json study = nlohmann::ordered_json::array();
    for (const auto cells : refinement) {
      studies::OvalMembraneSettings s = base;
      s.cells = static_cast<int>(cells);
      s.dt_s = base.dt_s * base.cells / static_cast<double>(cells);  // same Courant number
      const studies::MembraneRun r = studies::run_oval_membrane(s);
      const double lost = 100.0 * (1.0 - r.frames.back().area / r.frames.front().area);
      refine.row({static_cast<double>(cells), s.dt_s, lost, r.frames.back().aspect_ratio});
      refine_timings.push_back({{"cells", cells}, {"wall_seconds", r.wall_seconds}});
      study.push_back({{"cells", cells}, {"area_lost_percent", lost}, {"failure", r.failure}});
      chart.series.push_back(area_ratio_series(r, cells));
    }
    out.write_text("refinement.csv", refine.text());
    write_timings(out, {{"refinement", refine_timings}});
    write_chart(out, "area.png", chart);
    nlohmann::ordered_json fig;
    fig["solver"] = base.solver;
    fig["area_lost_percent"] = 100.0 * (1.0 - run.frames.back().area / a0);
    fig["thesis_area_lost_percent"] = base.solver == "eulerian" ? 2.575 : 3.67;
    fig["initial_aspect_ratio"] = run.frames.front().aspect_ratio;
    fig["final_aspect_ratio"] = run.frames.back().aspect_ratio;
    fig["steps"] = run.steps;
    fig["wall_seconds"] = run.wall_seconds;
    fig["refinement"] = study;
    write_summary(out, "experiment oval-membrane", ctx.config, fig, run.failure);
    return Outcome{run.failure};
  };
}

// ------------------------------------------------ kinematics and morphology (Figs 8.15–8.18)

std::function<Outcome(const io::OutputDir&)> prepare_swim_study(const Context& ctx, const std::string& name) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  const SwimOutputOptions options = read_output_options(ctx.config);
  return [settings, options, ctx, name](const io::OutputDir& out) {
    const SwimRecording rec = run_swim(settings, options, &out, ctx.progress);
    write_metrics_csv(out, rec.metrics);
    if (name == "morphology") {
      io::CsvWriter csv({"t", "volume_ratio", "aperture_ratio", "volume", "aperture_area"});
      for (const auto& r : rec.metrics) csv.row({r.t, r.volume_ratio, r.aperture_ratio, r.volume, r.aperture_area});
      out.write_text("morphology.csv", csv.text());
    }
    write_swim_plots(out, rec.metrics, name);
    write_summary(out, "experiment " + name, ctx.config, swim_figures(settings, rec), rec.stats.failure);
    return Outcome{rec.stats.failure};
  };
}

// -------------------------------------------- structural and numerical instability (Figs 8.11/8.12)

/// Runs a scene that is expected to become unstable, keeps pictures of a few frames and of the
/// failing state, and reports which kind of instability the checks found. Exit status 0 either way:
/// finding (or not finding) the instability is the result.
std::function<Outcome(const io::OutputDir&)> prepare_instability(const Context& ctx, const std::string& name) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  const scene::InstabilityFigure figure = scene::read_instability_figure(ctx.config);
  const int panels = figure.panels;
  const double zoom = figure.zoom_diameters;
  const std::string expected = figure.expected;
  return [settings, panels, zoom, expected, ctx, name](const io::OutputDir& out) {
    jellyfish::SwimSimulation sim(settings);
    struct Snapshot {
      fluid::FlowState flow;
      render::FieldPicture picture;
    };
    std::vector<std::unique_ptr<Snapshot>> snaps;
    std::vector<jellyfish::SliceFrame> frames;
    const double every = settings.duration_s / std::max(1, panels - 1);
    double next = 0.0;
    auto snapshot = [&](const jellyfish::SwimSimulation& s) {
      auto snap = std::make_unique<Snapshot>();
      snap->flow = s.flow();
      snap->picture = swim_picture(s, zoom);
      snap->picture.state = &snap->flow;
      snaps.push_back(std::move(snap));
    };
    const jellyfish::SwimRunStats stats = sim.run(
        [&](const jellyfish::SwimSimulation& s) -> std::string {
          frames.push_back(s.jellyfish().slice_frame(s.time_s()));
          if (s.time_s() >= next - 1e-9 || !s.check().empty()) {
            snapshot(s);
            next += every;
          }
          return {};
        },
        ctx.progress);
    render::FieldPictureOptions po;
    po.quantity = render::FieldQuantity::speed;
    std::vector<render::FieldPicture> pictures;
    for (const auto& s : snaps) pictures.push_back(s->picture);
    if (!pictures.empty()) {
      const std::string figure = name == "structural-instability" ? "figure_8_11.png" : "figure_8_12.png";
      out.write_text(figure, render::field_panels_png(pictures, std::min<int>(3, static_cast<int>(pictures.size())), po));
    }
    SwimRecording rec;
    rec.frames = frames;
    for (const auto& f : frames) rec.frame_times.push_back(f.time_s);
    rec.stats = stats;
    rec.metrics = jellyfish::compute_metrics(
        frames, {settings.tank.density_kg_per_m3, std::max(settings.tank.viscosity_m2_per_s, 1e-9)});
    write_metrics_csv(out, rec.metrics);
    nlohmann::ordered_json fig = swim_figures(settings, rec);
    const std::string kind = stats.failure.rfind("structural", 0) == 0 ? "structural"
                             : stats.failure.rfind("numerical", 0) == 0 ? "numerical" : "none";
    fig["instability"] = kind;
    fig["expected_instability"] = expected;
    fig["instability_message"] = stats.failure;
    fig["bell_modulus"] = settings.jellyfish().bell_modulus_pa;
    write_summary(out, "experiment " + name, ctx.config, fig, "");
    return Outcome{};
  };
}

// ------------------------------------------------------------ frequency sweep (Figs 8.13/8.14)

struct SweepRun {
  std::size_t frequency_index = 0;  ///< into sweep.frequencies (which may repeat a value)
  double frequency = 0.0;
  int placement = 0;      ///< k of the shift k / placements of a cell
  double offset_m = 0.0;  ///< the first jellyfish's shift along its swimming axis
  Vec2 shift_m;           ///< the same shift as a vector
  SwimRecording rec;
  double distance() const { return rec.metrics.empty() ? 0.0 : rec.metrics.back().position; }
  double lateral() const { return rec.metrics.empty() ? 0.0 : rec.metrics.back().lateral; }
  bool sound() const { return rec.stats.failure.empty(); }
};

/// The fluid cell's extent along a unit direction (exact for directions along the axes).
double cell_extent_along(const coupling::TankSpec& tank, Vec2 direction) {
  return std::abs(direction.x) * tank.width_m / tank.cells_x + std::abs(direction.y) * tank.height_m / tank.cells_y;
}

/// Every (frequency, placement) run of the sweep. The first jellyfish is shifted along its swimming
/// axis by k / placements of a fluid cell: on the coarse default scene the distance after a few
/// cycles is chaotic (a 0.1 µm shift of the start changes it by half, docs/jellyfish.md "Grid
/// sensitivity"), so one run per frequency is one sample and the mean over placements the estimate.
std::vector<SweepRun> plan_sweep(const jellyfish::SwimSettings& base, const std::vector<double>& frequencies,
                                 int placements) {
  const Vec2 axis = rotated(Vec2{0.0, 1.0}, base.jellyfish().tilt_rad);
  const double cell = cell_extent_along(base.tank, axis);
  std::vector<SweepRun> runs;
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    for (int k = 0; k < placements; ++k) {
      SweepRun r;
      r.frequency_index = i;
      r.frequency = frequencies[i];
      r.placement = k;
      r.offset_m = cell * k / placements;
      r.shift_m = r.offset_m * axis;
      runs.push_back(std::move(r));
    }
  }
  return runs;
}

/// Mean, spread and failures of one frequency's runs. The statistics cover the sound runs (all of
/// them when every run failed: the distance up to the failure).
struct SweepPoint {
  double frequency = 0.0, mean = 0.0, min = 0.0, max = 0.0, std_dev = 0.0, lateral = 0.0, wall_s = 0.0;
  int runs = 0, failed = 0;
};

SweepPoint summarise_frequency(const std::vector<SweepRun>& runs, std::size_t frequency_index) {
  SweepPoint p;
  std::vector<const SweepRun*> mine, sound;
  for (const auto& r : runs) {
    if (r.frequency_index != frequency_index) continue;
    p.frequency = r.frequency;
    mine.push_back(&r);
    if (r.sound()) sound.push_back(&r);
    p.wall_s += r.rec.stats.wall_seconds;
  }
  p.runs = static_cast<int>(mine.size());
  p.failed = p.runs - static_cast<int>(sound.size());
  const std::vector<const SweepRun*>& used = sound.empty() ? mine : sound;
  p.min = INFINITY;
  p.max = -INFINITY;
  for (const SweepRun* r : used) {
    p.mean += r->distance() / used.size();
    p.lateral += r->lateral() / used.size();
    p.min = std::min(p.min, r->distance());
    p.max = std::max(p.max, r->distance());
  }
  for (const SweepRun* r : used) p.std_dev += (r->distance() - p.mean) * (r->distance() - p.mean);
  p.std_dev = used.size() > 1 ? std::sqrt(p.std_dev / (used.size() - 1)) : 0.0;  // sample standard deviation
  return p;
}

/// Every run of the sweep on the pool's threads (no more than there are runs); the threads used.
int run_sweep(const jellyfish::SwimSettings& base, int threads_wanted, std::vector<SweepRun>& runs) {
  const int threads = std::min(resolve_threads(threads_wanted), static_cast<int>(runs.size()));
  WorkerPool pool(std::max(1, threads));
  pool.run_tasks(runs.size(), [&](std::size_t k) {
    jellyfish::SwimSettings s = base;
    jellyfish::JellyfishSpec& jelly = s.school.front();
    jelly.frequency_hz = runs[k].frequency;
    jelly.aperture_centre_m += runs[k].shift_m;
    runs[k].rec = run_swim(s, {}, nullptr, {});
  });
  return threads;
}

/// Distance travelled versus frequency (Fig. 8.14): the mean per frequency, then each placement.
render::ChartSpec sweep_distance_chart(int placements, double duration_s) {
  render::ChartSpec distance;
  distance.title = "Distance travelled versus contraction frequency (Fig. 8.14)";
  distance.x_label = "frequency";
  distance.x_unit = "Hz";
  distance.y_label = "distance travelled";
  distance.y_unit = "m";
  distance.series.resize(2);
  distance.series[0].label = "mean of " + std::to_string(placements) + " placements, " +
                             io::format_double(duration_s) + " s";
  distance.series[0].markers = true;
  distance.series[1].label = "each placement (shifts of k/" + std::to_string(placements) + " cell)";
  distance.series[1].markers = true;
  distance.series[1].line = false;
  return distance;
}

/// The trajectories of the first placement (Fig. 8.13), a series per frequency.
render::ChartSpec trajectories_chart() {
  render::ChartSpec trajectories;
  trajectories.title = "Trajectories (Fig. 8.13), first placement";
  trajectories.x_label = "t";
  trajectories.x_unit = "s";
  trajectories.y_label = "bell centroid travelled";
  trajectories.y_unit = "m";
  return trajectories;
}

/// The bell centroid's distance travelled over time.
render::Series position_series(const std::string& label, const std::vector<jellyfish::MetricsRow>& metrics) {
  render::Series series;
  series.label = label;
  for (const auto& m : metrics) {
    series.x.push_back(m.t);
    series.y.push_back(m.position);
  }
  return series;
}

/// summary.json's figures of a sweep: the best frequency and distance, the placements and threads.
nlohmann::ordered_json sweep_figures(double best, double best_f, int placements, int threads) {
  nlohmann::ordered_json fig;
  fig["units"] = {{"frequency", "Hz"}, {"distance", "m"}, {"offset", "m"}, {"time", "s"}};
  fig["best_frequency"] = best_f;
  fig["best_distance"] = std::isfinite(best) ? best : 0.0;
  fig["placements"] = placements;
  fig["threads"] = threads;
  return fig;
}

std::function<Outcome(const io::OutputDir&)> prepare_sweep(const Context& ctx) {
  const jellyfish::SwimSettings base = read_swim_settings(ctx.config);
  const scene::SweepScene sweep = scene::read_sweep(ctx.config);
  const std::vector<double> frequencies = sweep.frequencies;
  const int placements = sweep.placements;
  const int threads_wanted = sweep.threads;
  return [base, frequencies, placements, threads_wanted, ctx](const io::OutputDir& out) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<SweepRun> runs = plan_sweep(base, frequencies, placements);
    const int threads = run_sweep(base, threads_wanted, runs);

    io::CsvWriter csv({"frequency", "distance_travelled", "mean_speed", "lateral_drift", "failed", "placements",
                       "distance_min", "distance_max", "distance_std"});
    io::CsvWriter run_csv({"frequency", "placement", "offset", "distance_travelled", "lateral_drift", "failed"});
    nlohmann::ordered_json frequency_timings = nlohmann::ordered_json::array(),
                           run_timings = nlohmann::ordered_json::array();
    render::ChartSpec distance = sweep_distance_chart(placements, base.duration_s), trajectories = trajectories_chart();
    nlohmann::ordered_json table = nlohmann::ordered_json::array();
    for (const auto& r : runs) {
      run_csv.row({r.frequency, static_cast<double>(r.placement), r.offset_m, r.distance(), r.lateral(),
                   r.sound() ? 0.0 : 1.0});
      run_timings.push_back({{"frequency", r.frequency}, {"placement", r.placement}, {"wall_seconds", r.rec.stats.wall_seconds}});
      distance.series[1].x.push_back(r.frequency);
      distance.series[1].y.push_back(r.distance());
      table.push_back({{"frequency", r.frequency}, {"placement", r.placement}, {"offset", r.offset_m},
                       {"distance_travelled", r.distance()}, {"failure", r.rec.stats.failure}});
      if (r.placement != 0) continue;
      trajectories.series.push_back(position_series(io::format_double(r.frequency) + " Hz", r.rec.metrics));
    }
    double best = -INFINITY, best_f = 0.0;
    for (std::size_t i = 0; i < frequencies.size(); ++i) {
      const SweepPoint p = summarise_frequency(runs, i);
      const double f = p.frequency;
      const double speed = base.duration_s > 0 ? p.mean / base.duration_s : 0.0;
      csv.row({f, p.mean, speed, p.lateral, static_cast<double>(p.failed), static_cast<double>(p.runs), p.min, p.max,
               p.std_dev});
      frequency_timings.push_back({{"frequency", f}, {"wall_seconds", p.wall_s}});
      distance.series[0].x.push_back(f);
      distance.series[0].y.push_back(p.mean);
      if (p.failed < p.runs && p.mean > best) {
        best = p.mean;
        best_f = f;
      }
    }
    out.write_text("sweep.csv", csv.text());
    out.write_text("sweep_runs.csv", run_csv.text());
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_timings(out, {{"wall_seconds", wall}, {"frequencies", frequency_timings}, {"runs", run_timings}});
    write_chart(out, "sweep.png", distance);
    write_chart(out, "trajectories.png", trajectories);
    nlohmann::ordered_json fig = sweep_figures(best, best_f, placements, threads);
    fig["wall_seconds"] = wall;
    fig["simulated_seconds"] = base.duration_s;
    fig["bell_height"] = base.jellyfish().height_m;
    fig["runs"] = table;
    write_summary(out, "sweep", ctx.config, fig, "");
    return Outcome{};
  };
}

// ------------------------------------------------------------------- fluid-free model (§8.2.3)

std::function<Outcome(const io::OutputDir&)> prepare_fluidless(const Context& ctx) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  const scene::FluidlessScene fluidless = scene::read_fluidless(ctx.config);
  const jellyfish::FluidlessSettings fl = fluidless.model;
  const double point_mass = fluidless.point_mass;
  sim::TimeSettings time = fluidless.time;
  time.duration = settings.duration_s;
  time.frame_interval = settings.frame_interval_s;
  const bool compare = fluidless.compare_with_fluid;
  return [settings, fl, point_mass, time, compare, ctx](const io::OutputDir& out) {
    jellyfish::JellyfishSpec spec = settings.jellyfish();
    spec.point_mass_kg = point_mass;
    jellyfish::Jellyfish jelly(spec);
    jellyfish::FluidlessSystem system(jelly, fl);
    ode::Vector y = system.pack_state();
    std::vector<jellyfish::SliceFrame> frames;
    const auto start = std::chrono::steady_clock::now();
    const sim::RunOutcome result = sim::integrate(
        system, y, time,
        [&](double t, const ode::Vector& yf) -> std::string {
          if (std::string p = sim::check_finite(yf); !p.empty()) return p;
          system.unpack_state(yf);
          frames.push_back(jelly.slice_frame(t));
          return {};
        },
        ctx.progress);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    SwimRecording rec;
    rec.frames = frames;
    for (const auto& f : frames) rec.frame_times.push_back(f.time_s);
    rec.stats.simulated_seconds = result.statistics.simulated_seconds;
    rec.stats.wall_seconds = wall;
    rec.stats.steps = result.statistics.steps;
    rec.stats.failure = result.failure;
    rec.metrics = jellyfish::compute_metrics(frames, {settings.tank.density_kg_per_m3,
                                                     std::max(settings.tank.viscosity_m2_per_s, 1e-9)});
    write_metrics_csv(out, rec.metrics);
    write_swim_plots(out, rec.metrics, "fluid-free");
    nlohmann::ordered_json fig = swim_figures(settings, rec);
    fig["function_evaluations"] = result.statistics.function_evaluations;
    if (compare && result.failure.empty()) {
      const SwimRecording with_fluid = run_swim(settings, {}, nullptr, {});
      write_metrics_csv(out, with_fluid.metrics, "metrics_with_fluid.csv");
      fig["with_fluid"] = swim_figures(settings, with_fluid);
      fig["speedup_over_fluid"] = wall > 0 ? with_fluid.stats.wall_seconds / wall : 0.0;
    }
    write_summary(out, "experiment fluidless", ctx.config, fig, result.failure);
    return Outcome{result.failure};
  };
}

// ------------------------------------------- stable step: explicit versus semi-implicit coupling

std::function<Outcome(const io::OutputDir&)> prepare_coupling_stability(const Context& ctx) {
  const jellyfish::SwimSettings base = read_swim_settings(ctx.config);
  const std::vector<double> steps = scene::read_coupling_stability_steps(ctx.config);
  return [base, steps, ctx](const io::OutputDir& out) {
    io::CsvWriter csv({"dt", "explicit_stable", "semi_implicit_stable", "semi_implicit_krylov_per_step"});
    nlohmann::ordered_json fig, runs = nlohmann::ordered_json::array(), timings = nlohmann::ordered_json::array();
    double largest[2] = {0.0, 0.0};
    for (double dt : steps) {
      double wall[2] = {0, 0}, krylov = 0.0;
      bool stable[2] = {false, false};
      for (int scheme = 0; scheme < 2; ++scheme) {
        jellyfish::SwimSettings s = base;
        s.coupling.scheme = scheme == 0 ? coupling::Scheme::explicit_euler : coupling::Scheme::semi_implicit;
        s.coupling.max_time_step_s = dt;
        s.coupling.safety_factor = 1.0;
        s.frame_interval_s = std::max(dt, base.frame_interval_s);
        const SwimRecording r = run_swim(s, {}, nullptr, {});
        stable[scheme] = r.stats.failure.empty();
        wall[scheme] = r.stats.simulated_seconds > 0 ? r.stats.wall_seconds / r.stats.simulated_seconds : 0.0;
        if (scheme == 1 && r.stats.steps > 0) krylov = static_cast<double>(r.stats.krylov_iterations) / r.stats.steps;
        if (stable[scheme]) largest[scheme] = std::max(largest[scheme], dt);
        const char* name = scheme == 0 ? "explicit" : "semi-implicit";
        runs.push_back({{"dt", dt}, {"scheme", name}, {"failure", r.stats.failure},
                        {"distance_travelled", r.metrics.empty() ? 0.0 : r.metrics.back().position}});
        timings.push_back({{"dt", dt}, {"scheme", name}, {"wall_per_simulated_second", wall[scheme]}});
      }
      csv.row({dt, stable[0] ? 1.0 : 0.0, stable[1] ? 1.0 : 0.0, krylov});
    }
    out.write_text("coupling_stability.csv", csv.text());
    write_timings(out, {{"runs", timings}});
    fig["largest_stable_dt_explicit"] = largest[0];
    fig["largest_stable_dt_semi_implicit"] = largest[1];
    fig["stable_step_ratio"] = largest[0] > 0 ? largest[1] / largest[0] : 0.0;
    fig["bell_modulus"] = base.jellyfish().bell_modulus_pa;
    fig["runs"] = runs;
    write_summary(out, "experiment coupling-stability", ctx.config, fig, "");
    return Outcome{};
  };
}

/// The chapter 8 studies extend the jellyfish scene on the thesis's own coarse tank (Fig. 8.21), as
/// they did before the built-in scene was resolved: their figures stay reproducible.
Experiment with_base(Experiment e) {
  e.base_path = "scenes/jellyfish.toml";
  e.base_overlay_path = "scenes/jellyfish-thesis.toml";
  return e;
}

}  // namespace

Experiment oval_membrane_experiment() {
  Experiment e{"oval-membrane", "Stockie & Wetton's oval membrane: area kept by the immersed boundary (Figs 8.8/8.9)",
               "experiments/oval-membrane.toml", prepare_oval_membrane};
  e.shorthands = {"solver"};
  return e;
}
Experiment kinematics_experiment() {
  return with_base({"kinematics", "Position, velocity and acceleration of the 4 cm jellyfish at 0.7 Hz (Figs 8.15-8.17)",
                    "experiments/kinematics.toml",
                    [](const Context& c) { return prepare_swim_study(c, "kinematics"); }});
}
Experiment morphology_experiment() {
  return with_base({"morphology", "Bell volume and aperture area over the cycle, normalised (Fig. 8.18, Fig. 6.10)",
                    "experiments/morphology.toml",
                    [](const Context& c) { return prepare_swim_study(c, "morphology"); }});
}
Experiment structural_instability_experiment() {
  return with_base({"structural-instability", "A too-soft bell (1.186e4 Pa) deforms beyond repair (Fig. 8.11)",
                    "experiments/structural-instability.toml",
                    [](const Context& c) { return prepare_instability(c, "structural-instability"); }});
}
Experiment numerical_instability_experiment() {
  return with_base({"numerical-instability", "A too-stiff bell (1.186e6 Pa) with explicit coupling blows up (Fig. 8.12)",
                    "experiments/numerical-instability.toml",
                    [](const Context& c) { return prepare_instability(c, "numerical-instability"); }});
}
Experiment frequency_sweep_experiment() {
  return with_base({"frequency-sweep", "Distance travelled versus contraction frequency on the thesis's tank, in parallel (Figs 8.13/8.14)",
                    "experiments/frequency-sweep.toml", prepare_sweep});
}
Experiment sweep_experiment() {
  Experiment e{"sweep", "Distance travelled versus contraction frequency on the built-in (resolved) scene, in parallel (`jellysim sweep`)",
               "experiments/sweep.toml", prepare_sweep};
  e.base_path = "scenes/jellyfish.toml";
  return e;
}
Experiment fluidless_experiment() {
  return with_base({"fluidless", "The jellyfish without a fluid: drag and a dV/dt pressure (section 8.2.3)",
                    "experiments/fluidless.toml", prepare_fluidless});
}
Experiment coupling_stability_experiment() {
  return with_base({"coupling-stability", "Largest stable step of the explicit and the semi-implicit coupling",
                    "experiments/coupling-stability.toml", prepare_coupling_stability});
}

}  // namespace jellysim::experiments
