// Rendering-pipeline benchmarks (docs/rendering.md):
//  - BM_GeometryFrame/<latitude samples>/<disc points>: one frame of geometry from a 21-point slice
//    (resample, extrapolate, all three noises, normals twice, tentacle tubes).
//  - BM_RenderFrame/<width>/<multisampling>: one frame drawn offscreen (EGL surfaceless, Mesa
//    llvmpipe) at width × (3/4 width) and read back into memory, default resolution mesh.
#include <benchmark/benchmark.h>

#include <string>

#include "geometry/extrapolation.hpp"
#include "geometry/synthetic_bell.hpp"
#include "render/gl_renderer.hpp"

namespace {

using namespace jellysim;

jellyfish::SliceFrame bench_slice() {
  geometry::SyntheticBell spec;
  spec.contraction = 0.5;
  spec.time_s = 1.0;
  return geometry::synthetic_bell(spec);
}

void BM_GeometryFrame(benchmark::State& state) {
  geometry::GeometrySettings s;
  s.latitude_samples = static_cast<int>(state.range(0));
  s.disc_points = static_cast<int>(state.range(1));
  const jellyfish::SliceFrame slice = bench_slice();
  const geometry::GeometryBuilder builder(s, 0.028);
  std::size_t vertices = 0;
  for (auto _ : state) {
    const geometry::FrameGeometry g = builder.build(slice);
    vertices = g.mesh.vertex_count();
    benchmark::DoNotOptimize(g.mesh.positions.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GeometryFrame)->Args({65, 64})->Args({129, 128})->Unit(benchmark::kMillisecond);

void BM_RenderFrame(benchmark::State& state) {
  std::string why;
  if (!render::offscreen_gl_available(&why)) {
    state.SkipWithError(("no offscreen OpenGL: " + why).c_str());
    return;
  }
  const int width = static_cast<int>(state.range(0));
  const geometry::FrameGeometry g = geometry::GeometryBuilder(geometry::GeometrySettings{}, 0.028).build(bench_slice());
  render::OffscreenRenderer renderer(width, width * 3 / 4, static_cast<int>(state.range(1)));
  const render::Camera camera = render::camera_looking_at({0.0, 0.01, 0.0}, {0.4, 0.2, 1.0}, 0.12, 40.0);
  for (auto _ : state) {
    const render::RgbImage image = renderer.render(g.mesh, camera, render::RenderStyle{});
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderFrame)->Args({640, 4})->Args({640, 1})->Args({320, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
