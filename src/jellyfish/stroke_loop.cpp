#include "jellysim/jellyfish/stroke_loop.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/sim/frame_clock.hpp"

namespace jellysim::jellyfish {

int frames_per_cycle(double rate_hz, double frequency_hz) {
  return std::max(1, static_cast<int>(std::lround(rate_hz / frequency_hz)));
}

SwimSettings loop_search_settings(SwimSettings settings, const LoopSettings& loop) {
  if (settings.school.size() != 1 || !settings.obstacles.empty() || !settings.structures.empty())
    throw InputError("field 'render.loop' = true needs a scene with one jellyfish and nothing else in the tank (this "
                     "one has " + std::to_string(settings.school.size()) + " jellyfish, " +
                     std::to_string(settings.obstacles.size()) + " obstacles and " +
                     std::to_string(settings.structures.size()) + " IB2d structures)");
  if (loop.cycles >= loop.max_cycles)
    throw InputError("field 'render.loop_cycles' = " + std::to_string(loop.cycles) +
                     " must be below render.loop_max_cycles = " + std::to_string(loop.max_cycles) +
                     " (the loop starts at cycle 1 at the earliest and closes by render.loop_max_cycles)");
  const double f = settings.jellyfish().frequency_hz;
  const double asked = settings.frames_per_second > 0.0 ? settings.frames_per_second : 1.0 / settings.frame_interval_s;
  const int per_cycle = frames_per_cycle(asked, f);
  settings.frames_per_second = per_cycle * f;
  settings.frame_interval_s = 1.0 / settings.frames_per_second;
  const auto last_frame = static_cast<double>(loop.max_cycles * per_cycle + 1);
  settings.duration_s = last_frame / settings.frames_per_second;
  return settings;
}

Vec2 umbrella_centroid(const SliceFrame& frame) {
  Vec2 sum{};
  for (const Vec2& p : frame.umbrella) sum += p;
  return sum / static_cast<double>(frame.umbrella.size());
}

namespace {

Vec2 centroid_velocity(const std::vector<SliceFrame>& frames, std::size_t k) {
  if (k == 0 || k + 1 >= frames.size()) throw std::out_of_range("stroke_mismatch: a frame without both neighbours");
  const SliceFrame& before = frames[k - 1];
  const SliceFrame& after = frames[k + 1];
  return (umbrella_centroid(after) - umbrella_centroid(before)) / (after.time_s - before.time_s);
}

}  // namespace

StrokeMismatch stroke_mismatch(const std::vector<SliceFrame>& frames, std::size_t a, std::size_t b,
                               double diameter_m, double frequency_hz) {
  const SliceFrame& fa = frames.at(a);
  const SliceFrame& fb = frames.at(b);
  if (fa.umbrella.size() != fb.umbrella.size() || fa.umbrella.empty())
    throw std::invalid_argument("stroke_mismatch: umbrellas of different point counts");
  const Vec2 ca = umbrella_centroid(fa), cb = umbrella_centroid(fb);
  double sum = 0.0;
  for (std::size_t i = 0; i < fa.umbrella.size(); ++i) sum += norm_squared((fb.umbrella[i] - cb) - (fa.umbrella[i] - ca));
  StrokeMismatch m;
  m.shape = std::sqrt(sum / static_cast<double>(fa.umbrella.size())) / diameter_m;
  m.speed = norm(centroid_velocity(frames, b) - centroid_velocity(frames, a)) / (diameter_m * frequency_hz);
  return m;
}

const StrokeMismatch* LoopSearch::loop_check() const {
  if (checked.empty()) return nullptr;
  if (periodic_cycle > 0) return &checked.back();
  return &*std::min_element(checked.begin(), checked.end(),
                            [](const StrokeMismatch& x, const StrokeMismatch& y) { return x.largest() < y.largest(); });
}

int LoopSearch::start_cycle() const {
  const StrokeMismatch* check = loop_check();
  return check ? check->cycle - cycles : 0;
}

bool LoopSearch::recorded(std::size_t frames, int frames_per_cycle) const {
  if (periodic_cycle == 0) return false;
  return frames >= static_cast<std::size_t>(periodic_cycle * frames_per_cycle) + 2;
}

LoopSearch search_loop(const std::vector<SliceFrame>& frames, int frames_per_cycle, const LoopSettings& loop,
                       double diameter_m, double frequency_hz) {
  LoopSearch s;
  s.cycles = loop.cycles;
  const auto per_cycle = static_cast<std::size_t>(frames_per_cycle);
  for (int c = loop.cycles + 1; c <= loop.max_cycles && static_cast<std::size_t>(c) * per_cycle + 1 < frames.size();
       ++c) {
    StrokeMismatch m = stroke_mismatch(frames, static_cast<std::size_t>(c - loop.cycles) * per_cycle,
                                       static_cast<std::size_t>(c) * per_cycle, diameter_m, frequency_hz);
    m.cycle = c;
    s.checked.push_back(m);
    if (m.largest() <= loop.tolerance) {
      s.periodic_cycle = c;
      break;
    }
  }
  return s;
}

LoopClip cut_loop(const std::vector<SliceFrame>& frames, std::size_t first, std::size_t count, double rate_hz,
                  RootMotion root_motion, double diameter_m, double frequency_hz) {
  if (count == 0 || first == 0 || first + count + 1 >= frames.size())
    throw std::out_of_range("cut_loop: the loop and its neighbouring frames are not all recorded");
  LoopClip clip;
  clip.first_frame = first;
  clip.closure = stroke_mismatch(frames, first, first + count, diameter_m, frequency_hz);
  clip.travel = umbrella_centroid(frames[first + count]) - umbrella_centroid(frames[first]);
  const sim::FrameClock clock = sim::FrameClock::at_rate(rate_hz, static_cast<double>(count) / rate_hz, 0.0,
                                                         sim::FrameClock::Ending::nearest_frame);
  clip.duration_s = clock.frame_time(static_cast<std::int64_t>(count));
  for (std::size_t i = 0; i <= count; ++i) {
    SliceFrame f = frames[first + i];
    f.time_s = clock.frame_time(static_cast<std::int64_t>(i));
    if (root_motion == RootMotion::remove) {
      const Vec2 shift = -(static_cast<double>(i) / static_cast<double>(count)) * clip.travel;
      for (Vec2& p : f.umbrella) p += shift;
      for (auto& tentacle : f.tentacles)
        for (Vec2& p : tentacle) p += shift;
    }
    clip.frames.push_back(std::move(f));
  }
  return clip;
}

}  // namespace jellysim::jellyfish
