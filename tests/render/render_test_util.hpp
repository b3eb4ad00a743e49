#pragma once
// Shared by the rendering tests (tests/render, tests/experiments): skip where no offscreen OpenGL device
// exists, and a fresh scratch directory per process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "jellysim/render/gl_renderer.hpp"

namespace jellysim::render::testing {

#define REQUIRE_OFFSCREEN_GL()                                                               \
  do {                                                                                       \
    std::string why;                                                                         \
    if (!offscreen_gl_available(&why)) GTEST_SKIP() << "no offscreen OpenGL device: " << why; \
  } while (0)

inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("jellysim_test_render_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace jellysim::render::testing
