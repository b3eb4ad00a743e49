// `jellysim experiment resonance` (issue 37, docs/control.md): the bell's natural frequency in
// water from a release test, then a frequency sweep around it (Hoover & Miller 2015: driving the
// bell near its natural frequency is best).
//  1. Release: the stroke contracts the bell, the contraction is held at its peak (the contraction
//     clock slowed to a standstill) for resonance.hold seconds, then released (γ = 1: every muscle
//     at its uncontracted rest length); the bell's volume rings down with the fluid coupled. The
//     damped frequency is 1 / (2 × the mean time between successive extrema of V(t) − V_end).
//  2. Sweep: the stroke driven at resonance.multiples × that frequency (the scene's frequency when
//     the ring-down has no oscillation: overdamped), each run on a thread; speed and cost of
//     transport as `jellysim optimize` measures them (stroke_figures).
#include "jellysim/core/errors.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/experiments/optimize.hpp"
#include "jellysim/jellyfish/metrics.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/experiment_scenes.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::experiments {
namespace {

struct RingDown {
  std::vector<double> t, volume;  ///< from the release on
  double frequency_hz = NAN;      ///< NaN: no oscillation (overdamped)
  int extrema = 0;
  std::string failure;
};

/// Holds the contraction at its peak, releases it, records the volume.
RingDown ring_down(jellyfish::SwimSettings settings, const scene::ResonanceScene& r) {
  const jellyfish::JellyfishSpec& spec = settings.jellyfish();
  const double peak = spec.profile.contract_fraction / spec.frequency_hz + spec.neural_delay_s;
  settings.duration_s = peak + r.hold_s + r.ring_down_s;
  jellyfish::SwimSimulation sim(settings);
  RingDown out;
  const auto record_now = [&] {
    out.t.push_back(sim.time_s());
    out.volume.push_back(jellyfish::measure_bell(sim.jellyfish().umbrella_points()).volume_m3);
  };
  const auto run_to = [&](double t_end, bool record) {
    while (sim.time_s() < t_end - 1e-12 && out.failure.empty()) {
      sim.step_toward(std::min(t_end, sim.time_s() + settings.frame_interval_s));
      out.failure = sim.check();
      if (record) record_now();
    }
  };
  run_to(peak, false);
  sim.set_frequency(0, 1e-9);  // the contraction clock stands still: the peak is held
  run_to(peak + r.hold_s, false);
  sim.set_gamma(0, 1.0);  // released: every muscle at its uncontracted rest length
  record_now();           // the release: an extremum (the held bell is at rest)
  run_to(peak + r.hold_s + r.ring_down_s, true);
  return out;
}

/// The damped frequency from the extrema of V − V_end (V_end: the mean of the last quarter) whose
/// size is at least 5 % of the release's displacement (smaller wiggles are the flow's, not the
/// bell's ring), the release itself the first: 1 / (2 × their mean spacing).
void fit_frequency(RingDown& d) {
  const std::size_t n = d.volume.size();
  if (n < 8) return;
  double end = 0.0;
  for (std::size_t k = 3 * n / 4; k < n; ++k) end += d.volume[k] / static_cast<double>(n - 3 * n / 4);
  const double significant = 0.05 * std::abs(d.volume[0] - end);
  std::vector<double> times{d.t[0]};
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double a = d.volume[k - 1] - end, b = d.volume[k] - end, c = d.volume[k + 1] - end;
    if (((b > a && b >= c) || (b < a && b <= c)) && std::abs(b) >= significant) times.push_back(d.t[k]);
  }
  d.extrema = static_cast<int>(times.size());
  if (times.size() < 2) return;  // no overshoot: overdamped
  d.frequency_hz = 1.0 / (2.0 * (times.back() - times.front()) / static_cast<double>(times.size() - 1));
}

struct SweepPoint {
  double frequency = 0.0;
  std::map<std::string, double> figures;
  bool failed = false;
};

std::vector<SweepPoint> sweep(const config::Config& config, const std::vector<double>& frequencies, double cycles, int threads) {
  std::vector<SweepPoint> points(frequencies.size());
  WorkerPool pool(std::max(1, std::min(resolve_threads(threads), static_cast<int>(frequencies.size()))));
  pool.run_tasks(frequencies.size(), [&](std::size_t k) {
    const SerialThreadsScope serial;
    config::Config c = config;
    c.set("jellyfish.frequency=" + io::format_double(frequencies[k]));
    // One frame beyond the last cycle (the frame clock may stop short of cycles / f).
    c.set("duration=" + io::format_double(cycles / frequencies[k] + c.number("output.frame_interval")));
    const Evaluation e = evaluate_swim(c, std::nullopt, 0.0);
    points[k] = {frequencies[k], e.figures, e.failed};
  });
  return points;
}

