#include "jellysim/elastic/body.hpp"

#include "jellysim/elastic/forces.hpp"
#include "jellysim/elastic/spring_assembly.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace jellysim::elastic {

namespace {

void require_point(const Body& body, int index, const char* what) {
  const auto n = static_cast<int>(body.points.size());
  if (index < 0 || index >= n) {
    throw std::invalid_argument(std::string(what) + " index " + std::to_string(index) +
                                " is out of range [0, " + std::to_string(n - 1) + "]");
  }
}

void require_non_negative(double value, const char* what) {
  if (!(value >= 0.0 && std::isfinite(value))) {
    throw std::invalid_argument(std::string(what) + " = " + std::to_string(value) +
                                " must be finite and non-negative");
  }
}

int append_point(PointMasses& points, Vec2 position, Vec2 velocity, double mass, PointKind kind, int motion) {
  points.position.push_back(position);
  points.velocity.push_back(velocity);
  points.mass.push_back(mass);
  points.kind.push_back(kind);
  points.motion.push_back(motion);
  return static_cast<int>(points.size()) - 1;
}

}  // namespace

int Body::add_point(Vec2 position, double mass, PointKind kind, Vec2 velocity) {
  if (kind == PointKind::Prescribed) {
    throw std::invalid_argument("prescribed points are added with add_prescribed_point");
  }
  if (kind == PointKind::Free && !(mass > 0.0 && std::isfinite(mass))) {
    throw std::invalid_argument("point mass = " + std::to_string(mass) + " must be positive and finite");
  }
  if (kind == PointKind::Pinned) velocity = {};
  return append_point(points, position, velocity, mass, kind, -1);
}

int Body::add_prescribed_point(PrescribedMotion motion) {
  if (!motion) throw std::invalid_argument("a prescribed point needs a motion function");
  const PrescribedState start = motion(0.0);
  prescribed.push_back(std::move(motion));
  return append_point(points, start.position, start.velocity, 0.0, PointKind::Prescribed,
                      static_cast<int>(prescribed.size()) - 1);
}

void Body::add_linear_spring(int i, int j, double stiffness, double rest_length) {
  require_point(*this, i, "linear spring end");
  require_point(*this, j, "linear spring end");
  if (i == j) {
    throw std::invalid_argument("a linear spring needs two distinct points, got " + std::to_string(i) + " twice");
  }
  require_non_negative(stiffness, "linear spring stiffness");
  if (rest_length < 0.0) rest_length = norm(points.position[j] - points.position[i]);
  require_non_negative(rest_length, "linear spring rest length");
  linear.i.push_back(i);
  linear.j.push_back(j);
  linear.stiffness.push_back(stiffness);
  linear.rest_length.push_back(rest_length);
}

void Body::add_angular_spring(int i, int j, int k, double stiffness, double rest_angle) {
  for (int index : {i, j, k}) require_point(*this, index, "angular spring point");
  if (i == j || j == k || i == k) {
    throw std::invalid_argument("an angular spring needs three distinct points");
  }
  require_non_negative(stiffness, "angular spring stiffness");
  if (std::isnan(rest_angle)) {
    rest_angle = turning_angle(points.position[i], points.position[j], points.position[k]);
  }
  if (!std::isfinite(rest_angle)) throw std::invalid_argument("angular spring rest angle must be finite");
  angular.i.push_back(i);
  angular.j.push_back(j);
  angular.k.push_back(k);
  angular.stiffness.push_back(stiffness);
  angular.rest_angle.push_back(rest_angle);
}

namespace {

void require_three_distinct_points(const Body& body, int i, int j, int k, const char* what) {
  for (int index : {i, j, k}) require_point(body, index, what);
  if (i == j || j == k || i == k) throw std::invalid_argument(std::string("a ") + what + " needs three distinct points");
}

void require_two_distinct_points(const Body& body, int i, int j, const char* what) {
  require_point(body, i, what);
  require_point(body, j, what);
  if (i == j) {
    throw std::invalid_argument(std::string("a ") + what + " needs two distinct points, got " + std::to_string(i) +
                                " twice");
  }
}

}  // namespace

