// The project's thread pool (core/parallel.hpp): dynamic task scheduling for independent jobs.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "jellysim/core/parallel.hpp"

namespace {

using jellysim::WorkerPool;

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
      for (int i = 0; i < 200; ++i) x = 0.5 * x + 1.0 / (1.0 + x);  // uneven-free work that depends on k only
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
