#pragma once
// Does any pair of segments cross? Sort and sweep along x (issue 23: the polygon and bell checks
// were quadratic, 14 s for a 50,000-vertex outline): segments are visited by their smallest x, and
// each is tested only against the earlier ones whose x-extent it can still reach and whose
// y-extent overlaps its own. For outlines that a vertical line crosses a bounded number of times
// (any shape drawn as a boundary) that is O(n log n); the answer is always the exact pairwise one.
#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

#include "jellysim/math/vec2.hpp"

namespace jellysim::jellyfish {

using Segment = std::array<Vec2, 2>;

/// True when crosses(s[i], s[j]) for some pair i < j that skip(i, j) does not exclude.
template <class Crosses, class Skip>
bool any_pair_crosses(const std::vector<Segment>& s, Crosses&& crosses, Skip&& skip) {
  const std::size_t n = s.size();
  auto lo = [&](std::size_t k, int axis) { return std::min(axis == 0 ? s[k][0].x : s[k][0].y, axis == 0 ? s[k][1].x : s[k][1].y); };
  auto hi = [&](std::size_t k, int axis) { return std::max(axis == 0 ? s[k][0].x : s[k][0].y, axis == 0 ? s[k][1].x : s[k][1].y); };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return lo(a, 0) < lo(b, 0) || (lo(a, 0) == lo(b, 0) && a < b);
  });
  std::vector<std::size_t> active;
  for (std::size_t k : order) {
    const double x = lo(k, 0);
    // Segments that end before this one starts can meet no later segment either.
    active.erase(std::remove_if(active.begin(), active.end(), [&](std::size_t a) { return hi(a, 0) < x; }), active.end());
    for (std::size_t a : active) {
      if (hi(a, 1) < lo(k, 1) || hi(k, 1) < lo(a, 1)) continue;
      const std::size_t i = std::min(a, k), j = std::max(a, k);
      if (!skip(i, j) && crosses(s[i], s[j])) return true;
    }
    active.push_back(k);
  }
  return false;
}

}  // namespace jellysim::jellyfish
