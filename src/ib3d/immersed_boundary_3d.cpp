#include "jellysim/ib3d/immersed_boundary_3d.hpp"

#include <algorithm>
#include <stdexcept>

#include "jellysim/ode/gmres.hpp"

namespace jellysim::ib3d {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

fluid3d::Boundaries3d at_rest(fluid3d::Boundaries3d b) {
  for (auto& a : b.axis) a.wall_velocity = {};
  return b;
}

/// Zeroes component c outside its unknown faces (boundary faces, periodic copies, ghosts): a body
/// force acts only where the momentum equation is solved.
void zero_outside_unknowns(const fluid3d::Grid3d& g, const fluid3d::Boundaries3d& b, int c, fluid3d::Field3d& q) {
  const int lo = -fluid3d::Grid3d::ghosts;
  for (int d = 0; d < 3; ++d) {
    const auto range = fluid3d::unknown_range(g, b, c, d);
    const int a = (d + 1) % 3, e = (d + 2) % 3;
    for (int i = lo; i <= g.n(d) + fluid3d::Grid3d::ghosts; ++i) {
      if (i >= range[0] && i < range[1]) continue;
      for (int ie = lo; ie <= g.n(e) + fluid3d::Grid3d::ghosts; ++ie)
        for (int ia = lo; ia <= g.n(a) + fluid3d::Grid3d::ghosts; ++ia) {
          fluid3d::Index3 idx{};
          idx[static_cast<std::size_t>(d)] = i;
          idx[static_cast<std::size_t>(a)] = ia;
          idx[static_cast<std::size_t>(e)] = ie;
          q[g.index(idx[0], idx[1], idx[2])] = 0.0;
        }
    }
  }
}

void fill_zero(fluid3d::Velocity3d& v) {
  for (auto& q : v.c) std::fill(q.begin(), q.end(), 0.0);
}

/// Kernel self-overlap Σ_i φ(r − i)²: 3/8 for Peskin's 4-point function at any r (Peskin 2002,
/// eq. 6.27's third condition); the bilinear kernel's varies, 1/2 … 1, its mean 2/3 is used.
double self_overlap(coupling::Kernel k) { return k == coupling::Kernel::peskin4 ? 3.0 / 8.0 : 2.0 / 3.0; }

}  // namespace

std::string_view to_string(Scheme3d s) { return s == Scheme3d::explicit_euler ? "explicit" : "semi-implicit"; }
std::string_view to_string(Preconditioner3d p) { return p == Preconditioner3d::none ? "none" : "self-mobility"; }

Eigen::VectorXd flatten(std::span<const Vec3> v) {
  Eigen::VectorXd out(3 * static_cast<Eigen::Index>(v.size()));
  for (std::size_t m = 0; m < v.size(); ++m)
    for (std::size_t c = 0; c < 3; ++c) out[static_cast<Eigen::Index>(3 * m + c)] = v[m][c];
  return out;
}

void unflatten(const Eigen::VectorXd& in, std::vector<Vec3>& out) {
  out.resize(static_cast<std::size_t>(in.size() / 3));
  for (std::size_t m = 0; m < out.size(); ++m)
    for (std::size_t c = 0; c < 3; ++c) out[m][c] = in[static_cast<Eigen::Index>(3 * m + c)];
}

ImmersedBoundary3d::ImmersedBoundary3d(fluid3d::FluidSolver3d& fluid, Markers3d& markers, const ForceModel3d& forces,
                                       const CouplingSettings3d& settings)
    : fluid_(fluid),
      markers_(markers),
      forces_(forces),
      settings_(settings),
      pool_(std::make_unique<WorkerPool>(resolve_threads(settings.threads))),
      homogeneous_(at_rest(fluid.settings().boundaries)),
      transfer_(fluid.state().grid, fluid.settings().boundaries, settings.kernel, pool_.get()),
      pressure_(fluid3d::make_pressure_solver_3d("fft", fluid.state().grid, homogeneous_, {}, pool_.get())),
      scratch_(fluid.state().grid),
      rhs_(fluid.state().grid.padded_size(), 0.0),
      phi_(fluid.state().grid.padded_size(), 0.0),
      time_s_(fluid.state().time_s) {
  markers_.velocity.resize(markers_.size(), Vec3{});
  markers_.force.resize(markers_.size(), Vec3{});
}

void ImmersedBoundary3d::archive(core::StateArchive& a) {
  const core::StateArchive::Scope scope(a, "ib3d");
  a.value("time", time_s_);
  std::vector<double> increment(last_increment_.data(), last_increment_.data() + last_increment_.size());
  a.vector("last_increment", increment);
  if (a.is_restoring())
    last_increment_ = Eigen::Map<const Eigen::VectorXd>(increment.data(), static_cast<Eigen::Index>(increment.size()));
  a.values("marker_position", std::span<Vec3>(markers_.position));
  a.values("marker_velocity", std::span<Vec3>(markers_.velocity));
  a.values("marker_force", std::span<Vec3>(markers_.force));
}

