#pragma once
// Passive tracer ("marker") particles carried by the flow, as in thesis Figures 8.11/8.12.
#include <vector>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

class Tracers {
 public:
  Tracers() = default;
  explicit Tracers(std::vector<Vec2> positions_m) : positions_(std::move(positions_m)) {}
  /// A regular lattice of count_x × count_y particles filling the rectangle [lo, hi].
  static Tracers lattice(Vec2 lo_m, Vec2 hi_m, int count_x, int count_y);

  /// Midpoint (second-order Runge–Kutta) step through the velocity field; particles stay inside
  /// the domain (wrapped on periodic axes, clamped onto the other sides).
  void advect(const Velocity& vel, const Boundaries& b, double dt_s);

  const std::vector<Vec2>& positions() const { return positions_; }
  std::vector<Vec2>& positions() { return positions_; }

 private:
  std::vector<Vec2> positions_;
};

}  // namespace jellysim::fluid
