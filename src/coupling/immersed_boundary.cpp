#include "jellysim/coupling/immersed_boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "jellysim/core/state_archive.hpp"
#include "jellysim/elastic/spring_assembly.hpp"
#include "jellysim/fluid/projection.hpp"

namespace jellysim::coupling {

namespace {

using Triplet = Eigen::Triplet<double>;

std::string format_vec(Vec2 p) {
  std::ostringstream s;
  s.precision(4);
  s << "(" << p.x << ", " << p.y << ") m";
  return s.str();
}

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

/// Zeroes every stored sample of a face field outside the half-open range (boundary faces and
/// ghosts): a body force acts only where the momentum equation is solved.
void keep_only(fluid::Field& f, const fluid::FaceRange& r) {
  for (int j = -1; j <= f.count_y(); ++j) {
    double* row = f.ptr(0, j);
    if (j < r.j_begin || j >= r.j_end) {
      std::fill(row - 1, row + f.count_x() + 1, 0.0);  // the whole row, ghosts included
    } else {
      std::fill(row - 1, row + r.i_begin, 0.0);
      std::fill(row + r.i_end, row + f.count_x() + 1, 0.0);
    }
  }
}

void add_block(std::vector<Triplet>& t, int a, int b, const Mat2& d) {
  t.emplace_back(2 * a, 2 * b, d.xx);
  t.emplace_back(2 * a, 2 * b + 1, d.xy);
  t.emplace_back(2 * a + 1, 2 * b, d.yx);
  t.emplace_back(2 * a + 1, 2 * b + 1, d.yy);
}

Eigen::VectorXd flatten(std::span<const Vec2> v) {
  Eigen::VectorXd out(2 * static_cast<Eigen::Index>(v.size()));
  for (std::size_t p = 0; p < v.size(); ++p) {
    out[2 * static_cast<Eigen::Index>(p)] = v[p].x;
    out[2 * static_cast<Eigen::Index>(p) + 1] = v[p].y;
  }
  return out;
}

void unflatten(const Eigen::VectorXd& in, std::vector<Vec2>& out) {
  out.resize(static_cast<std::size_t>(in.size() / 2));
  for (std::size_t p = 0; p < out.size(); ++p)
    out[p] = {in[2 * static_cast<Eigen::Index>(p)], in[2 * static_cast<Eigen::Index>(p) + 1]};
}

}  // namespace

std::span<const ImmersedBoundary::SchemeEntry> ImmersedBoundary::schemes() {
  static const SchemeEntry table[] = {
      {Scheme::semi_implicit, "semi-implicit", &ImmersedBoundary::step_semi_implicit},  // backward Euler exchange
      {Scheme::explicit_euler, "explicit", &ImmersedBoundary::step_explicit},  // eqs. 4.19–4.21: forces at t^n
  };
  return table;
}

std::vector<std::string> scheme_names() {
  std::vector<std::string> names;
  for (const auto& entry : ImmersedBoundary::schemes()) names.emplace_back(entry.name);
  return names;
}

std::string_view to_string(Scheme s) {
  for (const auto& entry : ImmersedBoundary::schemes())
    if (entry.scheme == s) return entry.name;
  return "unknown";
}

std::optional<Scheme> scheme_from_string(std::string_view name) {
  for (const auto& entry : ImmersedBoundary::schemes())
    if (entry.name == name) return entry.scheme;
  return std::nullopt;
}

std::string_view to_string(Preconditioner p) { return p == Preconditioner::none ? "none" : "mobility"; }

std::optional<Preconditioner> preconditioner_from_string(std::string_view name) {
  if (name == "none") return Preconditioner::none;
  if (name == "mobility") return Preconditioner::mobility;
  return std::nullopt;
}

ImmersedBoundary::ImmersedBoundary(fluid::FluidSolver& fluid, elastic::Body& body, const CouplingSettings& settings,
                                   Actuator actuator)
    : fluid_(fluid),
      body_(body),
      settings_(settings),
      actuator_(std::move(actuator)),
      time_s_(fluid.time_s()),
      projector_(fluid::make_pressure_solver(fluid.settings().pressure_solver, fluid.settings().pressure),
                 fluid.settings().geometry),
      scratch_(fluid.state().grid),
      homogeneous_(fluid.settings().boundaries.homogeneous()),
      base_field_(fluid.state().grid),
      transfer_{fluid.state().grid, homogeneous_, settings.kernel, settings.west_mirror} {
  if (!(settings_.safety_factor > 0.0)) throw std::invalid_argument("coupling safety factor must be > 0");
  if (!(settings_.max_time_step_s > 0.0)) throw std::invalid_argument("coupling max time step must be > 0");
  if (settings_.west_mirror && homogeneous_.west.type != fluid::BoundaryType::free_slip)
    throw std::invalid_argument("a mirror west side must be a free-slip wall");
  if (axisymmetric() && settings_.west_mirror)
    throw std::invalid_argument("axisymmetric coupling: the west side is the axis, not a mirror half tank");
  body_.points.velocity.assign(body_.points.size(), Vec2{});
  refresh_markers();
  if (const int threads = resolve_threads(settings_.threads); threads > 1) pool_ = std::make_unique<WorkerPool>(threads);
}


void ImmersedBoundary::refresh_markers() {
  const auto& kind = body_.points.kind;
  is_target_.assign(body_.points.size(), 0);
  has_targets_ = false;
  for (std::size_t p = 0; p < kind.size(); ++p)
    if (kind[p] != elastic::PointKind::Free) is_target_[p] = 1, has_targets_ = true;
  mobility_points_.clear();  // the next preconditioned step rebuilds R
  build_symmetric_unknowns();
  split_target_unknowns();
}

void ImmersedBoundary::continue_from(const ImmersedBoundary& earlier) {
  time_s_ = earlier.time_s_;
  steps_ = earlier.steps_;
  last_increment_ = earlier.last_increment_;
}

namespace {

/// A dense matrix whose shape is part of the state.
void archive_matrix(core::StateArchive& a, std::string_view name, Eigen::MatrixXd& m) {
  const core::StateArchive::Scope scope(a, name);
  std::array<Eigen::Index, 2> shape{m.rows(), m.cols()};
  a.value("shape", shape);
  if (a.is_restoring()) m.resize(shape[0], shape[1]);
  a.values("values", std::span<double>(m.data(), static_cast<std::size_t>(m.size())));
}

}  // namespace

void ImmersedBoundary::archive(core::StateArchive& a) {
  const core::StateArchive::Scope scope(a, "coupling");
  a.value("time", time_s_);
  a.value("steps", steps_);
  Eigen::MatrixXd increment = last_increment_;
  archive_matrix(a, "last_increment", increment);
  if (a.is_restoring()) last_increment_ = increment;
  {
    const core::StateArchive::Scope projection(a, "projector");
    projector_.archive(a);
  }
  // The response projections start from the last one's pressure (an iterative pressure solver's
  // first guess).
  fluid::archive(a, "response_pressure", scratch_.pressure);
  if (settings_.mobility_rebuild_cells > 0.0) {
    // R is reused until a marker has moved far enough: the restored run must reuse the same R.
    // (Rebuilt every step otherwise: nothing to keep.)
    a.vector("mobility_points", mobility_points_);
    archive_matrix(a, "mobility", mobility_matrix_);
    archive_matrix(a, "reduced_mobility", reduced_mobility_);
  }
}

void ImmersedBoundary::set_mirror_symmetry(std::vector<int> partners) {
  if (!partners.empty() && partners.size() != body_.points.size())
    throw std::invalid_argument("mirror partners: one per point needed");
  mirror_partner_ = std::move(partners);
  build_symmetric_unknowns();
  split_target_unknowns();
  mobility_points_.clear();
}

void ImmersedBoundary::split_target_unknowns() {
  held_.clear();
  moving_.clear();
  const bool symmetric = !mirror_partner_.empty();
  const auto unknowns = symmetric ? static_cast<Eigen::Index>(picked_rows_.size())
                                  : 2 * static_cast<Eigen::Index>(body_.points.size());
  for (Eigen::Index u = 0; u < unknowns; ++u) {
    const auto point = symmetric ? static_cast<std::size_t>(independent_[static_cast<std::size_t>(picked_rows_[static_cast<std::size_t>(u)] / 2)])
                                 : static_cast<std::size_t>(u / 2);
    (is_target_[point] ? held_ : moving_).push_back(u);
  }
}

void ImmersedBoundary::build_symmetric_unknowns() {
  independent_.clear();
  picked_rows_.clear();
  if (mirror_partner_.size() != body_.points.size()) {
    mirror_partner_.clear();
    return;
  }
  // Unknowns of a symmetric increment: (x, y) of each point east of the axis (its partner moves by
  // (−x, y)), and y alone of a point on the axis (its own partner). East, because a half tank
  // solves the east half: their stencils need no mirror images.
  std::vector<Eigen::Triplet<double>> q;
  Eigen::Index d = 0;
  const auto& x = body_.points.position;
  for (std::size_t p = 0; p < mirror_partner_.size(); ++p) {
    const auto partner = static_cast<std::size_t>(mirror_partner_[p]);
    if (partner != p && x[p].x < x[partner].x) continue;
    const auto row = 2 * static_cast<Eigen::Index>(independent_.size());
    independent_.push_back(static_cast<int>(p));
    const auto xp = 2 * static_cast<Eigen::Index>(p), xq = 2 * static_cast<Eigen::Index>(partner);
    if (partner != p) {
      q.emplace_back(xp, d, 1.0);
      q.emplace_back(xq, d, -1.0);
      picked_rows_.push_back(row);
      ++d;
      q.emplace_back(xp + 1, d, 1.0);
      q.emplace_back(xq + 1, d, 1.0);
    } else {
      q.emplace_back(xp + 1, d, 1.0);
    }
    picked_rows_.push_back(row + 1);
    ++d;
  }
  const auto n2 = 2 * static_cast<Eigen::Index>(mirror_partner_.size());
  symmetric_basis_.resize(n2, d);
  symmetric_basis_.setFromTriplets(q.begin(), q.end());
  // pick_: unknown k is component picked of point independent_[…]; picked_rows_matrix_: the same
  // selection from R's rows (two per independent point).
  std::vector<Eigen::Triplet<double>> pick, rows;
  for (std::size_t k = 0; k < picked_rows_.size(); ++k) {
    const Eigen::Index row = picked_rows_[k];
    const Eigen::Index point = independent_[static_cast<std::size_t>(row / 2)];
    pick.emplace_back(static_cast<Eigen::Index>(k), 2 * point + row % 2, 1.0);
    rows.emplace_back(static_cast<Eigen::Index>(k), row, 1.0);
  }
  pick_.resize(d, n2);
  pick_.setFromTriplets(pick.begin(), pick.end());
  picked_rows_matrix_.resize(d, 2 * static_cast<Eigen::Index>(independent_.size()));
  picked_rows_matrix_.setFromTriplets(rows.begin(), rows.end());
}

void ImmersedBoundary::spread(std::span<const Vec2> points, std::span<const Vec2> forces,
                              fluid::FaceAccelerations& acc) const {
  const double rho = fluid_.settings().density_kg_per_m3;
  if (axisymmetric() && !mirror_partner_.empty()) {
    // The body is the whole slice, both halves of every ring: its energy is twice the rings'. The
    // force on a ring is half the force on its two points, i.e. that on its east point (the west
    // one is its mirror image), and half the force on a point of the axis (its own image).
    std::vector<Vec2> ring_points, ring_forces;
    ring_points.reserve(independent_.size());
    ring_forces.reserve(independent_.size());
    for (int p : independent_) {
      const auto k = static_cast<std::size_t>(p);
      ring_points.push_back(points[k]);
      ring_forces.push_back(mirror_partner_[k] == p ? 0.5 * forces[k] : forces[k]);
    }
    spread_forces_axisymmetric(ring_points, ring_forces, settings_.kernel, rho, acc, periodicity().y);
  } else if (axisymmetric()) {
    spread_forces_axisymmetric(points, forces, settings_.kernel, rho, acc, periodicity().y);
  } else {
    spread_forces(points, forces, settings_.kernel, rho, acc, periodicity());
  }
}

void ImmersedBoundary::interpolate_at_markers(const fluid::Velocity& vel, std::vector<Vec2>& out) const {
  const auto& x = body_.points.position;
  out.resize(x.size());
  if (axisymmetric()) interpolate_velocities_axisymmetric(vel, x, settings_.kernel, out, periodicity().y);
  else if (settings_.west_mirror) interpolate_velocities(transfer_, vel, x, out);
  else interpolate_velocities(vel, x, settings_.kernel, out, periodicity());
}

Vec2 ImmersedBoundary::target_position(std::size_t p, double t) const {
  if (body_.points.kind[p] == elastic::PointKind::Prescribed)
    return body_.prescribed[static_cast<std::size_t>(body_.points.motion[p])](t).position;
  return body_.points.position[p];
}

void ImmersedBoundary::mask_target_forces(std::span<Vec2> force) const {
  if (!has_targets_) return;
  for (std::size_t p = 0; p < force.size(); ++p)
    if (is_target_[p]) force[p] = Vec2{};
}

double ImmersedBoundary::next_time_step() const {
  const fluid::FluidSettings& fs = fluid_.settings();
  double dt = fluid::stability_time_step(fluid_.state().velocity, fs.viscosity_m2_per_s, settings_.safety_factor,
                                         fs.convection, &fs.boundaries);
  // The markers move with the fluid, but their interpolated speed can exceed the face maxima of the
  // last step; include it in the CFL limit of eq. 4.8.
  const fluid::MacGrid& g = fluid_.state().grid;
  double marker_speed = 0.0;
  for (Vec2 v : body_.points.velocity) marker_speed = std::max(marker_speed, std::max(std::abs(v.x), std::abs(v.y)));
  if (marker_speed > 0.0) dt = std::min(dt, settings_.safety_factor * std::min(g.dx(), g.dy()) / marker_speed);
  if (axisymmetric()) dt = std::min(dt, fluid_.stable_time_step());  // its viscous limit near the axis
  if (!(dt == dt)) return 0.0;
  return std::min(dt, settings_.max_time_step_s);
}

CoupledStepReport ImmersedBoundary::step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("coupled time step must be > 0");
  const auto schemes = ImmersedBoundary::schemes();
  const auto entry = std::find_if(schemes.begin(), schemes.end(), [this](const SchemeEntry& e) {
    return e.scheme == settings_.scheme;
  });
  if (entry == schemes.end()) throw std::invalid_argument("unknown coupling scheme");
  CoupledStepReport r = (this->*(entry->step))(dt_s);
  time_s_ += dt_s;
  ++steps_;
  return r;
}

