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

namespace {
// Table V of Ghia et al. (1982): primary vortex centre (x, y) and ψ_min.
constexpr std::array<GhiaCavityReference, 4> kGhiaReferences{{
    {100.0, kGhiaRe100CentrelineU, kGhiaRe100CentrelineV, {0.6172, 0.7344, -0.103423}},
    {400.0, kGhiaRe400CentrelineU, kGhiaRe400CentrelineV, {0.5547, 0.6055, -0.113909}, 5},
    {1000.0, kGhiaRe1000CentrelineU, kGhiaRe1000CentrelineV, {0.5313, 0.5625, -0.117929}},
    {3200.0, kGhiaRe3200CentrelineU, kGhiaRe3200CentrelineV, {0.5165, 0.5469, -0.120377}},
}};
}  // namespace

std::span<const GhiaCavityReference> ghia_references() { return kGhiaReferences; }

const GhiaCavityReference* ghia_reference(double reynolds) {
  for (const GhiaCavityReference& r : kGhiaReferences)
    if (std::abs(reynolds - r.reynolds) <= 1e-9 * r.reynolds) return &r;
  return nullptr;
}

std::span<const ProfilePoint> ghia_centreline_u(double reynolds) {
  const GhiaCavityReference* r = ghia_reference(reynolds);
  return r ? r->centreline_u : std::span<const ProfilePoint>{};
}

std::span<const ProfilePoint> ghia_centreline_v(double reynolds) {
  const GhiaCavityReference* r = ghia_reference(reynolds);
  return r ? r->centreline_v : std::span<const ProfilePoint>{};
}

}  // namespace jellysim::fluid
