#pragma once
// A small persistent thread pool for the SPH particle loops. Work is split into fixed contiguous
// index ranges and every particle's sum runs in a fixed order, so results do not depend on the
// number of threads (determinism). Helpers spin briefly before sleeping, because one SPH pass over
// a few hundred particles takes only tens of microseconds.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace jellysim::sph {

class WorkerPool {
 public:
  /// threads >= 1; 1 runs everything on the caller's thread.
  explicit WorkerPool(int threads = 1);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(helpers_.size()) + 1; }
  /// Calls body(begin, end, part) on disjoint ranges covering [0, n), part = 0 .. threads() − 1;
  /// returns when all are done. Ranges depend only on n and the thread count.
  using Body = std::function<void(std::size_t, std::size_t, int)>;
  void run(std::size_t n, const Body& body);

 private:
  void helper_loop(int index);
  std::pair<std::size_t, std::size_t> range(std::size_t n, int part) const;

  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<bool> stop_{false};
  const Body* body_ = nullptr;
  std::size_t n_ = 0;
};

}  // namespace jellysim::sph