void ImmersedBoundary::compute_forces(std::vector<Vec2>& force) const {
  force.assign(body_.points.size(), Vec2{});
  elastic::add_spring_forces(body_, body_.points.position, force);
  // Dashpots use the markers' velocities from the end of the last step (explicit: they are not
  // in the stiffness K of the semi-implicit step).
  elastic::add_dashpot_forces(body_, body_.points.position, body_.points.velocity, force);
}

void ImmersedBoundary::assemble_stiffness(Eigen::SparseMatrix<double>& k) const {
  std::vector<Triplet> t;
  elastic::for_each_spring_jacobian_block(body_, body_.points.position,
                                          [&t](int a, int b, const Mat2& d) { add_block(t, a, b, d); });
  const auto n = static_cast<Eigen::Index>(2 * body_.points.size());
  k.resize(n, n);
  k.setFromTriplets(t.begin(), t.end());
}

void ImmersedBoundary::move_markers_with_fluid(double dt_s) {
  // Eq. 4.20: x(t + Δt) = x(t) + Δt u(x(t), t + Δt).
  auto& x = body_.points.position;
  auto& v = body_.points.velocity;
  interpolate_at_markers(fluid_.state().velocity, v);
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (has_targets_ && is_target_[p]) {
      // Target points are not carried by the fluid: they sit still or follow their path.
      const Vec2 next = target_position(p, time_s_ + dt_s);
      v[p] = (next - x[p]) / dt_s;
      x[p] = next;
    } else {
      x[p] += dt_s * v[p];
    }
  }
}

