// Particle-fluid benchmarks (docs/sph.md):
//  - BM_SphAccelerations/threads: one SPH force evaluation (density + pressure + viscosity, mirrored
//    walls) of the mosquito-larva fluid (625 particles, h = 0.05), with 1 or 2 threads.
//  - BM_SphAccelerationsLarge/threads: the same for 10,000 particles (shows the O(n) cell grid).
//  - BM_MosquitoLarva/threads: simulating 1 s of the mosquito-larva scene (κ_p = 40, Dormand–Prince,
//    tolerances 1e-4 + 1e-3 |y|) including collisions.
//  - BM_SphLarvaDerivative/threads, BM_SphLarvaRun/threads: one y' and 1 s of a developed larva state.
//  - BM_SphLarvaDerivativeOneVsTwo: one thread against two on that y', alternating in short blocks.
//  - BM_SphSideBySideFluids: one fluid alone against the same with a second thread evaluating its own
//    fluid next to it (the machine's ceiling for two threads).
//  - BM_PoolCeiling/job_us/phases: the best a two-thread WorkerPool can do here with jobs of a given
//    length: perfectly divisible arithmetic on private data, one thread against two.
#include "jellysim/math/median.hpp"
#include "jellysim/sph/bodies.hpp"
#include "jellysim/sph/fluid.hpp"
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/scene.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

