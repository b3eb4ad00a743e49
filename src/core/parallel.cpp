#include "jellysim/core/parallel.hpp"

#include <optional>

#include "jellysim/math/median.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace jellysim {

namespace {

using Clock = std::chrono::steady_clock;
/// A helper spins this long for the next evaluation before it sleeps (an RK step asks for its
/// stages a few microseconds apart; between accepted steps come the collision pass and the
/// controller, tens of microseconds).
constexpr auto kIdleSpin = std::chrono::microseconds(200);
/// A barrier spins this long before it sleeps (phases are balanced, so the partner is usually
/// microseconds away unless the machine has descheduled it).
constexpr auto kBarrierSpin = std::chrono::microseconds(50);

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

}  // namespace

void PathChooser::record(double seconds) {
  if (in_trial()) (position_ % 2 == 0 ? parallel_times_ : serial_times_).push_back(seconds);
  if (++position_ < period_) return;
  if (!parallel_times_.empty() && !serial_times_.empty()) {
    parallel_wins_ = median(parallel_times_) <= median(serial_times_);
  }
  position_ = 0;
  parallel_times_.clear();
  serial_times_.clear();
}

namespace {
thread_local bool t_serial_threads = false;  ///< inside a SerialThreadsScope
}  // namespace

SerialThreadsScope::SerialThreadsScope() : previous_(t_serial_threads) { t_serial_threads = true; }
SerialThreadsScope::~SerialThreadsScope() { t_serial_threads = previous_; }

int resolve_threads(int threads) {
  if (threads >= 1) return threads;
  if (t_serial_threads) return 1;
  const unsigned cores = std::thread::hardware_concurrency();
  return static_cast<int>(std::clamp<unsigned>(cores, 1, 64));
}

WorkerPool::WorkerPool(int threads) {
  if (threads < 1 || threads > 64) throw std::invalid_argument("WorkerPool: threads must be in [1, 64]");
  for (int i = 1; i < threads; ++i) helpers_.emplace_back([this, i] { helper_loop(i); });
}

WorkerPool::~WorkerPool() {
  stop_.store(true);
  generation_.fetch_add(1);
  generation_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

std::pair<std::size_t, std::size_t> WorkerPool::range(std::size_t n, int part) const {
  const auto parts = static_cast<std::size_t>(threads());
  const auto p = static_cast<std::size_t>(part);
  return {n * p / parts, n * (p + 1) / parts};
}

void WorkerPool::run_phases(std::span<const Phase> phases, bool parallel) { run_phases(phases, {}, parallel); }

void WorkerPool::run_phases(std::span<const Phase> phases, std::span<const Gate> gates, bool parallel) {
  if (!gates.empty() && gates.size() != phases.size()) {
    throw std::invalid_argument("WorkerPool::run_phases: one gate per phase (or none)");
  }
  if (helpers_.empty() || !parallel) {  // same parts, one after another on this thread
    for (std::size_t k = 0; k < phases.size(); ++k) {
      if (!gates.empty() && gates[k] && !gates[k]()) continue;
      for (int part = 0; part < threads(); ++part) phases[k](part);
    }
    return;
  }
  phases_ = phases;
  gates_ = gates;
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();  // no system call unless a helper sleeps
  run_my_phases(0);  // ends with a barrier that every helper has passed its last phase
  if (failed_.load()) {
    failed_.store(false);
    std::rethrow_exception(std::exchange(error_, nullptr));
  }
}

void WorkerPool::run(std::size_t n, const Body& body) {
  const Phase phase = [&](int part) {
    const auto [b, e] = range(n, part);
    body(b, e, part);
  };
  run_phases(std::span<const Phase>(&phase, 1), n >= 64);
}

void WorkerPool::run_tasks(std::size_t n, const Task& task) {
  std::atomic<std::size_t> next{0};
  const bool side_by_side = n > 1 && threads() > 1;
  const Phase phase = [&](int) {
    std::optional<SerialThreadsScope> serial;
    if (side_by_side) serial.emplace();
    for (std::size_t k = next++; k < n; k = next++) task(k);
  };
  run_phases(std::span<const Phase>(&phase, 1), n > 1);
}

void WorkerPool::run_my_phases(int part) {
  // Read once: after the last barrier the caller may already be setting up the next run.
  const std::span<const Phase> phases = phases_;
  const std::span<const Gate> gates = gates_;
  for (std::size_t k = 0; k < phases.size(); ++k) {
    if (!gates.empty() && gates[k] && !gates[k]()) continue;  // every thread skips it alike
    try {
      phases[k](part);
    } catch (...) {  // keep to the barriers, or the other threads would wait forever
      if (!failed_.exchange(true)) error_ = std::current_exception();
    }
    barrier();
  }
}

namespace {

/// Spins on `word` while it equals `old` for up to `spin`, then sleeps on it (futex) until it changes.
void wait_while_equal(const std::atomic<std::uint32_t>& word, std::uint32_t old, std::chrono::microseconds spin) {
  const auto deadline = Clock::now() + spin;
  for (int spins = 1; word.load(std::memory_order_acquire) == old; ++spins) {
    if ((spins & 63) == 0 && Clock::now() > deadline) {
      word.wait(old, std::memory_order_acquire);
    } else {
      cpu_relax();
    }
  }
}

}  // namespace

// Sense by generation: the last thread to arrive resets the count and bumps the generation.
void WorkerPool::barrier() {
  const std::uint32_t generation = barrier_generation_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads()) {
    arrived_.store(0, std::memory_order_relaxed);
    barrier_generation_.fetch_add(1, std::memory_order_release);
    barrier_generation_.notify_all();
    return;
  }
  wait_while_equal(barrier_generation_, generation, kBarrierSpin);
}

void WorkerPool::wait_for_work(std::uint32_t seen) { wait_while_equal(generation_, seen, kIdleSpin); }

void WorkerPool::helper_loop(int part) {
  std::uint32_t seen = 0;
  while (true) {
    wait_for_work(seen);
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load()) return;
    run_my_phases(part);
  }
}

SerialWorker::SerialWorker(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)), thread_([this] { loop(); }) {}

SerialWorker::~SerialWorker() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return jobs_.empty() && !busy_; });
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void SerialWorker::rethrow_failure() {
  if (!failure_) return;
  std::exception_ptr failure = failure_;
  failure_ = nullptr;
  std::rethrow_exception(failure);
}

void SerialWorker::submit(std::function<void()> job) {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return jobs_.size() < capacity_ || failure_; });
    rethrow_failure();
    jobs_.push_back(std::move(job));
  }
  changed_.notify_all();
}

void SerialWorker::drain() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return (jobs_.empty() && !busy_) || failure_; });
  rethrow_failure();
}

void SerialWorker::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, nothing left
    std::function<void()> job = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
    lock.unlock();
    std::exception_ptr error;
    try {
      job();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    busy_ = false;
    if (error && !failure_) {
      failure_ = error;
      jobs_.clear();  // the rest would write after a missing file
    }
    changed_.notify_all();
  }
}

}  // namespace jellysim