CoupledStepReport ImmersedBoundary::step_explicit(double dt_s) {
  CoupledStepReport report;
  report.dt_s = dt_s;
  if (actuator_) actuator_(time_s_, body_);
  compute_forces(force_);
  mask_target_forces(force_);
  fluid::FaceAccelerations& acc = fluid_.body_acceleration();
  acc.u.fill(0.0);
  acc.v.fill(0.0);
  spread(body_.points.position, force_, acc);
  report.fluid = fluid_.step(dt_s);
  move_markers_with_fluid(dt_s);
  return report;
}

void ImmersedBoundary::spread_to_interior_faces(std::span<Vec2> forces, fluid::Velocity& w) {
  w.u.fill(0.0);
  w.v.fill(0.0);
  mask_target_forces(forces);  // targets hold the body from outside; they push no fluid
  spread(body_.points.position, forces, w);
  const fluid::MacGrid& g = scratch_.grid;
  keep_only(w.u, fluid::interior_u_faces(g, homogeneous_));
  keep_only(w.v, fluid::interior_v_faces(g, homogeneous_));
}

void ImmersedBoundary::project_spread_forces(std::span<Vec2> forces) {
  fluid::Velocity& w = scratch_.velocity;
  spread_to_interior_faces(forces, w);
  fluid::apply_velocity_boundaries(w, homogeneous_);
  projector_.project(scratch_, homogeneous_, 1.0, fluid_.settings().density_kg_per_m3);
}

