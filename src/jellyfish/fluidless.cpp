#include "jellysim/jellyfish/fluidless.hpp"

#include "jellysim/elastic/forces.hpp"
#include "jellysim/elastic/spring_assembly.hpp"

#include <cmath>

namespace jellysim::jellyfish {

std::pair<double, double> cavity_area_and_rate(const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                                               const std::vector<int>& ring) {
  double area = 0.0, rate = 0.0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const auto a = static_cast<std::size_t>(ring[k]), b = static_cast<std::size_t>(ring[(k + 1) % ring.size()]);
    area += cross(x[a], x[b]);
    rate += cross(v[a], x[b]) + cross(x[a], v[b]);
  }
  return {0.5 * area, 0.5 * rate};
}

FluidlessSystem::FluidlessSystem(Jellyfish& jellyfish, const FluidlessSettings& settings)
    : jellyfish_(jellyfish), settings_(settings) {
  if (jellyfish.spec().elastic_model != ElasticModel::continuum) return;
  // Drag per unit length: each point's share of the bell and tentacle lines it lies on.
  const elastic::Body& body = jellyfish.body();
  point_drag_.assign(body.points.size(), 0.0);
  auto add_line = [&](const std::vector<int>& line) {  // the umbrella, then each tentacle (its root shared)
    std::vector<Vec2> x;
    for (int p : line) x.push_back(body.points.position[static_cast<std::size_t>(p)]);
    const std::vector<double> arc = arc_per_point(x);
    for (std::size_t k = 0; k < line.size(); ++k) point_drag_[static_cast<std::size_t>(line[k])] += settings.drag_kg_per_s_m2 * arc[k];
  };
  add_line(jellyfish.layout().umbrella);
  for (const std::vector<int>& strand : jellyfish.layout().tentacles) add_line(strand);
}

Eigen::Index FluidlessSystem::dimension() const {
  return 4 * static_cast<Eigen::Index>(jellyfish_.body().points.size());
}

Eigen::Index FluidlessSystem::position_size() const { return dimension() / 2; }

ode::Vector FluidlessSystem::pack_state() const {
  const auto& p = jellyfish_.body().points;
  const auto n = static_cast<Eigen::Index>(p.size());
  ode::Vector y(4 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    y[2 * k] = p.position[static_cast<std::size_t>(k)].x;
    y[2 * k + 1] = p.position[static_cast<std::size_t>(k)].y;
    y[2 * (n + k)] = p.velocity[static_cast<std::size_t>(k)].x;
    y[2 * (n + k) + 1] = p.velocity[static_cast<std::size_t>(k)].y;
  }
  return y;
}

void FluidlessSystem::unpack_state(const ode::Vector& y) const {
  auto& p = jellyfish_.body().points;
  const auto n = static_cast<Eigen::Index>(p.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    p.position[static_cast<std::size_t>(k)] = {y[2 * k], y[2 * k + 1]};
    p.velocity[static_cast<std::size_t>(k)] = {y[2 * (n + k)], y[2 * (n + k) + 1]};
  }
}

void FluidlessSystem::compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const {
  jellyfish_.actuate(t);
  elastic::Body& body = jellyfish_.body();
  const std::size_t n = body.points.size();
  x_.resize(n);
  v_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    x_[k] = {y[static_cast<Eigen::Index>(2 * k)], y[static_cast<Eigen::Index>(2 * k + 1)]};
    v_[k] = {y[static_cast<Eigen::Index>(2 * (n + k))], y[static_cast<Eigen::Index>(2 * (n + k) + 1)]};
  }
  // Eq. 2.17 against still water: one κ_d per marker (thesis), or per unit length (continuum).
  body.drag_coefficient = point_drag_.empty() ? settings_.drag_kg_per_s : 0.0;
  elastic::accumulate_forces(body, x_, v_, t, f_);
  for (std::size_t k = 0; k < point_drag_.size(); ++k) f_[k] += elastic::drag_force(v_[k], {}, point_drag_[k]);
  // Eq. 8.1 in the slice: p = −α dA/dt, pushing each umbrella segment outward (away from the cavity).
  const std::vector<int>& ring = jellyfish_.layout().umbrella;
  const auto [area, rate] = cavity_area_and_rate(x_, v_, ring);
  const double pressure = -settings_.pressure_factor * (area >= 0 ? rate : -rate);
  for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
    const auto a = static_cast<std::size_t>(ring[k]), b = static_cast<std::size_t>(ring[k + 1]);
    const Vec2 edge = x_[b] - x_[a];
    // Outward normal: the cavity lies to the right of left tip → apex → right tip when area < 0.
    const Vec2 outward = (area >= 0 ? -1.0 : 1.0) * perp(edge);
    const Vec2 force = 0.5 * pressure * outward;  // |perp(edge)| = segment length
    f_[a] += force;
    f_[b] += force;
  }
  dydt.resize(static_cast<Eigen::Index>(4 * n));
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 acc = f_[k] / body.points.mass[k];
    dydt[static_cast<Eigen::Index>(2 * k)] = v_[k].x;
    dydt[static_cast<Eigen::Index>(2 * k + 1)] = v_[k].y;
    dydt[static_cast<Eigen::Index>(2 * (n + k))] = acc.x;
    dydt[static_cast<Eigen::Index>(2 * (n + k) + 1)] = acc.y;
  }
}

void FluidlessSystem::compute_jacobian(double t, const ode::Vector& y, ode::SparseMatrix& jac) const {
  jellyfish_.actuate(t);
  const elastic::Body& body = jellyfish_.body();
  const std::size_t n = body.points.size();
  x_.resize(n);
  for (std::size_t k = 0; k < n; ++k) x_[k] = {y[static_cast<Eigen::Index>(2 * k)], y[static_cast<Eigen::Index>(2 * k + 1)]};
  const auto velocity = static_cast<Eigen::Index>(2 * n);  // first velocity row
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index k = 0; k < velocity; ++k) entries.emplace_back(k, velocity + k, 1.0);  // dx/dt = v
  elastic::for_each_spring_jacobian_block(body, x_, [&](int a, int b, const Mat2& d) {
    const double m = 1.0 / body.points.mass[static_cast<std::size_t>(a)];
    const Eigen::Index r = velocity + 2 * a, c = 2 * b;
    entries.emplace_back(r, c, m * d.xx);
    entries.emplace_back(r, c + 1, m * d.xy);
    entries.emplace_back(r + 1, c, m * d.yx);
    entries.emplace_back(r + 1, c + 1, m * d.yy);
  });
  for (std::size_t p = 0; p < n; ++p) {
    const double drag = (point_drag_.empty() ? settings_.drag_kg_per_s : point_drag_[p]) / body.points.mass[p];
    const auto r = velocity + static_cast<Eigen::Index>(2 * p);
    entries.emplace_back(r, r, -drag);
    entries.emplace_back(r + 1, r + 1, -drag);
  }
  jac.resize(2 * velocity, 2 * velocity);
  jac.setFromTriplets(entries.begin(), entries.end());
}

}  // namespace jellysim::jellyfish
