#include "sph/parallel.hpp"

#include <stdexcept>

namespace jellysim::sph {

namespace {
constexpr int kSpinIterations = 20000;  ///< ~tens of microseconds before a helper goes to sleep
}

WorkerPool::WorkerPool(int threads) {
  if (threads < 1 || threads > 64) throw std::invalid_argument("WorkerPool: threads must be in [1, 64]");
  for (int i = 1; i < threads; ++i) helpers_.emplace_back([this, i] { helper_loop(i); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
    generation_.fetch_add(1);
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

std::pair<std::size_t, std::size_t> WorkerPool::range(std::size_t n, int part) const {
  const auto parts = static_cast<std::size_t>(threads());
  const auto p = static_cast<std::size_t>(part);
  return {n * p / parts, n * (p + 1) / parts};
}

void WorkerPool::run(std::size_t n, const Body& body) {
  if (helpers_.empty() || n < 64) {  // small jobs: every part on this thread, same ranges
    for (int part = 0; part < threads(); ++part) {
      const auto [b, e] = range(n, part);
      body(b, e, part);
    }
    return;
  }
  body_ = &body;
  n_ = n;
  pending_.store(static_cast<int>(helpers_.size()));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    generation_.fetch_add(1);
  }
  wake_.notify_all();
  const auto [b, e] = range(n, 0);
  body(b, e, 0);
  while (pending_.load(std::memory_order_acquire) != 0) std::this_thread::yield();
  body_ = nullptr;
}

void WorkerPool::helper_loop(int index) {
  std::uint64_t seen = 0;
  while (true) {
    int spins = 0;
    while (generation_.load(std::memory_order_acquire) == seen && spins < kSpinIterations) ++spins;
    if (generation_.load(std::memory_order_acquire) == seen) {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return generation_.load() != seen; });
    }
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load()) return;
    const auto [b, e] = range(n_, index);
    (*body_)(b, e, index);
    pending_.fetch_sub(1, std::memory_order_release);
  }
}

}  // namespace jellysim::sph