void ImmersedBoundary::apply_response(const Eigen::VectorXd& forces, Eigen::VectorXd& velocity_at_markers) {
  unflatten(forces, work_);
  project_spread_forces(work_);
  interpolate_at_markers(scratch_.velocity, velocity_);
  mask_target_forces(velocity_);  // the fluid does not move target points
  velocity_at_markers = flatten(velocity_);
}

Eigen::MatrixXd ImmersedBoundary::response_by_projections() {
  const auto n = 2 * static_cast<Eigen::Index>(body_.points.size());
  if (!mirror_partner_.empty()) {
    // On the symmetric unknowns: column k is the picked velocity for the symmetric force Q e_k.
    const Eigen::Index d = symmetric_basis_.cols();
    Eigen::MatrixXd r(d, d);
    Eigen::VectorXd force, column;
    for (Eigen::Index k = 0; k < d; ++k) {
      force = symmetric_basis_.col(k);
      apply_response(force, column);
      r.col(k) = pick_ * column;
    }
    return r;
  }
  Eigen::MatrixXd r(n, n);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(n), column;
  for (Eigen::Index k = 0; k < n; ++k) {
    unit[k] = 1.0;
    apply_response(unit, column);
    r.col(k) = column;
    unit[k] = 0.0;
  }
  return r;
}

