#pragma once
// PLplot keeps its streams in process-wide state and is not thread-safe: two charts drawn at once
// (e.g. the runs of `jellysim batch` on threads) corrupt each other. Every PLplot session holds
// this lock from before its plstream is made until after it is destroyed.
#include <mutex>

namespace jellysim::render {

inline std::mutex& plplot_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace jellysim::render