void Body::add_torsional_beam(int i, int j, int k, double stiffness, double curvature) {
  require_three_distinct_points(*this, i, j, k, "torsional beam");
  require_non_negative(stiffness, "torsional beam stiffness");
  if (std::isnan(curvature)) curvature = beam_cross_product(points.position[i], points.position[j], points.position[k]);
  if (!std::isfinite(curvature)) throw std::invalid_argument("torsional beam curvature must be finite");
  torsional.i.push_back(i);
  torsional.j.push_back(j);
  torsional.k.push_back(k);
  torsional.stiffness.push_back(stiffness);
  torsional.curvature.push_back(curvature);
}

void Body::add_non_invariant_beam(int i, int j, int k, double stiffness, Vec2 curvature) {
  require_three_distinct_points(*this, i, j, k, "non-invariant beam");
  require_non_negative(stiffness, "non-invariant beam stiffness");
  if (std::isnan(curvature.x) && std::isnan(curvature.y)) {
    curvature = points.position[i] - 2.0 * points.position[j] + points.position[k];
  }
  if (!std::isfinite(curvature.x) || !std::isfinite(curvature.y)) {
    throw std::invalid_argument("non-invariant beam curvature must be finite");
  }
  non_invariant.i.push_back(i);
  non_invariant.j.push_back(j);
  non_invariant.k.push_back(k);
  non_invariant.stiffness.push_back(stiffness);
  non_invariant.curvature.push_back(curvature);
}

void Body::add_power_spring(int i, int j, double stiffness, double rest_length, double degree) {
  require_two_distinct_points(*this, i, j, "power spring");
  require_non_negative(stiffness, "power spring stiffness");
  // α < 1 has an infinite stiffness dT/dl at rest; large α overflows |e|^α for modest stretches.
  if (!(degree >= 1.0 && degree <= 10.0)) {
    throw std::invalid_argument("power spring degree = " + std::to_string(degree) + " must be in [1, 10]");
  }
  if (rest_length < 0.0) rest_length = norm(points.position[j] - points.position[i]);
  require_non_negative(rest_length, "power spring rest length");
  power.i.push_back(i);
  power.j.push_back(j);
  power.stiffness.push_back(stiffness);
  power.rest_length.push_back(rest_length);
  power.degree.push_back(degree);
}

void Body::add_dashpot(int i, int j, double coefficient) {
  require_two_distinct_points(*this, i, j, "dashpot");
  require_non_negative(coefficient, "dashpot coefficient");
  dashpots.i.push_back(i);
  dashpots.j.push_back(j);
  dashpots.coefficient.push_back(coefficient);
}

namespace {

double elastic_energy(const Body& body) {
  const auto& x = body.points.position;
  double e = 0.0;
  for (std::size_t s = 0; s < body.linear.size(); ++s) {
    e += linear_spring_energy(x[body.linear.i[s]], x[body.linear.j[s]], body.linear.stiffness[s],
                              body.linear.rest_length[s]);
  }
  const auto& ang = body.angular;
  for (std::size_t s = 0; s < ang.size(); ++s) {
    e += angular_spring_energy(x[ang.i[s]], x[ang.j[s]], x[ang.k[s]], ang.stiffness[s], ang.rest_angle[s]);
  }
  const auto& tb = body.torsional;
  for (std::size_t s = 0; s < tb.size(); ++s) {
    e += torsional_beam_energy(x[tb.i[s]], x[tb.j[s]], x[tb.k[s]], tb.stiffness[s], tb.curvature[s]);
  }
  const auto& nb = body.non_invariant;
  for (std::size_t s = 0; s < nb.size(); ++s) {
    e += non_invariant_beam_energy(x[nb.i[s]], x[nb.j[s]], x[nb.k[s]], nb.stiffness[s], nb.curvature[s]);
  }
  const auto& pw = body.power;
  for (std::size_t s = 0; s < pw.size(); ++s) {
    e += power_spring_energy(x[pw.i[s]], x[pw.j[s]], pw.stiffness[s], pw.rest_length[s], pw.degree[s]);
  }
  return e;
}

// Drag (eq. 2.17) on every point; gravity (eq. 2.18) on points of finite mass.
void add_drag_and_gravity(const Body& body, const std::vector<Vec2>& x, const std::vector<Vec2>& v, double t,
                          std::vector<Vec2>& force) {
  const auto& pts = body.points;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    if (body.drag_coefficient != 0.0) {
      const Vec2 fluid = body.fluid_velocity ? body.fluid_velocity(x[p], t) : Vec2{};
      force[p] += drag_force(v[p], fluid, body.drag_coefficient);
    }
    if (pts.kind[p] == PointKind::Free) force[p] += gravity_force(pts.mass[p], body.gravity);
  }
}

}  // namespace