// The exchange is backward Euler (§4.3): ΔX = Δt U_L + Δt² R (F + K ΔX), R = J P S / ρ, i.e.
// A ΔX = b with A = I − Δt² R K and b = Δt U_L + Δt² R F. From a guess x0 of the increment (the
// last step's), the correction e = ΔX − x0 solves
//   A e = Δt U_L − x0 + Δt² R (F + K x0) = Δt J P (u* + Δt S (F + K x0) / ρ) − x0
// by GMRES from zero. The stages below are that derivation's steps, in order.
CoupledStepReport ImmersedBoundary::step_semi_implicit(double dt_s) {
  CoupledStepReport report;
  report.dt_s = dt_s;
  SemiImplicitStep s;
  linearise_forces(dt_s, s);
  report.fluid = predict_fluid(s);
  build_right_hand_side(s);
  report.krylov = solve_increment(s);
  apply_end_of_step_forces(s, report.krylov);
  move_markers_with_fluid(dt_s);
  return report;
}

void ImmersedBoundary::linearise_forces(double dt_s, SemiImplicitStep& s) {
  // Forces at the end of the step: rest lengths at t + Δt, positions linearised about x^n.
  s.dt = dt_s;
  s.dt2 = dt_s * dt_s;
  if (actuator_) actuator_(time_s_ + dt_s, body_);
  compute_forces(force_);
  assemble_stiffness(s.stiffness);
  s.f0 = flatten(force_);
  // Where the fluid step is affine in the body acceleration (Eulerian: one projection of u* + Δt a),
  // the guess's forces ride along with it (predict_fluid): "merged".
  s.merged = fluid_.projects_body_acceleration_linearly() && dt_s <= fluid_.stable_time_step();
  if (last_increment_.size() == s.f0.size()) s.x0 = last_increment_;
  else if (s.merged) s.x0 = dt_s * flatten(body_.points.velocity);  // first step: the markers' own motion
}

fluid::StepReport ImmersedBoundary::predict_fluid(SemiImplicitStep& s) {
  // The fluid over the step, u_L = P u* (advection, diffusion, projection); merged, one projection
  // gives u_L + Δt P S (F + K x0)/ρ and the right-hand side at once. Then U_L at the markers.
  fluid::FaceAccelerations& acc = fluid_.body_acceleration();
  if (s.merged) {
    unflatten(s.f0 + s.stiffness * s.x0, work_);
    spread_to_interior_faces(work_, acc);
  } else {
    acc.u.fill(0.0);
    acc.v.fill(0.0);
  }
  const fluid::StepReport report = fluid_.step(s.dt);
  if (s.merged) {
    acc.u.fill(0.0);
    acc.v.fill(0.0);
  }
  interpolate_at_markers(fluid_.state().velocity, velocity_);
  const auto& x = body_.points.position;
  if (has_targets_)  // target points move along their path: ΔX is known
    for (std::size_t p = 0; p < x.size(); ++p)
      if (is_target_[p]) velocity_[p] = (target_position(p, time_s_ + s.dt) - x[p]) / s.dt;
  return report;
}