void write_outputs(const io::OutputDir& out, const RingDown& d, const std::vector<SweepPoint>& points) {
  std::string ring = "t,volume\n";
  for (std::size_t k = 0; k < d.t.size(); ++k) ring += io::format_double(d.t[k]) + "," + io::format_double(d.volume[k]) + "\n";
  out.write_text("ringdown.csv", ring);
  std::string text = "frequency,speed,cost_of_transport,distance_per_cycle,peak_muscle_tension,failed\n";
  render::Series speed{"speed", {}, {}, true, true};
  for (const SweepPoint& p : points) {
    const auto f = [&](const char* name) { return p.failed ? NAN : p.figures.at(name); };
    text += io::format_double(p.frequency) + "," + io::format_double(f("speed")) + "," + io::format_double(f("cost_of_transport")) +
            "," + io::format_double(f("distance_per_cycle")) + "," + io::format_double(f("peak_muscle_tension")) + "," +
            (p.failed ? "1" : "0") + "\n";
    if (!p.failed) {
      speed.x.push_back(p.frequency);
      speed.y.push_back(f("speed"));
    }
  }
  out.write_text("resonance.csv", text);
  render::ChartSpec chart;
  chart.title = "resonance: speed against driving frequency" +
                (std::isnan(d.frequency_hz) ? std::string(" (ring-down overdamped)")
                                            : " (natural " + std::to_string(std::lround(d.frequency_hz * 100) / 100.0).substr(0, 4) + " Hz)");
  chart.x_label = "frequency";
  chart.x_unit = "Hz";
  chart.y_label = "speed";
  chart.y_unit = "m/s";
  chart.series = {speed};
  out.write_text("resonance.png", render::chart_png(chart));
}

/// The sweep point best by `figure` (largest speed, smallest cost), NaN when none.
double best_frequency(const std::vector<SweepPoint>& points, const char* figure, bool largest) {
  double best = NAN, value = NAN;
  for (const SweepPoint& p : points) {
    if (p.failed || !std::isfinite(p.figures.at(figure))) continue;
    const double v = p.figures.at(figure);
    if (std::isnan(value) || (largest ? v > value : v < value)) value = v, best = p.frequency;
  }
  return best;
}

std::function<Outcome(const io::OutputDir&)> prepare_resonance(const Context& ctx) {
  const jellyfish::SwimSettings settings = read_swim_settings(ctx.config);
  if (settings.school.size() != 1) throw InputError("experiment resonance needs exactly one jellyfish");
  const scene::ResonanceScene r = scene::read_resonance(ctx.config);
  return [settings, r, ctx](const io::OutputDir& out) {
    RingDown d = ring_down(settings, r);
    if (!d.failure.empty()) return Outcome{"the release test: " + d.failure};
    fit_frequency(d);
    const double centre = std::isnan(d.frequency_hz) ? settings.jellyfish().frequency_hz : d.frequency_hz;
    std::vector<double> frequencies;
    for (double m : r.multiples) {  // at most the scene's 5 Hz, each frequency once
      const double f = std::min(5.0, m * centre);
      if (std::find(frequencies.begin(), frequencies.end(), f) == frequencies.end()) frequencies.push_back(f);
    }
    const std::vector<SweepPoint> points = sweep(ctx.config, frequencies, r.cycles, r.threads);
    write_outputs(out, d, points);
    nlohmann::ordered_json j;
    j["natural_frequency_hz"] = std::isnan(d.frequency_hz) ? nlohmann::ordered_json() : nlohmann::ordered_json(d.frequency_hz);
    j["ring_down_extrema"] = d.extrema;
    j["sweep_centre_hz"] = centre;
    j["fastest_frequency_hz"] = best_frequency(points, "speed", true);
    j["cheapest_frequency_hz"] = best_frequency(points, "cost_of_transport", false);
    j["sweep_runs"] = points.size();
    write_summary(out, "experiment resonance", ctx.config, j, "");
    return Outcome{};
  };
}

}  // namespace

Experiment resonance_experiment() {
  Experiment e{"resonance",
               "The bell's natural frequency in water from a release (ring-down of its volume), then speed and cost "
               "of transport driven around it (Hoover & Miller 2015; docs/control.md)",
               "experiments/resonance.toml", prepare_resonance};
  e.base_path = "scenes/jellyfish.toml";
  return e;
}

}  // namespace jellysim::experiments
