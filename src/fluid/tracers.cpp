#include "jellysim/fluid/tracers.hpp"

#include "jellysim/fluid/semi_lagrangian.hpp"

namespace jellysim::fluid {

Tracers Tracers::lattice(Vec2 lo_m, Vec2 hi_m, int count_x, int count_y) {
  std::vector<Vec2> p;
  p.reserve(static_cast<std::size_t>(count_x) * count_y);
  for (int j = 0; j < count_y; ++j)
    for (int i = 0; i < count_x; ++i)
      p.push_back({lo_m.x + (hi_m.x - lo_m.x) * (i + 0.5) / count_x,
                   lo_m.y + (hi_m.y - lo_m.y) * (j + 0.5) / count_y});
  return Tracers(std::move(p));
}

void Tracers::advect(const Velocity& vel, const Boundaries& b, double dt_s) {
  const MacGrid& g = vel.u.grid();
  for (Vec2& x : positions_) {
    const Vec2 mid = confine_to_domain(g, b, x + 0.5 * dt_s * vel.sample(x));
    x = confine_to_domain(g, b, x + dt_s * vel.sample(mid));
  }
}

}  // namespace jellysim::fluid
