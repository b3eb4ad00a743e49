#pragma once
// The project's one thread pool: a small persistent pool of threads. Its first user is the SPH force
// evaluation, a fixed sequence of phases (load + mirrors, grid, density, forces): every thread runs
// each phase for its own part
// (fixed contiguous index ranges) and a spin barrier separates the phases, so a whole evaluation
// costs one hand-off and a few barriers. Every particle's sum is computed by one thread in a fixed
// order, so results do not depend on the number of threads (determinism). Waiting threads spin
// briefly, then sleep on the atomic (futex): one evaluation of a few hundred particles takes only
// tens of microseconds and the integrator asks for the next one a few microseconds later, but on a
// machine busy with other work a spinning thread would only steal time from its partner.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <cstdint>
#include <exception>
#include <functional>
#include <span>
#include <thread>
#include <utility>
#include <vector>

namespace jellysim {

/// The number of threads a `threads` setting asks for: itself when >= 1, all cores
/// (std::thread::hardware_concurrency, at least 1, at most 64) when 0 — or 1 when 0 is asked on
/// a thread inside a SerialThreadsScope (a task of a parallel sweep or batch already has its core).
int resolve_threads(int threads);

/// While alive, resolve_threads(0) on this thread gives 1: work that is itself one of several run
/// side by side (WorkerPool::run_tasks on several threads, an MPI rank) does not spread further.
class SerialThreadsScope {
 public:
  SerialThreadsScope();
  ~SerialThreadsScope();
  SerialThreadsScope(const SerialThreadsScope&) = delete;
  SerialThreadsScope& operator=(const SerialThreadsScope&) = delete;

 private:
  bool previous_;
};

class WorkerPool {
 public:
  /// threads in [1, 64]; 1 runs everything on the caller's thread. Throws std::invalid_argument.
  explicit WorkerPool(int threads = 1);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(helpers_.size()) + 1; }
  /// The contiguous part `part` of [0, n): [n p / P, n (p + 1) / P) for P = threads().
  std::pair<std::size_t, std::size_t> range(std::size_t n, int part) const;

  /// One phase: called with each part 0 .. threads() − 1 exactly once.
  using Phase = std::function<void(int part)>;
  /// Runs the phases in order; no part starts phase k + 1 before every part finished phase k.
  /// With `parallel` false (or one thread) the caller runs every part of each phase in turn, which
  /// gives the same results. Returns when all phases are done. An exception thrown by a phase is
  /// rethrown here once every thread has finished (the first one caught; later phases still run).
  void run_phases(std::span<const Phase> phases, bool parallel = true);
  /// A phase's gate, asked by every thread just before the phase (after the previous barrier):
  /// false skips the phase and its barrier. It must give every thread the same answer, so it may
  /// read only data final before that barrier (and write nothing), and must not throw.
  using Gate = std::function<bool()>;
  /// As above; `gates[k]` (when non-empty) decides whether phase k runs. gates.size() == phases.size().
  void run_phases(std::span<const Phase> phases, std::span<const Gate> gates, bool parallel = true);

  /// Calls body(begin, end, part) on the ranges of [0, n) (a single phase; serial when n < 64).
  using Body = std::function<void(std::size_t, std::size_t, int)>;
  void run(std::size_t n, const Body& body);

  /// Runs task(k) for k = 0 .. n − 1, each exactly once, the threads taking the next task as they
  /// finish one (for independent jobs of uneven length, e.g. the runs of a sweep). A task's result
  /// must depend on k alone, so the results do not depend on the number of threads.
  using Task = std::function<void(std::size_t k)>;
  void run_tasks(std::size_t n, const Task& task);

 private:
  void helper_loop(int part);
  void wait_for_work(std::uint32_t seen);
  void run_my_phases(int part);
  void barrier();

  std::vector<std::thread> helpers_;
  alignas(64) std::atomic<std::uint32_t> generation_{0};  ///< bumped once per run_phases call
  std::atomic<bool> stop_{false};
  std::span<const Phase> phases_;
  std::span<const Gate> gates_;
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};
  // Spin barrier state, on its own cache line.
  alignas(64) std::atomic<int> arrived_{0};
  alignas(64) std::atomic<std::uint32_t> barrier_generation_{0};
};

/// Chooses between running a repeated parallel job on all threads or serially, by timing both now
/// and then (the results are the same either way). On a machine busy with other work, a thread
/// waiting at a barrier for a descheduled partner makes the parallel path slower than one thread;
/// then the serial path wins until the next trial. The parallel path runs first; the last
/// 2 × `trials` jobs of every `period` alternate between the paths, and the path with the shorter
/// median job decides the next period (a median, not a total: on a shared machine one job stalled by
/// a descheduled thread would otherwise hand a whole period to the slower path).
class PathChooser {
 public:
  explicit PathChooser(int period = 512, int trials = 8) : period_(period), trials_(trials) {
    parallel_times_.reserve(static_cast<std::size_t>(trials));
    serial_times_.reserve(static_cast<std::size_t>(trials));
  }
  /// Whether the next job should run in parallel.
  bool parallel() const { return in_trial() ? position_ % 2 == 0 : parallel_wins_; }
  /// Records the wall time (s) of the job just run on the path parallel() chose.
  void record(double seconds);

 private:
  bool in_trial() const { return position_ >= period_ - 2 * trials_; }

  int period_, trials_, position_ = 0;
  bool parallel_wins_ = true;
  std::vector<double> parallel_times_, serial_times_;  ///< the current trial's jobs
};

/// One background thread that runs jobs in the order they were submitted, while the submitter goes
/// on: e.g. a run's per-frame files written while the simulation computes the next frame (issue
/// 34). At most `capacity` jobs wait; submit() blocks while the queue is full, so a slow writer
/// slows the producer instead of filling memory. The first exception a job throws is rethrown by
/// the next submit() or drain() (the jobs after it are dropped); the destructor drains without
/// throwing, so what was submitted before an error elsewhere is still written.
class SerialWorker {
 public:
  explicit SerialWorker(std::size_t capacity = 2);
  ~SerialWorker();
  SerialWorker(const SerialWorker&) = delete;
  SerialWorker& operator=(const SerialWorker&) = delete;

  void submit(std::function<void()> job);
  /// Returns when every job submitted so far has run; rethrows the first exception one threw.
  void drain();

 private:
  void loop();
  void rethrow_failure();

  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> jobs_;
  bool busy_ = false;  ///< a job is running
  bool stop_ = false;
  std::exception_ptr failure_;
  std::thread thread_;  ///< last: started once the rest is ready
};

}  // namespace jellysim