void ImmersedBoundary::build_right_hand_side(SemiImplicitStep& s) {
  // b − A x0 = Δt U − x0, plus Δt² R (F + K x0) when the forces were not merged into the fluid step.
  const Eigen::VectorXd fluid_velocity = flatten(velocity_);
  if (s.x0.size() != s.f0.size()) s.x0 = s.dt * fluid_velocity;
  s.rhs = s.dt * fluid_velocity - s.x0;
  if (!s.merged) {
    Eigen::VectorXd response;
    apply_response(s.f0 + s.stiffness * s.x0, response);
    std::swap(base_field_, scratch_.velocity);  // P S (F + K x0) / ρ
    s.rhs += s.dt2 * response;
  }
  // A mirror-symmetric scene has a symmetric solution: solve for it (the state is made symmetric
  // after the step anyway), so that the last step's solver error does not seed an antisymmetric
  // part the symmetric preconditioner would leave to plain GMRES.
  if (!mirror_partner_.empty()) keep_symmetric_part(s.rhs);
}

ode::GmresReport ImmersedBoundary::solve_increment(SemiImplicitStep& s) {
  // With the mobility preconditioner M ≈ A (exact to round-off with the FFT pressure solver),
  // GMRES solves A M⁻¹ y = rhs and e = M⁻¹ y: one iteration when M = A. Each operator application
  // spreads K M⁻¹ v_k and projects it; those fields are kept (basis_fields_), so that the
  // end-of-step force field P S K e is their combination with GMRES's coefficients.
  const bool preconditioned = settings_.preconditioner == Preconditioner::mobility;
  if (preconditioned) prepare_preconditioner(s.dt, s.stiffness);
  Eigen::VectorXd z;
  ode::LinearOperator op = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    if (preconditioned) apply_preconditioner(in, z);
    const Eigen::VectorXd& e = preconditioned ? z : in;
    Eigen::VectorXd rkv;
    apply_response(s.stiffness * e, rkv);
    // Keep the field by swapping buffers (the next projection overwrites all of scratch_).
    if (s.applied >= basis_fields_.size()) basis_fields_.push_back(scratch_.velocity);
    else std::swap(basis_fields_[s.applied], scratch_.velocity);
    ++s.applied;
    out = e - s.dt2 * rkv;
  };
  const ode::GmresReport krylov = ode::gmres_from_zero(op, s.rhs, s.correction, s.coefficients,
                                                       settings_.krylov_tolerance, settings_.krylov_max_iterations);
  if (preconditioned) {
    apply_preconditioner(s.correction, z);
    s.correction = z;
  }
  last_increment_ = s.x0 + s.correction;
  return krylov;
}

void ImmersedBoundary::apply_end_of_step_forces(const SemiImplicitStep& s, const ode::GmresReport& krylov) {
  // u^{n+1} = u_L + Δt P S (F + K ΔX) / ρ. The fluid holds u_L, plus Δt P S (F + K x0) / ρ when
  // merged; the rest is Δt P S K e / ρ, GMRES's combination of the kept fields.
  fluid::Velocity& u = fluid_.state().velocity;
  auto add = [&u](double c, const fluid::Velocity& g) {
    for (std::size_t k = 0; k < u.u.raw().size(); ++k) u.u.raw()[k] += c * g.u.raw()[k];
    for (std::size_t k = 0; k < u.v.raw().size(); ++k) u.v.raw()[k] += c * g.v.raw()[k];
  };
  if (krylov.coefficients_valid && s.coefficients.size() <= static_cast<Eigen::Index>(s.applied)) {
    if (!s.merged) add(s.dt, base_field_);
    for (Eigen::Index k = 0; k < s.coefficients.size(); ++k)
      add(s.dt * s.coefficients[k], basis_fields_[static_cast<std::size_t>(k)]);
  } else {  // GMRES restarted or stopped early: project the end-of-step forces afresh
    unflatten(s.merged ? Eigen::VectorXd(s.stiffness * s.correction) : Eigen::VectorXd(s.f0 + s.stiffness * last_increment_),
              work_);
    project_spread_forces(work_);
    add(s.dt, scratch_.velocity);
  }
  fluid::refresh_velocity_ghosts(u, fluid_.settings().boundaries);
}

