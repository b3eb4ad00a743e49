#include "jellysim/fluid/reference_data.hpp"

#include <cmath>
#include <numbers>

namespace jellysim::fluid {

double TaylorGreen::wavenumber() const { return 2.0 * std::numbers::pi / length_m; }

double TaylorGreen::decay(double t_s) const {
  const double k = wavenumber();
  return std::exp(-2.0 * viscosity_m2_per_s * k * k * t_s);
}

Vec2 TaylorGreen::velocity(Vec2 x, double t_s) const {
  const double k = wavenumber();
  const double a = speed_m_per_s * decay(t_s);
  return {a * std::sin(k * x.x) * std::cos(k * x.y), -a * std::cos(k * x.x) * std::sin(k * x.y)};
}

double TaylorGreen::pressure(Vec2 x, double t_s, double density) const {
  const double k = wavenumber();
  const double a = speed_m_per_s * decay(t_s);
  return 0.25 * density * a * a * (std::cos(2.0 * k * x.x) + std::cos(2.0 * k * x.y));
}

Velocity TaylorGreen::sample(const MacGrid& g, double t_s) const {
  Velocity vel(g);
  for (int j = -1; j <= vel.u.count_y(); ++j)
    for (int i = -1; i <= vel.u.count_x(); ++i) vel.u(i, j) = velocity(vel.u.position(i, j), t_s).x;
  for (int j = -1; j <= vel.v.count_y(); ++j)
    for (int i = -1; i <= vel.v.count_x(); ++i) vel.v(i, j) = velocity(vel.v.position(i, j), t_s).y;
  return vel;
}

}  // namespace jellysim::fluid
