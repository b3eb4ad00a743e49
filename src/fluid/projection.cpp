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

namespace {

// Row j of the pressure equation's right-hand side ∇·u*/Δt (eq. 3.3); axisymmetric:
// (1/r) ∂(r u)/∂r with face radii iΔr, cell radii (i + ½)Δr.
void poisson_rhs_row(const Velocity& vel, int j, bool radial, double inv_dx, double inv_dy, double inv_dt,
                     double* rhs) {
  const int nx = vel.u.grid().nx;
  const double* ur = vel.u.ptr(0, j);
  const double* vr = vel.v.ptr(0, j);
  const double* vn = vel.v.ptr(0, j + 1);
  if (radial) {
    for (int i = 0; i < nx; ++i)
      rhs[i] = ((static_cast<double>(i + 1) * ur[i + 1] - static_cast<double>(i) * ur[i]) / (i + 0.5) * inv_dx +
                (vn[i] - vr[i]) * inv_dy) * inv_dt;
  } else {
    for (int i = 0; i < nx; ++i) rhs[i] = ((ur[i + 1] - ur[i]) * inv_dx + (vn[i] - vr[i]) * inv_dy) * inv_dt;
  }
}

// One row of the extrapolated guess φ_n + (φ_n − φ_{n−1})·Δt/Δt_n; whether the row's pressure is
// still the stored ρφ_n (compared while the guess is written).
bool extrapolate_phi_row(const double* pr, const double* last, const double* previous, int nx, double ratio,
                         double density_kg_per_m3, double* phi) {
  bool same = true;
  for (int i = 0; i < nx; ++i) {
    same &= pr[i] == last[i] * density_kg_per_m3;  // as stored by store_pressure
    phi[i] = last[i] + (last[i] - previous[i]) * ratio;
  }
  return same;
}

// The guess φ = p/ρ for row j.
void phi_from_pressure_row(const Field& p, int j, double inv_rho, double* phi) {
  const double* pr = p.ptr(0, j);
  for (int i = 0; i < p.grid().nx; ++i) phi[i] = pr[i] * inv_rho;
}

// p = ρφ on the cells (ghosts not set).
void store_pressure(const std::vector<double>& phi, double density_kg_per_m3, Field& p) {
  const MacGrid& g = p.grid();
  for (int j = 0; j < g.ny; ++j) {
    const double* row = phi.data() + static_cast<std::size_t>(j) * g.nx;
    double* pr = p.ptr(0, j);
    for (int i = 0; i < g.nx; ++i) pr[i] = row[i] * density_kg_per_m3;
  }
}

// Eq. 4.7: u = u* − Δt/ρ ∂p/∂x on every face the pressure acts on (eq. 4.4 differences);
// gx = Δt/(ρΔx), gy = Δt/(ρΔy).
void subtract_pressure_gradient(const Field& p, const Boundaries& b, double gx, double gy, Velocity& vel) {
  const MacGrid& g = p.grid();
  const FaceRange ru = projected_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j) {
    const double* pr = p.ptr(0, j);
    double* ur = vel.u.ptr(0, j);
    for (int i = ru.i_begin; i < ru.i_end; ++i) ur[i] -= gx * (pr[i] - pr[i - 1]);
  }
  const FaceRange rv = projected_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j) {
    const double* pr = p.ptr(0, j);
    const double* ps = p.ptr(0, j - 1);
    double* vr = vel.v.ptr(0, j);
    for (int i = rv.i_begin; i < rv.i_end; ++i) vr[i] -= gy * (pr[i] - ps[i]);
  }
}

}  // namespace

// Initial guess φ = p/ρ, or the extrapolation φ_n + (φ_n − φ_{n−1})·Δt/Δt_n when the state's
// pressure is still exactly what the last projection stored (nobody edited it) on the same
// grid. The extrapolation is written while the pressure is compared; a mismatch redoes the guess.
void Projector::prepare_rhs_and_guess(const FlowState& state, double dt_s, double density_kg_per_m3) {
  const MacGrid& g = state.grid;
  const bool radial = geometry_ == Geometry::axisymmetric;
  const std::size_t n = static_cast<std::size_t>(g.cell_count());
  const double inv_dx = 1.0 / g.dx();
  const double inv_dy = 1.0 / g.dy();
  const double inv_dt = 1.0 / dt_s;
  const double inv_rho = 1.0 / density_kg_per_m3;
  const bool guess = solver_->uses_initial_guess();
  const bool history = guess && extrapolate_ && have_previous_ && last_phi_.size() == n && previous_phi_.size() == n &&
                       last_dt_s_ > 0.0;
  const double ratio = history ? dt_s / last_dt_s_ : 0.0;
  bool unchanged = history;
  for (int j = 0; j < g.ny; ++j) {
    const std::size_t row = static_cast<std::size_t>(j) * g.nx;
    poisson_rhs_row(state.velocity, j, radial, inv_dx, inv_dy, inv_dt, rhs_.data() + row);
    if (history) {
      const bool same = extrapolate_phi_row(state.pressure.ptr(0, j), last_phi_.data() + row,
                                            previous_phi_.data() + row, g.nx, ratio, density_kg_per_m3,
                                            phi_.data() + row);
      unchanged = unchanged && same;
    } else if (guess) {
      phi_from_pressure_row(state.pressure, j, inv_rho, phi_.data() + row);
    }
  }
  if (history && !unchanged)
    for (int j = 0; j < g.ny; ++j)
      phi_from_pressure_row(state.pressure, j, inv_rho, phi_.data() + static_cast<std::size_t>(j) * g.nx);
}

void Projector::remember_phi(double dt_s) {
  const std::size_t n = phi_.size();
  std::swap(previous_phi_, last_phi_);
  std::swap(last_phi_, phi_);
  have_previous_ = have_last_ && previous_phi_.size() == n;
  have_last_ = true;
  last_dt_s_ = dt_s;
}

// Solves ∇²φ = ∇·u*/Δt, stores p = ρφ with ghosts and subtracts Δt ∇φ from the velocity.
PressureSolveReport Projector::project(FlowState& state, const Boundaries& b, double dt_s,
                                       double density_kg_per_m3) {
  const MacGrid& g = state.grid;
  const PoissonOperator op = geometry_ == Geometry::axisymmetric
                                 ? PoissonOperator::axisymmetric(g.nx, g.ny, g.dx(), g.dy(), pressure_boundaries(b))
                                 : PoissonOperator(g, b);
  const std::size_t n = static_cast<std::size_t>(g.cell_count());
  rhs_.resize(n);
  phi_.resize(n);
  prepare_rhs_and_guess(state, dt_s, density_kg_per_m3);
  const PressureSolveReport report = solver_->solve(op, rhs_, phi_);
  store_pressure(phi_, density_kg_per_m3, state.pressure);
  fill_pressure_ghosts(state.pressure, b);
  const double inv_rho = 1.0 / density_kg_per_m3;
  subtract_pressure_gradient(state.pressure, b, dt_s * inv_rho * (1.0 / g.dx()), dt_s * inv_rho * (1.0 / g.dy()),
                             state.velocity);
  refresh_velocity_ghosts(state.velocity, b);
  if (extrapolate_) remember_phi(dt_s);
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
