// Immersed-boundary jellyfish benchmarks (docs/jellyfish.md):
//  - BM_Swim/<scene>/<scheme>: one contraction cycle (1/0.7 s) of the built-in jellyfish scene
//    ("default": Fig. 8.21's 60 × 60 tank; "fine": scenes/jellyfish-fine.toml's 160 × 160 tank),
//    explicit or semi-implicit coupling, no outputs. Counters: wall seconds per simulated second
//    (wall_per_sim_s; < 0.1 means ten times faster than real time), steps and GMRES iterations.
//    The explicit scheme runs at the largest step coupling-stability found stable for it.
#include <benchmark/benchmark.h>

#include "experiments/experiment.hpp"
#include "experiments/jellyfish_runs.hpp"

namespace {

using namespace jellysim;

jellyfish::SwimSettings bench_scene(bool fine, bool semi_implicit) {
  io::Config c = experiments::default_config(experiments::find_experiment("jellyfish"));
  if (fine) {
    c.merge(io::Config::parse(experiments::embedded_text("scenes/jellyfish-fine.toml"), "scenes/jellyfish-fine.toml"));
  }
  c.set("tank.tracers_per_side=0");
  c.set("duration=" + io::format_double(1.0 / 0.7));
  c.set("output.frame_interval=0.1");
  c.set(std::string("coupling.scheme=") + (semi_implicit ? "semi-implicit" : "explicit"));
  if (!semi_implicit) c.set("coupling.max_dt=0.0025");
  return experiments::read_swim_settings(c);
}

void BM_Swim(benchmark::State& state, bool fine, bool semi_implicit) {
  const jellyfish::SwimSettings s = bench_scene(fine, semi_implicit);
  double wall = 0.0, simulated = 0.0, steps = 0.0, krylov = 0.0;
  for (auto _ : state) {
    const experiments::SwimRecording rec = experiments::run_swim(s, {}, nullptr, {});
    wall += rec.stats.wall_seconds;
    simulated += rec.stats.simulated_seconds;
    steps += static_cast<double>(rec.stats.steps);
    krylov += static_cast<double>(rec.stats.krylov_iterations);
    benchmark::DoNotOptimize(rec.metrics.data());
  }
  state.counters["wall_per_sim_s"] = simulated > 0 ? wall / simulated : 0.0;
  state.counters["steps_per_sim_s"] = simulated > 0 ? steps / simulated : 0.0;
  state.counters["krylov_per_step"] = steps > 0 ? krylov / steps : 0.0;
}

BENCHMARK_CAPTURE(BM_Swim, default_explicit, false, false)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Swim, default_semi_implicit, false, true)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Swim, fine_explicit, true, false)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Swim, fine_semi_implicit, true, true)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