Energy energy(const Body& body) {
  Energy e;
  const auto& pts = body.points;
  for (std::size_t p = 0; p < pts.size(); ++p) {
    if (pts.kind[p] != PointKind::Free) continue;
    e.kinetic += 0.5 * pts.mass[p] * norm_squared(pts.velocity[p]);
    e.gravity -= pts.mass[p] * dot(body.gravity, pts.position[p]);
  }
  e.elastic = elastic_energy(body);
  return e;
}

void add_spring_forces(const Body& body, const std::vector<Vec2>& x, std::vector<Vec2>& force) {
  const auto& lin = body.linear;
  for (std::size_t s = 0; s < lin.size(); ++s) {
    const Vec2 f = linear_spring_force(x[lin.i[s]], x[lin.j[s]], lin.stiffness[s], lin.rest_length[s]);
    force[lin.i[s]] += f;
    force[lin.j[s]] -= f;
  }
  const auto& ang = body.angular;
  for (std::size_t s = 0; s < ang.size(); ++s) {
    const AngularSpringForce f =
        angular_spring_force(x[ang.i[s]], x[ang.j[s]], x[ang.k[s]], ang.stiffness[s], ang.rest_angle[s]);
    force[ang.i[s]] += f.on_i;
    force[ang.j[s]] += f.on_j;
    force[ang.k[s]] += f.on_k;
  }
  // The beams' forces come with their Jacobians; only the forces are kept here.
  const auto add_three = [&force](int i, int j, int k, const ThreePointForce& f) {
    force[i] += f.on[0];
    force[j] += f.on[1];
    force[k] += f.on[2];
  };
  const auto& tb = body.torsional;
  for (std::size_t s = 0; s < tb.size(); ++s) {
    add_three(tb.i[s], tb.j[s], tb.k[s],
              torsional_beam_force_and_jacobian(x[tb.i[s]], x[tb.j[s]], x[tb.k[s]], tb.stiffness[s], tb.curvature[s]));
  }
  const auto& nb = body.non_invariant;
  for (std::size_t s = 0; s < nb.size(); ++s) {
    add_three(nb.i[s], nb.j[s], nb.k[s],
              non_invariant_beam_force_and_jacobian(x[nb.i[s]], x[nb.j[s]], x[nb.k[s]], nb.stiffness[s],
                                                    nb.curvature[s]));
  }
  const auto& pw = body.power;
  for (std::size_t s = 0; s < pw.size(); ++s) {
    const Vec2 f = power_spring_force(x[pw.i[s]], x[pw.j[s]], pw.stiffness[s], pw.rest_length[s], pw.degree[s]);
    force[pw.i[s]] += f;
    force[pw.j[s]] -= f;
  }
}

void add_dashpot_forces(const Body& body, const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                        std::vector<Vec2>& force) {
  const auto& dp = body.dashpots;
  for (std::size_t s = 0; s < dp.size(); ++s) {
    const int i = dp.i[s], j = dp.j[s];
    const Vec2 f = dashpot_force(x[i], x[j], v[i], v[j], dp.coefficient[s]);
    force[i] += f;
    force[j] -= f;
  }
}

void accumulate_forces(const Body& body, const std::vector<Vec2>& position, const std::vector<Vec2>& velocity,
                       double t, std::vector<Vec2>& force) {
  const std::size_t n = body.points.size();
  if (position.size() != n || velocity.size() != n) {
    throw std::invalid_argument("accumulate_forces: position/velocity sizes do not match the point count " +
                                std::to_string(n));
  }
  force.assign(n, Vec2{});
  add_spring_forces(body, position, force);
  add_dashpot_forces(body, position, velocity, force);
  add_drag_and_gravity(body, position, velocity, t, force);
}

}  // namespace jellysim::elastic
