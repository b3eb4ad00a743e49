#include "jellysim/fluid/projection.hpp"

#include "jellysim/core/state_archive.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::fluid {

double cell_divergence(const Velocity& vel, int i, int j) {
  const MacGrid& g = vel.u.grid();
  return (vel.u(i + 1, j) - vel.u(i, j)) / g.dx() + (vel.v(i, j + 1) - vel.v(i, j)) / g.dy();
}

double axisymmetric_cell_divergence(const Velocity& vel, int i, int j) {
  const MacGrid& g = vel.u.grid();
  return (static_cast<double>(i + 1) * vel.u(i + 1, j) - static_cast<double>(i) * vel.u(i, j)) / ((i + 0.5) * g.dx()) +
         (vel.v(i, j + 1) - vel.v(i, j)) / g.dy();
}

double max_divergence(const Velocity& vel, Geometry geometry) {
  if (geometry == Geometry::planar) return max_divergence(vel);
  const MacGrid& g = vel.u.grid();
  double m = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) m = std::max(m, std::abs(axisymmetric_cell_divergence(vel, i, j)));
  return m;
}

Field divergence(const Velocity& vel) {
  const MacGrid& g = vel.u.grid();
  Field d(g, kCellCentres);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) d(i, j) = cell_divergence(vel, i, j);
  return d;
}

double max_divergence(const Velocity& vel) {
  const MacGrid& g = vel.u.grid();
  double m = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) m = std::max(m, std::abs(cell_divergence(vel, i, j)));
  return m;
}

namespace {

double ghost_value(PressureBoundary side, double inside, double opposite) {
  switch (side) {
    case PressureBoundary::neumann: return inside;
    case PressureBoundary::dirichlet: return -inside;
    case PressureBoundary::periodic: return opposite;
  }
  return inside;
}

}  // namespace

void fill_pressure_ghosts(Field& p, const Boundaries& b) {
  const auto sides = pressure_boundaries(b);
  const int nx = p.grid().nx;
  const int ny = p.grid().ny;
  for (int j = 0; j < ny; ++j) {
    p(-1, j) = ghost_value(sides[0], p(0, j), p(nx - 1, j));
    p(nx, j) = ghost_value(sides[1], p(nx - 1, j), p(0, j));
  }
  for (int i = -1; i <= nx; ++i) {
    p(i, -1) = ghost_value(sides[2], p(i, 0), p(i, ny - 1));
    p(i, ny) = ghost_value(sides[3], p(i, ny - 1), p(i, 0));
  }
}