void ImmersedBoundary::prepare_preconditioner(double dt_s, const Eigen::SparseMatrix<double>& stiffness) {
  const auto& x = body_.points.position;
  if (!mobility_ && !axisymmetric()) mobility_ = std::make_unique<MobilityMatrix>(transfer_);
  bool rebuild = mobility_points_.size() != x.size();
  if (!rebuild) {
    const fluid::MacGrid& g = transfer_.grid;
    const double limit = settings_.mobility_rebuild_cells * std::min(g.dx(), g.dy());
    for (std::size_t p = 0; p < x.size() && !rebuild; ++p) rebuild = !(norm(x[p] - mobility_points_[p]) <= limit);
  }
  const bool symmetric = !mirror_partner_.empty();
  if (rebuild && axisymmetric()) {
    // Rings: the table of AxisymmetricMobility (translation invariant along z only). With the
    // mirror symmetry (an axisymmetric scene always has it) only the rings are unknowns: the east
    // points and those on the axis, which spread half the force on them (spread()).
    if (!ring_mobility_) ring_mobility_ = std::make_unique<AxisymmetricMobility>(transfer_);
    const double rho = fluid_.settings().density_kg_per_m3;
    if (symmetric) {
      std::vector<Vec2> rings;
      std::vector<char> masked;
      std::vector<double> scale;
      for (int p : independent_) {
        const auto k = static_cast<std::size_t>(p);
        rings.push_back(x[k]);
        masked.push_back(has_targets_ ? is_target_[k] : 0);
        scale.push_back(mirror_partner_[k] == p ? 0.5 : 1.0);
      }
      Eigen::MatrixXd r;
      ring_mobility_->assemble(rings, masked, scale, rho, r);
      reduced_mobility_ = r(picked_rows_, picked_rows_);  // the symmetric unknowns' rows and columns
    } else {
      ring_mobility_->assemble(x, is_target_, {}, rho, mobility_matrix_);
    }
    mobility_points_ = x;
    ++mobility_builds_;
  } else if (rebuild) {
    mobility_->assemble(x, is_target_, fluid_.settings().density_kg_per_m3, independent_, mobility_matrix_,
                        pool_.get());
    mobility_points_ = x;
    ++mobility_builds_;
    // On the symmetric unknowns: R_s = (picked rows of R) Q, the velocity of the picked unknowns
    // per unit symmetric force (forces K Q y are symmetric: f = Q (picked f)).
    if (symmetric) reduced_mobility_ = (picked_rows_matrix_ * mobility_matrix_) * symmetric_basis_;
  }
  // M = I − Δt² R K, factored every step (Δt and K change); the unknowns are few. Symmetric:
  // M_s = I − Δt² R_s K_s with K_s = pick K Q.
  const double dt2 = dt_s * dt_s;
  if (symmetric) {
    const Eigen::SparseMatrix<double> k_s = pick_ * stiffness * symmetric_basis_;
    preconditioner_matrix_.noalias() = reduced_mobility_ * k_s;
  } else {
    preconditioner_matrix_.noalias() = mobility_matrix_ * stiffness;
  }
  preconditioner_matrix_ *= -dt2;
  preconditioner_matrix_.diagonal().array() += 1.0;
  factor_preconditioner();
}

void ImmersedBoundary::factor_preconditioner() {
  if (held_.empty()) {
    preconditioner_lu_.compute(preconditioner_matrix_);
    return;
  }
  // M = [M_mm M_mh; 0 I] (moving and held unknowns): M e = r gives e_h = r_h and
  // M_mm e_m = r_m − M_mh r_h.
  moving_block_ = preconditioner_matrix_(moving_, moving_);
  coupling_block_ = preconditioner_matrix_(moving_, held_);
  preconditioner_lu_.compute(moving_block_);
}

Eigen::VectorXd ImmersedBoundary::solve_preconditioner(const Eigen::VectorXd& v) const {
  if (held_.empty()) return preconditioner_lu_.solve(v);
  Eigen::VectorXd out = v;
  const Eigen::VectorXd held = v(held_);
  const Eigen::VectorXd moving = v(moving_) - coupling_block_ * held;
  const Eigen::VectorXd solved = preconditioner_lu_.solve(moving);
  out(moving_) = solved;
  return out;
}

