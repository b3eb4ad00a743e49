#pragma once
// One recorded state of a 2D jellyfish slice: what the simulation hands to the rendering pipeline
// (thesis §7.2–7.4). Plain data in metres and seconds; no physics and no pixels.
#include <vector>

#include "jellysim/math/vec2.hpp"

namespace jellysim::jellyfish {

/// A subumbrellar muscle spring (§7.1) between two umbrella points.
struct MuscleState {
  int a = 0, b = 0;             ///< indices into SliceFrame::umbrella (a < b, opposing sides)
  double length_m = 0.0;        ///< current length |x_b − x_a|
  double rest_length_m = 0.0;   ///< uncontracted rest length l_{r_u} (eq. 7.5)
  /// Spring tension now, κ (l − l_r(t)) with l_r(t) the contracted rest length: N per metre of
  /// depth (planar slice) or the ring muscle's planar spring force (rings); positive pulls.
  double tension_n = 0.0;
};

struct SliceFrame {
  double time_s = 0.0;
  /// Subumbrellar surface points in the slice plane, ordered from the left aperture tip over the
  /// apex to the right aperture tip. The count is odd; the middle point is the apex, and
  /// umbrella[k] and umbrella[n − 1 − k] are opposing points (one disc each in §7.3).
  std::vector<Vec2> umbrella;
  /// Tentacle strands, each a polyline starting at (or next to) an aperture tip.
  std::vector<std::vector<Vec2>> tentacles;
  std::vector<MuscleState> muscles;
  double thickness_m = 0.0;  ///< umbrella thickness ϑ (§7.2)
  /// Unit vector from the aperture centre toward the apex (the swimming direction).
  Vec2 axis{0.0, 1.0};
};

}  // namespace jellysim::jellyfish
