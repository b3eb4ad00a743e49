#pragma once
// PLplot keeps its streams in process-wide state and is not thread-safe: two charts drawn at once
// (e.g. the runs of `jellysim batch` on threads) corrupt each other. Every PLplot session holds
// this lock from before its plstream is made until after it is destroyed.
#include <plplot/plstream.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::render {

inline std::mutex& plplot_mutex() {
  static std::mutex m;
  return m;
}

/// A PNG drawn by PLplot's pngcairo device into memory (open_memstream), returned as its bytes:
/// the caller writes them through its own file (never a file PLplot opens by name).
/// `draw(pls)` sets the page up, calls pls.init() and draws; nothing before init() may throw
/// (from init() on, the stream owns the memory file and closes it when it ends).
template <class Draw>
std::string plplot_png(Draw&& draw) {
  char* data = nullptr;
  std::size_t size = 0;
  std::FILE* memory = ::open_memstream(&data, &size);
  if (memory == nullptr) throw RunError("cannot draw a PNG: " + io::os_reason(errno));
  try {
    const std::lock_guard<std::mutex> lock(plplot_mutex());
    plstream pls;
    pls.sdev("pngcairo");
    pls.sfile(memory);
    draw(pls);
  } catch (...) {  // the stream has ended and closed the memory file
    std::free(data);
    throw;
  }
  std::string bytes(data, size);
  std::free(data);
  return bytes;
}

}  // namespace jellysim::render