void ImmersedBoundary::keep_symmetric_part(Eigen::VectorXd& v) const {
  for (std::size_t p = 0; p < mirror_partner_.size(); ++p) {
    const auto q = static_cast<std::size_t>(mirror_partner_[p]);
    if (q < p) continue;
    const auto a = 2 * static_cast<Eigen::Index>(p), b = 2 * static_cast<Eigen::Index>(q);
    const double x = 0.5 * (v[a] - v[b]), y = 0.5 * (v[a + 1] + v[b + 1]);
    v[a] = x;
    v[b] = -x;
    v[a + 1] = v[b + 1] = y;
  }
}

void ImmersedBoundary::apply_preconditioner(const Eigen::VectorXd& in, Eigen::VectorXd& out) const {
  if (mirror_partner_.empty()) {
    out = solve_preconditioner(in);
    return;
  }
  // in = s + a with s = ½(in + mirror(in)) symmetric: out = Q M_s⁻¹ (picked s) + a.
  Eigen::VectorXd symmetric = in;
  keep_symmetric_part(symmetric);
  const Eigen::VectorXd picked = pick_ * symmetric;
  out = in - symmetric + symmetric_basis_ * solve_preconditioner(picked);
}

std::string check_stability(const fluid::FlowState& flow, const elastic::Body& body, const StabilityLimits& limits,
                            const std::vector<double>* strain_reference) {
  const auto& x = body.points.position;
  const auto& v = body.points.velocity;
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (!std::isfinite(x[p].x) || !std::isfinite(x[p].y) || (p < v.size() && !std::isfinite(norm(v[p]))))
      return "numerical instability: marker " + std::to_string(p) + " has a non-finite position or velocity";
    if (p < v.size() && norm(v[p]) > limits.max_speed_m_per_s)
      return "numerical instability: marker " + std::to_string(p) + " at " + format_vec(x[p]) + " moves at " +
             format_number(norm(v[p])) + " m/s > max_speed = " + format_number(limits.max_speed_m_per_s) + " m/s";
  }
  auto check_field = [&](const fluid::Field& f, const char* name) -> std::string {
    for (int j = 0; j < f.count_y(); ++j)
      for (int i = 0; i < f.count_x(); ++i) {
        const double value = f(i, j);
        if (!(std::abs(value) <= limits.max_speed_m_per_s)) {
          return "numerical instability: fluid velocity " + std::string(name) + " = " + format_number(value) +
                 " m/s at " + format_vec(f.position(i, j)) + (std::isfinite(value) ? " exceeds max_speed = " +
                 format_number(limits.max_speed_m_per_s) + " m/s" : "");
        }
      }
    return {};
  };
  if (std::string p = check_field(flow.velocity.u, "u"); !p.empty()) return p;
  if (std::string p = check_field(flow.velocity.v, "v"); !p.empty()) return p;
  for (int j = 0; j < flow.pressure.count_y(); ++j)
    for (int i = 0; i < flow.pressure.count_x(); ++i)
      if (!std::isfinite(flow.pressure(i, j)))
        return "numerical instability: the fluid pressure is " + format_number(flow.pressure(i, j)) + " at " +
               format_vec(flow.pressure.position(i, j));
  const auto& lin = body.linear;
  for (std::size_t s = 0; s < lin.size(); ++s) {
    const double reference = strain_reference ? (*strain_reference)[s] : lin.rest_length[s];
    if (reference <= 0.0) continue;  // zero-length (pure tension) springs have no strain
    const double l = norm(x[lin.j[s]] - x[lin.i[s]]);
    const double strain = l / reference - 1.0;
    if (std::abs(strain) > limits.max_strain)
      return "structural instability: spring " + std::to_string(s) + " (points " + std::to_string(lin.i[s]) + "–" +
             std::to_string(lin.j[s]) + ") near " + format_vec(0.5 * (x[lin.i[s]] + x[lin.j[s]])) + " has strain " +
             format_number(strain) + " beyond max_strain = " + format_number(limits.max_strain);
  }
  const auto& ang = body.angular;
  for (std::size_t s = 0; s < ang.size(); ++s) {
    const double bend =
        elastic::wrap_angle(elastic::turning_angle(x[ang.i[s]], x[ang.j[s]], x[ang.k[s]]) - ang.rest_angle[s]);
    if (std::abs(bend) > limits.max_bend_rad)
      return "structural instability: joint " + std::to_string(s) + " at point " + std::to_string(ang.j[s]) + " " +
             format_vec(x[ang.j[s]]) + " is bent " + format_number(bend) + " rad from rest, beyond max_bend = " +
             format_number(limits.max_bend_rad) + " rad (the mesh folded)";
  }
  return {};
}

}  // namespace jellysim::coupling