double ImmersedBoundary3d::self_mobility() const {
  const double overlap = self_overlap(settings_.kernel);
  return (2.0 / 3.0) * overlap * overlap * overlap /
         (fluid_.settings().density_kg_per_m3 * fluid_.state().grid.cell_volume());
}

CoupledStepReport3d ImmersedBoundary3d::step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("ImmersedBoundary3d::step: the time step must be positive");
  CoupledStepReport3d r =
      settings_.scheme == Scheme3d::explicit_euler ? step_explicit(dt_s) : step_semi_implicit(dt_s);
  time_s_ += dt_s;
  return r;
}

void ImmersedBoundary3d::step_fluid_with_forces(double dt_s, std::span<const Vec3> force, CoupledStepReport3d& r) {
  auto t0 = Clock::now();
  fluid3d::Velocity3d& acc = fluid_.body_acceleration();
  fill_zero(acc);
  transfer_.spread(markers_.position, force, fluid_.settings().density_kg_per_m3, acc);
  r.transfer_s += seconds_since(t0);
  t0 = Clock::now();
  fluid_.step(dt_s);
  fill_zero(acc);
  r.fluid_s += seconds_since(t0);
}

void ImmersedBoundary3d::move_markers(double dt_s) {
  auto& x = markers_.position;
  transfer_.interpolate(fluid_.state().velocity, x, markers_.velocity);  // eq. 4.20
  for (std::size_t m = 0; m < x.size(); ++m)
    for (std::size_t c = 0; c < 3; ++c) x[m][c] += dt_s * markers_.velocity[m][c];
}

// Eqs. 4.19–4.21: forces at t^n, spread, the fluid step, the markers moved with the new flow.
CoupledStepReport3d ImmersedBoundary3d::step_explicit(double dt_s) {
  CoupledStepReport3d r;
  r.dt_s = dt_s;
  forces_.forces(time_s_, markers_.position, markers_.force);
  step_fluid_with_forces(dt_s, markers_.force, r);
  const auto t0 = Clock::now();
  move_markers(dt_s);
  r.transfer_s += seconds_since(t0);
  return r;
}

// Backward Euler exchange: from the guess x0 (the last increment), the fluid steps with the forces
// F + K x0 (u_L' = u_L + Δt P S (F + K x0)/(ρV)); the correction e = ΔX − x0 solves
//   (I − Δt² R K) e = Δt J u_L' − x0,
// and u^{n+1} = u_L' + Δt P S K e / (ρV). The stages below are that derivation's steps, in order.
CoupledStepReport3d ImmersedBoundary3d::step_semi_implicit(double dt_s) {
  CoupledStepReport3d r;
  r.dt_s = dt_s;
  SemiImplicitStep s;
  linearise_forces(dt_s, s);
  step_fluid_with_forces(dt_s, s.guess_forces, r);
  build_right_hand_side(s, r);
  const Eigen::VectorXd e = solve_correction(dt_s, s.rhs, s.predicted_norm, r);
  last_increment_ = s.x0 + e;
  const auto t0 = Clock::now();
  apply_end_of_step_forces(s, e, r);
  move_markers(dt_s);
  r.krylov_s += seconds_since(t0);
  return r;
}

void ImmersedBoundary3d::linearise_forces(double dt_s, SemiImplicitStep& s) {
  // Forces at the end of the step (t + Δt), positions linearised about Xⁿ; the guess x0.
  const auto& x = markers_.position;
  const std::size_t n = x.size();
  s.dt = dt_s;
  s.guess_forces.assign(n, Vec3{});
  std::vector<Vec3> f0(n);
  forces_.forces(time_s_ + dt_s, x, f0);
  s.x0 = last_increment_.size() == 3 * static_cast<Eigen::Index>(n) ? last_increment_
                                                                     : Eigen::VectorXd(dt_s * flatten(markers_.velocity));
  unflatten(s.x0, work_);
  forces_.jacobian_times(time_s_ + dt_s, x, work_, s.guess_forces);
  for (std::size_t m = 0; m < n; ++m)
    for (std::size_t c = 0; c < 3; ++c) s.guess_forces[m][c] += f0[m][c];
}

void ImmersedBoundary3d::build_right_hand_side(SemiImplicitStep& s, CoupledStepReport3d& r) {
  // Δt J u_L' (the increment the guess's forces give) − x0.
  const auto t0 = Clock::now();
  velocity_.resize(markers_.size());
  transfer_.interpolate(fluid_.state().velocity, markers_.position, velocity_);
  const Eigen::VectorXd predicted = s.dt * flatten(velocity_);
  s.predicted_norm = predicted.norm();
  s.rhs = predicted - s.x0;
  r.transfer_s += seconds_since(t0);
}

