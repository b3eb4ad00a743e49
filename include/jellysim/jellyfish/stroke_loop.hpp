#pragma once
// A seamless loop of the swimming stroke (issue 39 item 3, docs/rendering.md "A seamless loop"):
// the frame rate that puts every cycle start on a frame, the periodicity check at cycle starts
// (the umbrella's shape about its centroid and the centroid's speed against the previous cycle's),
// and the cut of whole cycles with the root motion removed or kept as a constant velocity. Pure
// functions of recorded slices; no files, no pixels.
#include <vector>

#include "jellysim/jellyfish/slice_frame.hpp"
#include "jellysim/jellyfish/swim_simulation.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::jellyfish {

/// What happens to the bell's travel in a loop.
enum class RootMotion {
  remove,    ///< the travel over the loop taken out linearly: the bell swims in place, frame N = frame 0
  constant,  ///< kept: frame N = frame 0 moved by the loop's travel (a constant velocity over loops)
};

struct LoopSettings {
  bool enabled = false;
  int cycles = 1;             ///< whole contraction cycles in the loop
  double tolerance = 0.05;    ///< largest mismatch: of the bell diameter (shape), of diameter × frequency (speed)
  int max_cycles = 10;        ///< the last cycle whose start may pass the check
  RootMotion root_motion = RootMotion::remove;
};

/// Frames per contraction cycle at about `rate_hz` frames a second: round(rate / frequency), at least 1.
int frames_per_cycle(double rate_hz, double frequency_hz);

/// The swim of a loop search: frames_per_second = frames_per_cycle · frequency (every cycle start a
/// frame), the duration the cap: max_cycles cycles and one frame. Throws InputError (naming
/// render.loop) unless the scene holds exactly one jellyfish and nothing else, and (naming
/// render.loop_cycles) unless the loop is shorter than render.loop_max_cycles.
SwimSettings loop_search_settings(SwimSettings settings, const LoopSettings& loop);

/// How far two recorded states of the stroke differ.
struct StrokeMismatch {
  int cycle = 0;         ///< the later frame's cycle (its frame is cycle · frames_per_cycle)
  double shape = 0.0;    ///< RMS over the umbrella points of the positions about the centroid, / diameter
  double speed = 0.0;    ///< |centroid velocity difference| / (diameter · frequency)
  double largest() const { return shape > speed ? shape : speed; }
};

/// Frames a and b compared (each needs its neighbours: the velocity is a central difference).
StrokeMismatch stroke_mismatch(const std::vector<SliceFrame>& frames, std::size_t a, std::size_t b,
                               double diameter_m, double frequency_hz);

/// Where a loop search stands. The check is the loop's own closure: cycle c's start against the
/// start of cycle c − cycles, the loop's first, for c = cycles + 1, cycles + 2, … (the loop never
/// starts at cycle 0, which starts from rest and whose start passes falsely); the first c within the
/// tolerance closes the loop, which is cycles c − cycles … c − 1.
struct LoopSearch {
  std::vector<StrokeMismatch> checked;  ///< each with `cycle` c, the closing cycle
  int periodic_cycle = 0;  ///< the first closing cycle within the tolerance; 0: none yet
  int cycles = 1;          ///< the loop's cycles
  /// The check the loop is cut by: the one that passed, or without one the best (nullptr: none).
  const StrokeMismatch* loop_check() const;
  /// The cycle the loop starts at: loop_check()'s c − cycles (0: nothing checked).
  int start_cycle() const;
  /// Whether `frames` hold the loop up to its closing frame and the frame after it.
  bool recorded(std::size_t frames, int frames_per_cycle) const;
};
LoopSearch search_loop(const std::vector<SliceFrame>& frames, int frames_per_cycle, const LoopSettings& loop,
                       double diameter_m, double frequency_hz);

/// A loop cut from a run: `frames` holds the loop's frames and, last, its closing frame (the one
/// after the last: frame 0 again, within `closure`); times from 0 on the run's frame grid.
struct LoopClip {
  std::vector<SliceFrame> frames;
  std::size_t first_frame = 0;  ///< the run's frame the loop starts at
  StrokeMismatch closure;       ///< the closing frame against the first (before root motion)
  Vec2 travel{};                ///< the umbrella centroid's travel over the loop, m
  double duration_s = 0.0;
};

/// Frames first … first + count of `frames` (needs first − 1 and first + count + 1 too), recorded
/// on a clock of `rate_hz` frames a second, with the root motion as `root_motion` says.
LoopClip cut_loop(const std::vector<SliceFrame>& frames, std::size_t first, std::size_t count, double rate_hz,
                  RootMotion root_motion, double diameter_m, double frequency_hz);

/// The umbrella's centroid: the mean of its slice points.
Vec2 umbrella_centroid(const SliceFrame& frame);

}  // namespace jellysim::jellyfish
