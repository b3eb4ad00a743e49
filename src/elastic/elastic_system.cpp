#include "jellysim/elastic/elastic_system.hpp"

#include "jellysim/elastic/forces.hpp"
#include "jellysim/elastic/spring_assembly.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace jellysim::elastic {

namespace {

using Triplet = Eigen::Triplet<double>;

Vec2 get(const ode::Vector& y, Eigen::Index slot) { return {y[2 * slot], y[2 * slot + 1]}; }

void set(ode::Vector& y, Eigen::Index slot, Vec2 value) {
  y[2 * slot] = value.x;
  y[2 * slot + 1] = value.y;
}

PrescribedState prescribed_state(const Body& body, std::size_t p, double t) {
  return body.prescribed[body.points.motion[p]](t);
}

void require_dimension(const Body& body, const ode::Vector& y) {
  const auto expected = static_cast<Eigen::Index>(4 * body.points.size());
  if (y.size() != expected) {
    throw std::invalid_argument("elastic state has " + std::to_string(y.size()) + " components, expected " +
                                std::to_string(expected));
  }
}

/// Positions and velocities from y = [x; v] (eq. 2.19); prescribed points follow their motion at t.
void read_state(const Body& body, const ode::Vector& y, double t, std::vector<Vec2>& x, std::vector<Vec2>& v) {
  require_dimension(body, y);
  const std::size_t n = body.points.size();
  x.resize(n);
  v.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    if (body.points.kind[p] == PointKind::Prescribed) {
      const PrescribedState s = prescribed_state(body, p, t);
      x[p] = s.position;
      v[p] = s.velocity;
    } else {
      x[p] = get(y, static_cast<Eigen::Index>(p));
      v[p] = get(y, static_cast<Eigen::Index>(n + p));
    }
  }
}

/// Collects the nonzeros of df/dy. Only rows of free points are written; a force on point a
/// depends on point b through the state only when b is not prescribed (see read_state).
class JacobianAssembler {
 public:
  JacobianAssembler(const Body& body, std::vector<Triplet>& out)
      : points_(body.points), n_(static_cast<Eigen::Index>(body.points.size())), out_(out) {
    out_.clear();
  }

  /// x_a' = v_a for free points: the identity block [0, I].
  void add_kinematics() {
    for (Eigen::Index a = 0; a < n_; ++a) {
      if (!free(a)) continue;
      out_.emplace_back(2 * a, 2 * (n_ + a), 1.0);
      out_.emplace_back(2 * a + 1, 2 * (n_ + a) + 1, 1.0);
    }
  }
  /// M⁻¹ ∂F_a/∂x_b.
  void add_position_block(int a, int b, const Mat2& d) {
    if (points_.kind[b] != PointKind::Prescribed) add_block(a, b, d);
  }
  /// M⁻¹ ∂F_a/∂v_b.
  void add_velocity_block(int a, int b, const Mat2& d) {
    if (points_.kind[b] != PointKind::Prescribed) add_block(a, static_cast<int>(n_) + b, d);
  }

 private:
  bool free(Eigen::Index p) const { return points_.kind[p] == PointKind::Free; }

  void add_block(int a, int column_slot, const Mat2& d) {
    if (!free(a)) return;
    const double inv_m = 1.0 / points_.mass[a];
    const Eigen::Index r = 2 * (n_ + a);
    const Eigen::Index c = 2 * static_cast<Eigen::Index>(column_slot);
    out_.emplace_back(r, c, inv_m * d.xx);
    out_.emplace_back(r, c + 1, inv_m * d.xy);
    out_.emplace_back(r + 1, c, inv_m * d.yx);
    out_.emplace_back(r + 1, c + 1, inv_m * d.yy);
  }

  const PointMasses& points_;
  Eigen::Index n_;
  std::vector<Triplet>& out_;
};

// Drag (eq. 2.17): ∂F/∂v = -κ_d I. The fluid velocity is treated as frozen: its dependence on the
// point's position (∂v_fluid/∂x) is left out of the Jacobian.
void add_drag(const Body& body, JacobianAssembler& jac) {
  if (body.drag_coefficient == 0.0) return;
  const Mat2 d = -body.drag_coefficient * Mat2::identity();
  const auto n = static_cast<int>(body.points.size());
  for (int p = 0; p < n; ++p) jac.add_velocity_block(p, p, d);
}