namespace {

using namespace jellysim;

sph::SphParameters larva_fluid() { return {0.05, 2000.0, 40.0, 8.9e-3}; }

void run_accelerations(benchmark::State& state, double side, double spacing) {
  const std::vector<sph::Wall> walls = sph::box_walls({0.0, 0.0}, {side, side});
  std::vector<Vec2> x = sph::triangular_lattice({0.0, 0.0}, {side, side}, spacing), v;
  sph::thermalise(x, v, 0.1 * spacing, 1.0, 7);
  const std::vector<double> m(x.size(), 3.0);
  sph::SphFluid fluid(larva_fluid(), walls, static_cast<int>(state.range(0)));
  std::vector<Vec2> a;
  for (auto _ : state) {
    fluid.compute_accelerations(x, v, m, a);
    benchmark::DoNotOptimize(a.data());
  }
  state.counters["particles"] = static_cast<double>(x.size());
  state.counters["evals_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SphAccelerations(benchmark::State& state) { run_accelerations(state, 1.0, 0.043); }
BENCHMARK(BM_SphAccelerations)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_SphAccelerationsLarge(benchmark::State& state) { run_accelerations(state, 4.0, 0.043); }
BENCHMARK(BM_SphAccelerationsLarge)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

sph::Scene larva_scene(int threads) {
  sph::Scene s;
  s.sph = larva_fluid();
  s.walls = sph::box_walls({0.0, 0.0}, {1.0, 1.0});
  sph::LarvaSpec spec;
  spec.wave_cells = 0.1;
  sph::Larva larva = sph::make_larva(spec);
  s.body = larva.body;
  s.outline = larva.outline;
  s.muscles = larva.muscles;
  s.position = sph::triangular_lattice_with_count({0.0, 0.0}, {1.0, 1.0}, 625, [](Vec2 p) {
    return std::abs(p.x - 0.5) < 0.2125 && std::abs(p.y - 0.5) < 0.0375;  // the larva plus h/4
  });
  const sph::MassSearch m = sph::find_particle_mass(s.position, 1.0 - 0.02, s.sph, s.walls, 1e-6);
  s.velocity.assign(s.position.size(), Vec2{});
  s.mass.assign(s.position.size(), m.mass_kg);
  s.fluid_count = s.position.size();
  s.collision = {1e-6, 0.005};
  s.threads = threads;
  return s;
}

/// Dormand–Prince with the experiment's tolerances (1e-4 + 1e-3 |y|) over `duration` seconds.
sph::RunSettings larva_settings(double duration) {
  sph::RunSettings rs;
  rs.time.integrator = "dopri5";
  rs.time.adaptive = true;
  rs.time.dt = 1e-3;
  rs.time.tolerances.atol = 1e-4;
  rs.time.tolerances.rtol = 1e-3;
  rs.time.duration = duration;
  rs.time.frame_interval = duration;
  return rs;
}

std::string keep_going(double, const sph::Scene&, const sph::CoupledSystem&) { return {}; }

void BM_MosquitoLarva(benchmark::State& state) {
  const sph::RunSettings rs = larva_settings(1.0);
  std::int64_t steps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sph::Scene s = larva_scene(static_cast<int>(state.range(0)));
    state.ResumeTiming();
    const sph::RunResult r = sph::run(s, rs, keep_going);
    steps = r.statistics.steps;
    benchmark::DoNotOptimize(s.position.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_MosquitoLarva)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// One thread against two on a developed larva state (docs/sph.md, "Two cores"), in one process.
// The state is the scene after 3 s, computed once (the same for any thread count; results are
// bit-identical for 1 and 2 threads, only the time differs).
sph::Scene developed_scene(int threads) {
  static const sph::Scene developed = [] {
    sph::Scene s = larva_scene(1);
    sph::run(s, larva_settings(3.0), keep_going);
    return s;
  }();
  sph::Scene s = developed;
  s.threads = threads;
  return s;
}

/// One evaluation of the whole right-hand side y' = f(t, y): SPH forces in the parallel region,
/// muscles and springs, packing.
void BM_SphLarvaDerivative(benchmark::State& state) {
  sph::Scene scene = developed_scene(static_cast<int>(state.range(0)));
  const sph::CoupledSystem system(scene);
  const ode::Vector y = system.pack_state();
  ode::Vector dydt(y.size());
  for (auto _ : state) {
    system.derivative(1.0, y, dydt);
    benchmark::DoNotOptimize(dydt.data());
  }
  state.counters["evals_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SphLarvaDerivative)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

/// One thread against two on the same right-hand side, alternating in blocks of 16 evaluations so
/// that the machine's changing speed (a shared virtual machine's can drift by 2× within minutes, and
/// its host takes cores away for milliseconds) affects both alike. Reports the medians over the block
/// pairs of each block's time per evaluation and of the pair's ratio, and the share of the two-thread
/// system's evaluations that ran on both threads. Each block starts with an untimed evaluation: in a
/// run the evaluations follow each other within microseconds, and the helper thread never falls
/// asleep as it does here during the other block.
void BM_SphLarvaDerivativeOneVsTwo(benchmark::State& state) {
  sph::Scene one = developed_scene(1), two = developed_scene(2);
  const sph::CoupledSystem system_one(one), system_two(two);
  const ode::Vector y = system_one.pack_state();
  ode::Vector dydt(y.size());
  constexpr int kBlock = 16;
  using Clock = std::chrono::steady_clock;
  std::vector<double> one_us, two_us, ratio;
  for (auto _ : state) {
    double us[2];
    for (int k = 0; k < 2; ++k) {
      const sph::CoupledSystem& system = k == 0 ? system_one : system_two;
      system.derivative(1.0, y, dydt);  // not timed (see above)
      const auto start = Clock::now();
      for (int e = 0; e < kBlock; ++e) system.derivative(1.0, y, dydt);
      us[k] = std::chrono::duration<double, std::micro>(Clock::now() - start).count() / kBlock;
      benchmark::DoNotOptimize(dydt.data());
    }
    one_us.push_back(us[0]);
    two_us.push_back(us[1]);
    ratio.push_back(us[0] / us[1]);
  }
  state.counters["one_thread_us"] = median(one_us);
  state.counters["two_threads_us"] = median(two_us);
  state.counters["ratio"] = median(ratio);
  // The share of the two-thread system's evaluations that ran on both threads (the PathChooser
  // runs a period serially when its trial finds the serial path no slower).
  const sph::SphFluid& fluid = system_two.fluid();
  const auto evaluations = static_cast<double>(std::max<std::int64_t>(1, fluid.evaluations()));
  state.counters["parallel_share"] = static_cast<double>(fluid.parallel_evaluations()) / evaluations;
}
BENCHMARK(BM_SphLarvaDerivativeOneVsTwo)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The machine's own ceiling for two threads: one fluid evaluated alone, and while a second thread
/// evaluates another fluid on its own copy of the data (nothing shared). Alternates in blocks of 16
/// evaluations and reports the medians over the block pairs; a slowdown near 1 means both cores can
/// run this work at full speed, so whatever two threads of one evaluation lose comes from what they
/// share (docs/sph.md, "Where the second core goes").
void BM_SphSideBySideFluids(benchmark::State& state) {
  const std::vector<sph::Wall> walls = sph::box_walls({0.0, 0.0}, {1.0, 1.0});
  std::vector<Vec2> x = sph::triangular_lattice({0.0, 0.0}, {1.0, 1.0}, 0.043), v;
  sph::thermalise(x, v, 0.1 * 0.043, 1.0, 7);
  const std::vector<double> m(x.size(), 3.0);
  sph::SphFluid measured(larva_fluid(), walls, 1), other(larva_fluid(), walls, 1);
  const std::vector<Vec2> x_other = x, v_other = v;
  const std::vector<double> m_other = m;
  std::vector<Vec2> a, a_other;
  // 0: idle (sleeps on the futex), 1: evaluate until told to stop, 2: quit. `busy` acknowledges.
  std::atomic<int> command{0};
  std::atomic<bool> busy{false};
  std::atomic<std::int64_t> partner_evaluations{0};
  std::thread partner([&] {
    while (true) {
      command.wait(0);
      if (command.load() == 2) return;
      busy.store(true);
      while (command.load() == 1) {
        other.compute_accelerations(x_other, v_other, m_other, a_other);
        partner_evaluations.fetch_add(1, std::memory_order_relaxed);
      }
      busy.store(false);
    }
  });
  constexpr int kBlock = 16;
  using Clock = std::chrono::steady_clock;
  const auto time_block = [&] {
    measured.compute_accelerations(x, v, m, a);  // not timed
    const auto start = Clock::now();
    for (int e = 0; e < kBlock; ++e) measured.compute_accelerations(x, v, m, a);
    benchmark::DoNotOptimize(a.data());
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count() / kBlock;
  };
  std::vector<double> alone_us, beside_us, slowdown, partner_us;
  for (auto _ : state) {
    const double alone = time_block();
    command.store(1);
    command.notify_one();
    while (!busy.load()) std::this_thread::yield();
    const std::int64_t before = partner_evaluations.load();
    const double beside = time_block();
    const auto partner_done = static_cast<double>(partner_evaluations.load() - before);
    command.store(0);
    while (busy.load()) std::this_thread::yield();
    alone_us.push_back(alone);
    beside_us.push_back(beside);
    slowdown.push_back(beside / alone);
    // The partner's time per evaluation meanwhile (the block's evaluations, untimed one included).
    if (partner_done > 0) partner_us.push_back(beside * (kBlock + 1) / partner_done);
  }
  command.store(2);
  command.notify_one();
  partner.join();
  state.counters["alone_us"] = median(alone_us);
  state.counters["side_by_side_us"] = median(beside_us);
  state.counters["slowdown"] = median(slowdown);
  if (!partner_us.empty()) state.counters["partner_us"] = median(partner_us);
}
BENCHMARK(BM_SphSideBySideFluids)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The ceiling for two threads on jobs of a given length: a job is `phases` phases of arithmetic on
/// private, cache-resident data, split evenly between the parts (nothing shared, no imbalance by
/// design), about job_us µs on one thread. One thread (the pool's serial path) and two alternate in
/// blocks of 16 jobs; the counters are medians over the block pairs. With jobs as short as the
/// larva's y' (~40 µs), the ratio shows what the guest's jitter between its two virtual cores
/// leaves of the ideal 2 (docs/sph.md, "Two cores").
void BM_PoolCeiling(benchmark::State& state) {
  const auto job_us = static_cast<double>(state.range(0));
  const auto phases = static_cast<int>(state.range(1));
  constexpr std::size_t kValues = 2048;  // 16 KiB per part: stays in L1
  std::vector<std::vector<double>> data(2, std::vector<double>(kValues, 1.0));
  int sweeps = 1;  // per part and phase, calibrated below
  const auto work = [&](int part) {
    std::vector<double>& d = data[static_cast<std::size_t>(part)];
    for (int s = 0; s < sweeps; ++s) {
      for (double& v : d) v = v * 0.999 + 0.001;
    }
    benchmark::DoNotOptimize(d.data());
  };
  using Clock = std::chrono::steady_clock;
  WorkerPool pool(2);
  const std::vector<WorkerPool::Phase> job(static_cast<std::size_t>(phases), WorkerPool::Phase(work));
  const auto time_jobs = [&](bool parallel, int count) {
    pool.run_phases(job, parallel);  // not timed: wakes the helper
    const auto start = Clock::now();
    for (int k = 0; k < count; ++k) pool.run_phases(job, parallel);
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count() / count;
  };
  // Calibrate: sweeps such that one thread takes about job_us per job.
  const double per_sweep = time_jobs(false, 64) / (2.0 * phases);
  sweeps = std::max(1, static_cast<int>(std::lround(job_us / (2.0 * phases * per_sweep))));
  constexpr int kBlock = 16;
  std::vector<double> one_us, two_us, ratio;
  for (auto _ : state) {
    const double one = time_jobs(false, kBlock), two = time_jobs(true, kBlock);
    one_us.push_back(one);
    two_us.push_back(two);
    ratio.push_back(one / two);
  }
  state.counters["one_thread_us"] = median(one_us);
  state.counters["two_threads_us"] = median(two_us);
  state.counters["ratio"] = median(ratio);
}
BENCHMARK(BM_PoolCeiling)
    ->Args({40, 1})
    ->Args({40, 3})
    ->Args({400, 3})
    ->Args({4000, 3})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// 1 s of the scene with Dormand–Prince and the collision pass, continued from the developed state.
void BM_SphLarvaRun(benchmark::State& state) {
  const sph::RunSettings rs = larva_settings(1.0);
  std::int64_t steps = 0, evaluations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sph::Scene s = developed_scene(static_cast<int>(state.range(0)));
    state.ResumeTiming();
    const sph::RunResult r = sph::run(s, rs, keep_going);
    steps = r.statistics.steps;
    evaluations = r.statistics.function_evaluations;
    benchmark::DoNotOptimize(s.position.data());
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK(BM_SphLarvaRun)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

}  // namespace