void ImmersedBoundary3d::apply_end_of_step_forces(const SemiImplicitStep& s, const Eigen::VectorXd& e,
                                                  CoupledStepReport3d& r) {
  // u += Δt P S K e / (ρV): the end-of-step force increment K e, projected, joins the flow.
  const std::size_t n = markers_.size();
  unflatten(e, work_);
  std::vector<Vec3> ke(n);
  forces_.jacobian_times(time_s_ + s.dt, markers_.position, work_, ke);
  project_spread(ke);
  ++r.projections;
  fluid3d::Velocity3d& u = fluid_.mutable_state().velocity;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < u.c[c].size(); ++i) u.c[c][i] += s.dt * scratch_.c[c][i];
  for (std::size_t m = 0; m < n; ++m)
    for (std::size_t c = 0; c < 3; ++c) markers_.force[m][c] = s.guess_forces[m][c] + ke[m][c];
}

Eigen::VectorXd ImmersedBoundary3d::solve_correction(double dt_s, const Eigen::VectorXd& rhs, double increment_norm,
                                                     CoupledStepReport3d& r) {
  const auto t0 = Clock::now();
  const bool preconditioned = prepare_preconditioner(dt_s);
  const double dt2 = dt_s * dt_s;
  const auto& x = markers_.position;
  std::vector<Vec3> ke(x.size());
  Eigen::VectorXd z, response;
  // Right-preconditioned: GMRES solves A M⁻¹ y = rhs, e = M⁻¹ y.
  const ode::LinearOperator op = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    z = preconditioned ? Eigen::VectorXd(preconditioner_.solve(in)) : in;
    unflatten(z, work_);
    forces_.jacobian_times(time_s_ + dt_s, x, work_, ke);
    apply_response(flatten(ke), response);
    ++r.projections;
    out = z - dt2 * response;
  };
  Eigen::VectorXd y, coefficients;
  // The residual is asked below tolerance × |ΔX| (the increment's size, not the guess's residual's:
  // a good guess needs few iterations). From zero, without restarts (a Krylov vector holds 3N
  // numbers: small beside a field).
  const double rhs_norm = rhs.norm();
  const double tolerance = rhs_norm > 0.0 ? settings_.krylov_tolerance * std::max(increment_norm, rhs_norm) / rhs_norm : 1.0;
  const ode::GmresReport g = ode::gmres_from_zero(op, rhs, y, coefficients, tolerance, settings_.krylov_max_iterations,
                                                  settings_.krylov_max_iterations);
  r.krylov_iterations = g.iterations;
  r.relative_residual = g.relative_residual;
  r.converged = g.converged;
  r.krylov_s += seconds_since(t0);
  return preconditioned ? Eigen::VectorXd(preconditioner_.solve(y)) : y;
}

bool ImmersedBoundary3d::prepare_preconditioner(double dt_s) {
  if (settings_.preconditioner == Preconditioner3d::none) return false;
  if (!forces_.stiffness(time_s_ + dt_s, markers_.position, stiffness_)) return false;
  const auto n = stiffness_.rows();
  Eigen::SparseMatrix<double> m(n, n);
  m.setIdentity();
  m -= (dt_s * dt_s * self_mobility()) * stiffness_;
  m.makeCompressed();
  preconditioner_.compute(m);
  return preconditioner_.info() == Eigen::Success;
}

void ImmersedBoundary3d::apply_response(const Eigen::VectorXd& f, Eigen::VectorXd& out) {
  unflatten(f, work_);
  project_spread(work_);
  velocity_.resize(work_.size());
  transfer_.interpolate(scratch_, markers_.position, velocity_);
  out = flatten(velocity_);
}

void ImmersedBoundary3d::project_spread(std::span<const Vec3> force) {
  fill_zero(scratch_);
  transfer_.spread(markers_.position, force, fluid_.settings().density_kg_per_m3, scratch_);
  project(scratch_);
}

// w ← P w: ∇²φ = ∇·w, w − ∇φ on the unknown faces, walls at rest.
void ImmersedBoundary3d::project(fluid3d::Velocity3d& w) {
  const fluid3d::Grid3d& g = fluid_.state().grid;
  for (int c = 0; c < 3; ++c) zero_outside_unknowns(g, homogeneous_, c, w.c[static_cast<std::size_t>(c)]);
  fluid3d::apply_velocity_boundaries(g, homogeneous_, w);
  fluid3d::for_each_interior_cell(g, [&](std::size_t I, int i, int j, int k) {
    rhs_[I] = fluid3d::divergence_at(g, w, i, j, k);
  });
  pressure_->solve(rhs_, phi_);
  for (int c = 0; c < 3; ++c) {
    const auto rx = fluid3d::unknown_range(g, homogeneous_, c, 0), ry = fluid3d::unknown_range(g, homogeneous_, c, 1),
               rz = fluid3d::unknown_range(g, homogeneous_, c, 2);
    const std::size_t s = g.stride(c);
    const double inv_h = 1.0 / g.h(c);
    fluid3d::Field3d& q = w.c[static_cast<std::size_t>(c)];
    for (int k = rz[0]; k < rz[1]; ++k)
      for (int j = ry[0]; j < ry[1]; ++j)
        for (int i = rx[0]; i < rx[1]; ++i) {
          const std::size_t I = g.index(i, j, k);
          q[I] -= inv_h * (phi_[I] - phi_[I - s]);
        }
  }
  fluid3d::apply_velocity_boundaries(g, homogeneous_, w);
}

}  // namespace jellysim::ib3d
