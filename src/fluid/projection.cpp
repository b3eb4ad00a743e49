#include "fluid/projection.hpp"

#include <algorithm>
#include <cmath>

namespace jellysim::fluid {

double cell_divergence(const Velocity& vel, int i, int j) {
  const MacGrid& g = vel.u.grid();
  return (vel.u(i + 1, j) - vel.u(i, j)) / g.dx() + (vel.v(i, j + 1) - vel.v(i, j)) / g.dy();
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
  const PoissonOperator op(g, b);
  const std::size_t n = static_cast<std::size_t>(g.cell_count());
  rhs_.resize(n);
  phi_.resize(n);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * g.nx + i;
      rhs_[k] = cell_divergence(state.velocity, i, j) / dt_s;  // eq. 3.3
      phi_[k] = state.pressure(i, j) / density_kg_per_m3;
    }
  const PressureSolveReport report = solver_->solve(op, rhs_, phi_);
  Field& p = state.pressure;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) p(i, j) = phi_[static_cast<std::size_t>(j) * g.nx + i];
  fill_pressure_ghosts(p, b);
  // Eq. 4.7: u = u* − Δt ∂φ/∂x on every face the pressure acts on (eq. 4.4 differences).
  const FaceRange ru = projected_u_faces(g, b);
  for (int j = ru.j_begin; j < ru.j_end; ++j)
    for (int i = ru.i_begin; i < ru.i_end; ++i) state.velocity.u(i, j) -= dt_s * (p(i, j) - p(i - 1, j)) / g.dx();
  const FaceRange rv = projected_v_faces(g, b);
  for (int j = rv.j_begin; j < rv.j_end; ++j)
    for (int i = rv.i_begin; i < rv.i_end; ++i) state.velocity.v(i, j) -= dt_s * (p(i, j) - p(i, j - 1)) / g.dy();
  refresh_velocity_ghosts(state.velocity, b);
  for (double& x : p.raw()) x *= density_kg_per_m3;
  return report;
}

}  // namespace jellysim::fluid