PressureSolveReport Projector::project(FlowState& state, const Boundaries& b, double dt_s,
                                       double density_kg_per_m3) {
  const MacGrid& g = state.grid;
  const bool radial = geometry_ == Geometry::axisymmetric;
  const PoissonOperator op = radial ? PoissonOperator::axisymmetric(g.nx, g.ny, g.dx(), g.dy(), pressure_boundaries(b))
                                    : PoissonOperator(g, b);
  const std::size_t n = static_cast<std::size_t>(g.cell_count());
  rhs_.resize(n);
  phi_.resize(n);
  const double inv_dx = 1.0 / g.dx();
  const double inv_dy = 1.0 / g.dy();
  const double inv_dt = 1.0 / dt_s;
  const double inv_rho = 1.0 / density_kg_per_m3;
  const Field& u = state.velocity.u;
  const Field& v = state.velocity.v;
  // Initial guess φ = p/ρ, or the extrapolation φ_n + (φ_n − φ_{n−1})·Δt/Δt_n when the state's
  // pressure is still exactly what the last projection stored (nobody edited it) on the same
  // grid. The extrapolation is written while the pressure is compared; a mismatch redoes the guess.
  const bool guess = solver_->uses_initial_guess();
  const bool history = guess && extrapolate_ && have_previous_ && last_phi_.size() == n && previous_phi_.size() == n &&
                       last_dt_s_ > 0.0;
  const double ratio = history ? dt_s / last_dt_s_ : 0.0;
  bool unchanged = history;
  for (int j = 0; j < g.ny; ++j) {
    const double* ur = u.ptr(0, j);
    const double* vr = v.ptr(0, j);
    const double* vn = v.ptr(0, j + 1);
    const double* pr = state.pressure.ptr(0, j);
    const std::size_t row = static_cast<std::size_t>(j) * g.nx;
    double* rhs = rhs_.data() + row;
    double* phi = phi_.data() + row;
    if (radial) {  // (1/r) ∂(r u)/∂r with face radii iΔr, cell radii (i + ½)Δr
      for (int i = 0; i < g.nx; ++i)
        rhs[i] = ((static_cast<double>(i + 1) * ur[i + 1] - static_cast<double>(i) * ur[i]) / (i + 0.5) * inv_dx +
                  (vn[i] - vr[i]) * inv_dy) * inv_dt;
    } else {
      for (int i = 0; i < g.nx; ++i) rhs[i] = ((ur[i + 1] - ur[i]) * inv_dx + (vn[i] - vr[i]) * inv_dy) * inv_dt;  // eq. 3.3
    }
    if (history) {
      const double* last = last_phi_.data() + row;
      const double* previous = previous_phi_.data() + row;
      bool same = true;
      for (int i = 0; i < g.nx; ++i) {
        same &= pr[i] == last[i] * density_kg_per_m3;  // as stored below
        phi[i] = last[i] + (last[i] - previous[i]) * ratio;
      }
      unchanged = unchanged && same;
    } else if (guess) {
      for (int i = 0; i < g.nx; ++i) phi[i] = pr[i] * inv_rho;
    }
  }
  if (history && !unchanged)
    for (int j = 0; j < g.ny; ++j) {
      const double* pr = state.pressure.ptr(0, j);
      double* phi = phi_.data() + static_cast<std::size_t>(j) * g.nx;
      for (int i = 0; i < g.nx; ++i) phi[i] = pr[i] * inv_rho;
    }
  const PressureSolveReport report = solver_->solve(op, rhs_, phi_);
  // p = ρφ with ghosts, then eq. 4.7: u = u* − Δt ∂φ/∂x = u* − Δt/ρ ∂p/∂x on every face the
  // pressure acts on (eq. 4.4 differences).
  Field& p = state.pressure;
  for (int j = 0; j < g.ny; ++j) {
    const double* phi = phi_.data() + static_cast<std::size_t>(j) * g.nx;
    double* pr = p.ptr(0, j);
    for (int i = 0; i < g.nx; ++i) pr[i] = phi[i] * density_kg_per_m3;
  }
  fill_pressure_ghosts(p, b);
  const double gx = dt_s * inv_rho * inv_dx;
  const double gy = dt_s * inv_rho * inv_dy;
  const FaceRange ru = projected_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j) {
    const double* pr = p.ptr(0, j);
    double* ur = state.velocity.u.ptr(0, j);
    for (int i = ru.i_begin; i < ru.i_end; ++i) ur[i] -= gx * (pr[i] - pr[i - 1]);
  }
  const FaceRange rv = projected_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j) {
    const double* pr = p.ptr(0, j);
    const double* ps = p.ptr(0, j - 1);
    double* vr = state.velocity.v.ptr(0, j);
    for (int i = rv.i_begin; i < rv.i_end; ++i) vr[i] -= gy * (pr[i] - ps[i]);
  }
  refresh_velocity_ghosts(state.velocity, b);
  if (extrapolate_) {  // keep φ_n and φ_{n−1} for the next guess (buffers rotate, no copy)
    std::swap(previous_phi_, last_phi_);
    std::swap(last_phi_, phi_);
    have_previous_ = have_last_ && previous_phi_.size() == n;
    have_last_ = true;
    last_dt_s_ = dt_s;
  }
  return report;
}

void Projector::archive(core::StateArchive& a) {
  a.vector("last_phi", last_phi_);
  a.vector("previous_phi", previous_phi_);
  a.value("last_dt", last_dt_s_);
  a.value("have_previous", have_previous_);
  a.value("have_last", have_last_);
}

}  // namespace jellysim::fluid
