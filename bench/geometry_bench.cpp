// Rendering-pipeline benchmarks (docs/rendering.md, "Measured figures"; issue 5's target: geometry
// plus rendering at ≥ 60 frames/s on one core). Every benchmark reports wall time and the CPU time
// of the whole process (all threads, llvmpipe's rasteriser threads included), so "CPU" is the cost
// on one core whatever LP_NUM_THREADS is.
//  - BM_GeometryFrame/lat/disc: one frame of geometry from a 21-point slice (resample, extrapolate,
//    all three noises, normals twice, tentacle tubes) into a reused FrameGeometry (the interactive
//    path: no allocation of the mesh arrays).
//  - BM_GeometryFrameFresh/lat/disc: the same, returning a new FrameGeometry each frame.
//  - BM_RenderFrame/width/samples/per_vertex/readback: one frame drawn offscreen (EGL surfaceless,
//    Mesa llvmpipe) at width × (3/4 width) with `samples` × multisampling (1: none), per-pixel (0) or
//    per-vertex (1) lighting; readback 1: resolved and read into a reused RgbImage, 0: drawn and
//    waited for (glFinish) only. Default resolution mesh.
//  - BM_InteractiveFrame/width/samples/per_vertex: geometry + render + readback per frame of a
//    contracting, ageing slice sequence (the noise changes every frame), what a real-time viewer
//    does; 640/1/1 is the interactive setting of docs/rendering.md.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/render/gl_renderer.hpp"

namespace {

using namespace jellysim;

jellyfish::SliceFrame bench_slice(double contraction = 0.5, double time_s = 1.0) {
  geometry::SyntheticBell spec;
  spec.contraction = contraction;
  spec.time_s = time_s;
  return geometry::synthetic_bell(spec);
}

/// One contraction cycle of 30 frames at 30 frames/s.
std::vector<jellyfish::SliceFrame> bench_sequence() {
  std::vector<jellyfish::SliceFrame> frames;
  for (int k = 0; k < 30; ++k) frames.push_back(bench_slice(0.5 - 0.5 * std::cos(2.0 * 3.14159265358979 * k / 30), 1.0 + k / 30.0));
  return frames;
}

const render::Camera& bench_camera() {
  static const render::Camera camera = render::camera_looking_at({0.0, 0.01, 0.0}, {0.4, 0.2, 1.0}, 0.12, 40.0);
  return camera;
}

bool skip_without_gl(benchmark::State& state) {
  std::string why;
  if (render::offscreen_gl_available(&why)) return false;
  state.SkipWithError(("no offscreen OpenGL: " + why).c_str());
  return true;
}

void frame_rate(benchmark::State& state) {
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

geometry::GeometrySettings geometry_settings(const benchmark::State& state) {
  geometry::GeometrySettings s;
  s.latitude_samples = static_cast<int>(state.range(0));
  s.disc_points = static_cast<int>(state.range(1));
  return s;
}

void BM_GeometryFrame(benchmark::State& state) {
  const jellyfish::SliceFrame slice = bench_slice();
  const geometry::GeometryBuilder builder(geometry_settings(state), 0.028);
  geometry::FrameGeometry g;
  for (auto _ : state) {
    builder.build(slice, g);
    benchmark::DoNotOptimize(g.mesh.positions.data());
  }
  state.counters["vertices"] = static_cast<double>(g.mesh.vertex_count());
  frame_rate(state);
}
BENCHMARK(BM_GeometryFrame)->Args({65, 64})->Args({129, 128})->ArgNames({"lat", "disc"})
    ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_GeometryFrameFresh(benchmark::State& state) {
  const jellyfish::SliceFrame slice = bench_slice();
  const geometry::GeometryBuilder builder(geometry_settings(state), 0.028);
  for (auto _ : state) {
    const geometry::FrameGeometry g = builder.build(slice);
    benchmark::DoNotOptimize(g.mesh.positions.data());
  }
  frame_rate(state);
}
BENCHMARK(BM_GeometryFrameFresh)->Args({65, 64})->ArgNames({"lat", "disc"})
    ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

render::RenderStyle style_of(const benchmark::State& state, int arg) {
  render::RenderStyle style;
  style.per_vertex_lighting = state.range(arg) != 0;
  return style;
}

void BM_RenderFrame(benchmark::State& state) {
  if (skip_without_gl(state)) return;
  const int width = static_cast<int>(state.range(0));
  const render::RenderStyle style = style_of(state, 2);
  const bool readback = state.range(3) != 0;
  const geometry::FrameGeometry g = geometry::GeometryBuilder(geometry::GeometrySettings{}, 0.028).build(bench_slice());
  render::OffscreenRenderer renderer(width, width * 3 / 4, static_cast<int>(state.range(1)));
  render::RgbImage image;
  for (auto _ : state) {
    if (readback) {
      renderer.render(g.mesh, bench_camera(), style, image);
    } else {
      renderer.draw(g.mesh, bench_camera(), style);
      renderer.finish();
    }
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["samples"] = renderer.samples();
  frame_rate(state);
}
BENCHMARK(BM_RenderFrame)
    ->ArgNames({"width", "samples", "per_vertex", "readback"})
    ->Args({640, 4, 0, 1})->Args({640, 4, 0, 0})
    ->Args({640, 1, 0, 1})->Args({640, 1, 0, 0})
    ->Args({640, 1, 1, 1})->Args({640, 1, 1, 0})
    ->Args({320, 1, 0, 1})
    ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_InteractiveFrame(benchmark::State& state) {
  if (skip_without_gl(state)) return;
  const int width = static_cast<int>(state.range(0));
  const render::RenderStyle style = style_of(state, 2);
  const std::vector<jellyfish::SliceFrame> frames = bench_sequence();
  const geometry::GeometryBuilder builder(geometry::GeometrySettings{}, 0.028);
  render::OffscreenRenderer renderer(width, width * 3 / 4, static_cast<int>(state.range(1)));
  geometry::FrameGeometry g;
  render::RgbImage image;
  std::size_t k = 0;
  for (auto _ : state) {
    builder.build(frames[k++ % frames.size()], g);
    renderer.render(g.mesh, bench_camera(), style, image);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  frame_rate(state);
}
BENCHMARK(BM_InteractiveFrame)
    ->ArgNames({"width", "samples", "per_vertex"})
    ->Args({640, 1, 1})->Args({640, 1, 0})->Args({640, 4, 0})
    ->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace
