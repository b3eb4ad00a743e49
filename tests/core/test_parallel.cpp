// The project's thread pool (core/parallel.hpp): dynamic task scheduling for independent jobs.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <stdexcept>
#include <vector>

#include "jellysim/core/parallel.hpp"

namespace {

using jellysim::WorkerPool;

// Dynamic scheduling: task 0 waits until every other task has run, which only works when the other
// threads take the remaining tasks while it waits (a static split would leave half of them behind
// task 0 and time out).
TEST(WorkerPool, RunTasksHandsTheNextTaskToWhicheverThreadIsFree) {
  const std::size_t n = 40;
  WorkerPool pool(2);
  std::atomic<std::size_t> done{0};
  bool others_finished_first = false;
  pool.run_tasks(n, [&](std::size_t k) {
    if (k == 0) {
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (done.load() < n - 1 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
      others_finished_first = done.load() == n - 1;
    }
    ++done;
  });
  EXPECT_TRUE(others_finished_first);
  EXPECT_EQ(done.load(), n);
}

TEST(WorkerPool, RunTasksRunsEveryTaskOnceWhateverTheThreadCount) {
  const std::size_t n = 1000;
  std::vector<double> reference;
  for (int threads : {1, 2, 3, 8}) {
    WorkerPool pool(threads);
    std::vector<std::atomic<int>> calls(n);
    std::vector<double> results(n, 0.0);
    pool.run_tasks(n, [&](std::size_t k) {
      ++calls[k];
      double x = static_cast<double>(k);
      for (std::size_t i = 0; i < 50 + 3 * (k % 7); ++i) x = 0.5 * x + 1.0 / (1.0 + x);  // uneven work; depends on k only
      results[k] = x;
    });
    for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(calls[k].load(), 1) << "task " << k << ", " << threads << " threads";
    if (reference.empty()) reference = results;
    EXPECT_EQ(results, reference) << threads << " threads";
  }
}

TEST(WorkerPool, RunTasksWithNoTasksOrOneTaskAndAnErrorReachesTheCaller) {
  WorkerPool pool(3);
  int ran = 0;
  pool.run_tasks(0, [&](std::size_t) { ++ran; });
  EXPECT_EQ(ran, 0);
  pool.run_tasks(1, [&](std::size_t) { ++ran; });
  EXPECT_EQ(ran, 1);
  EXPECT_THROW(pool.run_tasks(50, [](std::size_t k) { if (k == 17) throw std::runtime_error("task 17"); }),
               std::runtime_error);
  // The pool is still usable afterwards.
  std::atomic<int> count{0};
  pool.run_tasks(100, [&](std::size_t) { ++count; });
  EXPECT_EQ(count.load(), 100);
}

}  // namespace

namespace jellysim {
namespace {

TEST(WorkerPool, PhasesRunInOrderForEveryPartAndErrorsReachTheCaller) {
  for (int threads : {1, 2, 3}) {
    WorkerPool pool(threads);
    std::vector<int> first(static_cast<std::size_t>(threads), -1), second(static_cast<std::size_t>(threads), -1);
    int total = 0;
    const std::array<WorkerPool::Phase, 2> phases{
        WorkerPool::Phase([&](int part) { first[static_cast<std::size_t>(part)] = part; }),
        // Sees every part's first phase: the barrier separates the phases.
        WorkerPool::Phase([&](int part) {
          int sum = 0;
          for (int v : first) sum += v;
          second[static_cast<std::size_t>(part)] = sum;
          if (part == 0) total = sum;
        })};
    for (bool parallel : {true, false}) {
      pool.run_phases(phases, parallel);
      EXPECT_EQ(total, threads * (threads - 1) / 2);
      for (int v : second) EXPECT_EQ(v, total);
    }
    const std::array<WorkerPool::Phase, 1> failing{WorkerPool::Phase([&](int part) {
      if (part == threads - 1) throw std::runtime_error("phase failed");
    })};
    EXPECT_THROW(pool.run_phases(failing), std::runtime_error) << threads << " threads";
    pool.run_phases(phases);  // still usable
    EXPECT_EQ(total, threads * (threads - 1) / 2);
  }
  EXPECT_THROW(WorkerPool(0), std::invalid_argument);
  EXPECT_EQ(resolve_threads(3), 3);
  EXPECT_GE(resolve_threads(0), 1);
}

}  // namespace
}  // namespace jellysim

namespace jellysim {
namespace {

/// Runs one period of the chooser with the given times per path; returns the jobs run in parallel.
int run_period(PathChooser& chooser, int period, double parallel_s, double serial_s) {
  int parallel = 0;
  for (int k = 0; k < period; ++k) {
    const bool p = chooser.parallel();
    parallel += p ? 1 : 0;
    chooser.record(p ? parallel_s : serial_s);
  }
  return parallel;
}

TEST(PathChooser, FollowsTheFasterPathAndKeepsTrying) {
  PathChooser chooser(64, 4);
  EXPECT_EQ(run_period(chooser, 64, 3.0, 1.0), 56 + 4);  // parallel first; the trial finds serial faster
  EXPECT_EQ(run_period(chooser, 64, 3.0, 1.0), 4);       // serial but for the trial's parallel jobs
  EXPECT_EQ(run_period(chooser, 64, 1.0, 2.0), 4);       // the trial finds parallel faster again
  EXPECT_EQ(run_period(chooser, 64, 1.0, 2.0), 60);
}

TEST(PathChooser, OneStalledJobDoesNotDecideTheTrial) {
  PathChooser chooser(16, 4);
  int parallel = 0, trial_job = 0;
  for (int k = 0; k < 16; ++k) {
    const bool p = chooser.parallel();
    parallel += p ? 1 : 0;
    // Parallel jobs take 1 s and serial ones 2 s, but the first parallel trial job stalls for 100 s:
    // a total would pick the serial path, the median keeps the parallel one.
    const bool stalled = p && k >= 8 && trial_job++ == 0;
    chooser.record(stalled ? 100.0 : (p ? 1.0 : 2.0));
  }
  EXPECT_EQ(parallel, 8 + 4);
  EXPECT_EQ(run_period(chooser, 16, 1.0, 2.0), 8 + 4);  // still parallel outside the trial
}

}  // namespace

// A task run side by side with others (a pool of several threads) has its core: all cores (0)
// resolves to one thread there, and again to all cores after; an explicit count is kept.
TEST(WorkerPool, TasksRunSideBySideResolveAllCoresToOne) {
  const int all = resolve_threads(0);
  std::vector<int> seen(4, -1), explicit_count(4, -1);
  WorkerPool pool(2);
  pool.run_tasks(seen.size(), [&](std::size_t k) {
    seen[k] = resolve_threads(0);
    explicit_count[k] = resolve_threads(3);
  });
  for (std::size_t k = 0; k < seen.size(); ++k) {
    EXPECT_EQ(seen[k], 1);
    EXPECT_EQ(explicit_count[k], 3);
  }
  EXPECT_EQ(resolve_threads(0), all);
  {
    const SerialThreadsScope scope;
    EXPECT_EQ(resolve_threads(0), 1);
  }
  EXPECT_EQ(resolve_threads(0), all);
}

}  // namespace jellysim
