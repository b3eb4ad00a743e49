#pragma once
// Shared by the rendering tests (tests/render, tests/experiments): skip where no offscreen OpenGL device
// exists, and a fresh scratch directory per process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "jellysim/geometry/synthetic_bell.hpp"
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

/// `count` synthetic slices at 30 frames/s: frame k contracted by contraction_step · k, its
/// aperture moved by k · move_per_frame_m (m).
inline std::vector<jellyfish::SliceFrame> synthetic_stroke(int count, double contraction_step,
                                                           Vec2 move_per_frame_m = {0.0, 0.0}) {
  std::vector<jellyfish::SliceFrame> frames;
  for (int k = 0; k < count; ++k) {
    geometry::SyntheticBell spec;
    spec.contraction = contraction_step * k;
    spec.time_s = k / 30.0;
    spec.aperture_centre_m = spec.aperture_centre_m + static_cast<double>(k) * move_per_frame_m;
    frames.push_back(geometry::synthetic_bell(spec));
  }
  return frames;
}

}  // namespace jellysim::render::testing