// Dashpots: F_i = b ((v_j − v_i)·d̂) d̂ = −F_j. Both their velocity blocks (±b d̂d̂ᵀ) and their
// position blocks go in, in the same four-block pattern as a linear spring's.
void add_dashpots(const Body& body, const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                  JacobianAssembler& jac) {
  const auto& dp = body.dashpots;
  for (std::size_t s = 0; s < dp.size(); ++s) {
    const int i = dp.i[s], j = dp.j[s];
    const DashpotForce f = dashpot_force_and_jacobian(x[i], x[j], v[i], v[j], dp.coefficient[s]);
    jac.add_velocity_block(i, i, f.d_on_i_d_vi);
    jac.add_velocity_block(i, j, -f.d_on_i_d_vi);
    jac.add_velocity_block(j, i, -f.d_on_i_d_vi);
    jac.add_velocity_block(j, j, f.d_on_i_d_vi);
    jac.add_position_block(i, i, f.d_on_i_d_xi);
    jac.add_position_block(i, j, -f.d_on_i_d_xi);
    jac.add_position_block(j, i, -f.d_on_i_d_xi);
    jac.add_position_block(j, j, f.d_on_i_d_xi);
  }
}

/// Adds the triplets into jac's existing sparsity pattern without allocating; false (jac left
/// partly written) when the pattern lacks an entry.
bool accumulate_into_pattern(const std::vector<Triplet>& triplets, ode::SparseMatrix& jac) {
  std::fill_n(jac.valuePtr(), jac.nonZeros(), 0.0);
  const auto* outer = jac.outerIndexPtr();
  const auto* inner = jac.innerIndexPtr();
  for (const Triplet& t : triplets) {
    const auto* begin = inner + outer[t.col()];
    const auto* end = inner + outer[t.col() + 1];
    const auto* it = std::lower_bound(begin, end, t.row());
    if (it == end || *it != t.row()) return false;
    jac.valuePtr()[it - inner] += t.value();
  }
  return true;
}

void store(const std::vector<Triplet>& triplets, Eigen::Index dim, ode::SparseMatrix& jac) {
  const bool same_shape = jac.rows() == dim && jac.cols() == dim && jac.isCompressed();
  if (same_shape && accumulate_into_pattern(triplets, jac)) return;
  jac.resize(dim, dim);
  jac.setFromTriplets(triplets.begin(), triplets.end());
}

}  // namespace

ElasticSystem::ElasticSystem(const Body& body) : body_(body) {}

Eigen::Index ElasticSystem::dimension() const { return static_cast<Eigen::Index>(4 * body_.points.size()); }

Eigen::Index ElasticSystem::position_size() const { return static_cast<Eigen::Index>(2 * body_.points.size()); }

ode::Vector ElasticSystem::pack_state() const {
  const auto n = static_cast<Eigen::Index>(body_.points.size());
  ode::Vector y(4 * n);
  for (Eigen::Index p = 0; p < n; ++p) {
    set(y, p, body_.points.position[p]);
    set(y, n + p, body_.points.velocity[p]);
  }
  return y;
}

void ElasticSystem::unpack_state(const ode::Vector& y, double t, Body& body) {
  read_state(body, y, t, body.points.position, body.points.velocity);
}

// Eq. 2.19: x' = v, v' = F/m for free points; pinned points stay put; prescribed points move with
// their motion's velocity and acceleration.
void ElasticSystem::compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const {
  read_state(body_, y, t, x_, v_);
  accumulate_forces(body_, x_, v_, t, f_);
  const auto n = static_cast<Eigen::Index>(body_.points.size());
  dydt.resize(4 * n);
  for (Eigen::Index p = 0; p < n; ++p) {
    switch (body_.points.kind[p]) {
      case PointKind::Free:
        set(dydt, p, v_[p]);
        set(dydt, n + p, f_[p] / body_.points.mass[p]);
        break;
      case PointKind::Pinned:
        set(dydt, p, {});
        set(dydt, n + p, {});
        break;
      case PointKind::Prescribed: {
        const PrescribedState s = prescribed_state(body_, static_cast<std::size_t>(p), t);
        set(dydt, p, s.velocity);
        set(dydt, n + p, s.acceleration);
        break;
      }
    }
  }
}

void ElasticSystem::compute_jacobian(double t, const ode::Vector& y, ode::SparseMatrix& jac) const {
  read_state(body_, y, t, x_, v_);
  JacobianAssembler assembler(body_, triplets_);
  assembler.add_kinematics();
  for_each_spring_jacobian_block(body_, x_, [&](int a, int b, const Mat2& d) { assembler.add_position_block(a, b, d); });
  add_drag(body_, assembler);
  add_dashpots(body_, x_, v_, assembler);
  store(triplets_, dimension(), jac);
}

}  // namespace jellysim::elastic
