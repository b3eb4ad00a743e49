// Elastic-body benchmarks (docs/benchmarks.md):
//  - BM_SwingingBarStep: steps per second of the Figure 8.1 bar for every integrator (fixed dt = 0.01).
//  - BM_StiffBarWork: force evaluations needed by backward Euler (fixed steps) and Dormand–Prince
//    (adaptive) to reach a given accuracy on the bar with κ_l × 100, against a tight reference.
#include "jellysim/elastic/bar.hpp"
#include "jellysim/elastic/elastic_system.hpp"
#include "jellysim/ode/integrator.hpp"
#include "jellysim/sim/time_stepping.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace jellysim;

void BM_SwingingBarStep(benchmark::State& state) {
  const std::string name = ode::integrator_names()[static_cast<std::size_t>(state.range(0))];
  elastic::Body body = elastic::make_bar(elastic::BarSpec{});
  elastic::ElasticSystem system(body);
  auto integrator = ode::make_integrator(name);
  ode::Vector y = system.pack_state(), y_next(y.size());
  const double dt = 0.01;
  double t = 0.0;
  for (auto _ : state) {
    integrator->step(system, t, dt, y, y_next, nullptr);
    y.swap(y_next);
    t += dt;
    benchmark::DoNotOptimize(y.data());
  }
  state.SetLabel(name);
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["evals_per_step"] = static_cast<double>(system.evaluations()) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_SwingingBarStep)->DenseRange(0, 6)->Unit(benchmark::kMicrosecond);

constexpr double kStiffEndTime = 5.0;

elastic::BarSpec stiff_bar() {
  elastic::BarSpec spec;
  spec.stiffness *= 100.0;
  return spec;
}

/// State of the stiff bar at kStiffEndTime, by Dormand–Prince at a tight tolerance.
const ode::Vector& stiff_reference() {
  static const ode::Vector reference = [] {
    elastic::Body body = elastic::make_bar(stiff_bar());
    elastic::ElasticSystem system(body);
    ode::Vector y = system.pack_state();
    sim::TimeSettings ts{.integrator = "dopri5", .dt = 1e-4, .adaptive = true, .tolerances = {}, .duration = kStiffEndTime,
                         .frame_interval = kStiffEndTime};
    ts.tolerances.atol = ts.tolerances.rtol = 1e-12;
    sim::integrate(system, y, ts, [](double, const ode::Vector&) { return std::string(); });
    return y;
  }();
  return reference;
}

/// Arg 0: 0 = backward Euler with fixed dt = 5e-2 / 2^k, 1 = dopri5 adaptive with tol = 1e-3 / 10^k. Arg 1: k.
void BM_StiffBarWork(benchmark::State& state) {
  const bool implicit = state.range(0) == 0;
  const int k = static_cast<int>(state.range(1));
  const ode::Vector& reference = stiff_reference();
  sim::RunOutcome outcome;
  double error = 0.0;
  for (auto _ : state) {
    elastic::Body body = elastic::make_bar(stiff_bar());
    elastic::ElasticSystem system(body);
    ode::Vector y = system.pack_state();
    sim::TimeSettings ts{.integrator = implicit ? "backward-euler" : "dopri5", .dt = 1e-2, .adaptive = !implicit,
                         .tolerances = {}, .duration = kStiffEndTime, .frame_interval = kStiffEndTime};
    if (implicit) ts.dt = 5e-2 / static_cast<double>(1 << k);
    else ts.tolerances.atol = ts.tolerances.rtol = 1e-3 / std::pow(10.0, k);
    outcome = sim::integrate(system, y, ts, [](double, const ode::Vector&) { return std::string(); });
    error = (y - reference).head(y.size() / 2).lpNorm<Eigen::Infinity>();  // position error
  }
  state.SetLabel(implicit ? "backward-euler" : "dopri5");
  state.counters["position_error"] = error;
  state.counters["force_evals"] = static_cast<double>(outcome.statistics.function_evaluations);
  state.counters["jacobians"] = static_cast<double>(outcome.statistics.jacobian_evaluations);
  state.counters["steps"] = static_cast<double>(outcome.statistics.steps);
}
BENCHMARK(BM_StiffBarWork)
    ->ArgsProduct({{0}, {0, 1, 2, 4, 6}})
    ->ArgsProduct({{1}, {0, 1, 2, 3}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
