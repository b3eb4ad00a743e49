// SerialWorker (core/parallel.hpp): jobs run in submission order on one background thread, at
// most `capacity` wait, a job's exception comes back through submit() or drain(), and the
// destructor runs what was submitted.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "jellysim/core/parallel.hpp"

namespace jellysim {
namespace {

TEST(SerialWorker, RunsJobsInTheOrderTheyWereSubmitted) {
  std::vector<int> order;  // written by the worker only, read after drain()
  SerialWorker worker(2);
  for (int k = 0; k < 100; ++k) worker.submit([&order, k] { order.push_back(k); });
  worker.drain();
  ASSERT_EQ(order.size(), 100u);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(order[static_cast<std::size_t>(k)], k);
}

TEST(SerialWorker, SubmitWaitsWhileTheQueueIsFull) {
  std::atomic<bool> started{false}, release{false};
  std::atomic<int> done{0};
  SerialWorker worker(1);
  worker.submit([&] {
    started.store(true);
    while (!release.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ++done;
  });
  while (!started.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the worker holds it
  worker.submit([&] { ++done; });  // waits in the queue (capacity 1)
  std::atomic<bool> third_submitted{false};
  std::thread producer([&] {
    worker.submit([&] { ++done; });
    third_submitted.store(true);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(third_submitted.load()) << "the queue was full: submit() must wait";
  release.store(true);
  producer.join();
  worker.drain();
  EXPECT_EQ(done.load(), 3);
}

TEST(SerialWorker, AJobsErrorComesBackAndTheJobsAfterItAreDropped) {
  std::atomic<int> ran{0};
  std::atomic<bool> go{false};
  SerialWorker worker(4);
  // The first job holds the worker until all three are queued: a failure already reported would
  // make the third submit() rethrow it.
  worker.submit([&] {
    while (!go.load()) std::this_thread::yield();
    ++ran;
  });
  worker.submit([] { throw std::runtime_error("cannot write frames/field_000001.vti"); });
  worker.submit([&] { ++ran; });
  go.store(true);
  try {
    worker.drain();
    FAIL() << "drain() must rethrow";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write frames/field_000001.vti");
  }
  EXPECT_EQ(ran.load(), 1);  // the job after the failing one never ran
  worker.submit([&] { ran += 10; });  // reported once: the worker goes on
  worker.drain();
  EXPECT_EQ(ran.load(), 11);
}

TEST(SerialWorker, TheDestructorRunsWhatWasSubmitted) {
  std::atomic<int> ran{0};
  {
    SerialWorker worker(8);
    for (int k = 0; k < 5; ++k)
      worker.submit([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        ++ran;
      });
  }
  EXPECT_EQ(ran.load(), 5);
}

}  // namespace
}  // namespace jellysim
