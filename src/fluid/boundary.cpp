#include "jellysim/fluid/boundary.hpp"

#include <stdexcept>
#include <string>

namespace jellysim::fluid {

std::string_view to_string(BoundaryType type) {
  switch (type) {
    case BoundaryType::no_slip: return "no-slip";
    case BoundaryType::free_slip: return "free-slip";
    case BoundaryType::outflow: return "outflow";
    case BoundaryType::inflow: return "inflow";
    case BoundaryType::periodic: return "periodic";
  }
  return "unknown";
}

std::optional<BoundaryType> boundary_type_from_string(std::string_view name) {
  for (BoundaryType t : {BoundaryType::no_slip, BoundaryType::free_slip, BoundaryType::outflow,
                         BoundaryType::inflow, BoundaryType::periodic})
    if (to_string(t) == name) return t;
  return std::nullopt;
}

const BoundaryCondition& Boundaries::operator[](Side s) const {
  switch (s) {
    case Side::west: return west;
    case Side::east: return east;
    case Side::south: return south;
    case Side::north: return north;
  }
  return west;
}

void Boundaries::validate() const {
  const bool wp = west.type == BoundaryType::periodic;
  const bool ep = east.type == BoundaryType::periodic;
  const bool sp = south.type == BoundaryType::periodic;
  const bool np = north.type == BoundaryType::periodic;
  if (wp != ep) throw std::invalid_argument("periodic boundary on west needs periodic east and vice versa");
  if (sp != np) throw std::invalid_argument("periodic boundary on south needs periodic north and vice versa");
}

Boundaries Boundaries::homogeneous() const {
  Boundaries h = *this;
  for (BoundaryCondition* c : {&h.west, &h.east, &h.south, &h.north}) c->velocity_m_per_s = {};
  return h;
}

Boundaries Boundaries::all(BoundaryType type) {
  const BoundaryCondition c{type, {}};
  return {c, c, c, c};
}

Boundaries Boundaries::lid_driven_cavity(double lid_speed_m_per_s) {
  Boundaries b = all(BoundaryType::no_slip);
  b.north.velocity_m_per_s = {lid_speed_m_per_s, 0.0};
  return b;
}

PressureBoundary pressure_boundary_for(BoundaryType type) {
  switch (type) {
    case BoundaryType::outflow: return PressureBoundary::dirichlet;
    case BoundaryType::periodic: return PressureBoundary::periodic;
    default: return PressureBoundary::neumann;
  }
}

std::array<PressureBoundary, 4> pressure_boundaries(const Boundaries& b) {
  return {pressure_boundary_for(b.west.type), pressure_boundary_for(b.east.type),
          pressure_boundary_for(b.south.type), pressure_boundary_for(b.north.type)};
}

FaceRange interior_u_faces(const MacGrid& g, const Boundaries& b) {
  return {b.periodic_x() ? 0 : 1, g.nx, 0, g.ny};
}

FaceRange interior_v_faces(const MacGrid& g, const Boundaries& b) {
  return {0, g.nx, b.periodic_y() ? 0 : 1, g.ny};
}

FaceRange projected_u_faces(const MacGrid& g, const Boundaries& b) {
  FaceRange r = interior_u_faces(g, b);
  if (b.west.type == BoundaryType::outflow) r.i_begin = 0;
  if (b.east.type == BoundaryType::outflow) r.i_end = g.nx + 1;
  return r;
}

FaceRange projected_v_faces(const MacGrid& g, const Boundaries& b) {
  FaceRange r = interior_v_faces(g, b);
  if (b.south.type == BoundaryType::outflow) r.j_begin = 0;
  if (b.north.type == BoundaryType::outflow) r.j_end = g.ny + 1;
  return r;
}

namespace {

bool is_wall_like(BoundaryType t) {
  return t == BoundaryType::no_slip || t == BoundaryType::free_slip || t == BoundaryType::inflow;
}

// Tangential ghost: mirror about the prescribed value (no-slip, in-flow) or copy (free-slip,
// outflow), so that the average of ghost and first interior value equals the side's value.
double tangential_ghost(const BoundaryCondition& c, double interior, double wall_tangential) {
  if (c.type == BoundaryType::no_slip || c.type == BoundaryType::inflow)
    return 2.0 * wall_tangential - interior;
  return interior;
}

// Normal component on a side. `inner` is the first face inside, `inner2` the second.
// Returns the value on the side and the extra ghost beyond it.
struct NormalValues {
  double side, ghost;
};
NormalValues normal_values(const BoundaryCondition& c, double current_side, double inner,
                           bool copy_outflow, double wall_normal) {
  if (is_wall_like(c.type)) return {wall_normal, 2.0 * wall_normal - inner};
  const double side = copy_outflow ? inner : current_side;  // outflow: zero normal derivative
  return {side, side};
}

void apply_normal_u(Field& u, const Boundaries& b, bool copy_outflow) {
  const int nx = u.grid().nx;
  const int ny = u.grid().ny;
  for (int j = 0; j < ny; ++j) {
    if (b.periodic_x()) {
      u(nx, j) = u(0, j);
      u(-1, j) = u(nx - 1, j);
      u(nx + 1, j) = u(1, j);
      continue;
    }
    const NormalValues w = normal_values(b.west, u(0, j), u(1, j), copy_outflow, b.west.velocity_m_per_s.x);
    u(0, j) = w.side;
    u(-1, j) = w.ghost;
    const NormalValues e =
        normal_values(b.east, u(nx, j), u(nx - 1, j), copy_outflow, b.east.velocity_m_per_s.x);
    u(nx, j) = e.side;
    u(nx + 1, j) = e.ghost;
  }
}

void apply_normal_v(Field& v, const Boundaries& b, bool copy_outflow) {
  const int nx = v.grid().nx;
  const int ny = v.grid().ny;
  for (int i = 0; i < nx; ++i) {
    if (b.periodic_y()) {
      v(i, ny) = v(i, 0);
      v(i, -1) = v(i, ny - 1);
      v(i, ny + 1) = v(i, 1);
      continue;
    }
    const NormalValues s =
        normal_values(b.south, v(i, 0), v(i, 1), copy_outflow, b.south.velocity_m_per_s.y);
    v(i, 0) = s.side;
    v(i, -1) = s.ghost;
    const NormalValues n =
        normal_values(b.north, v(i, ny), v(i, ny - 1), copy_outflow, b.north.velocity_m_per_s.y);
    v(i, ny) = n.side;
    v(i, ny + 1) = n.ghost;
  }
}

void apply_tangential_v(Field& v, const Boundaries& b) {
  const int nx = v.grid().nx;
  const int ny = v.grid().ny;
  for (int j = -1; j <= ny + 1; ++j) {
    if (b.periodic_x()) {
      v(-1, j) = v(nx - 1, j);
      v(nx, j) = v(0, j);
      continue;
    }
    v(-1, j) = tangential_ghost(b.west, v(0, j), b.west.velocity_m_per_s.y);
    v(nx, j) = tangential_ghost(b.east, v(nx - 1, j), b.east.velocity_m_per_s.y);
  }
}

void apply_tangential_u(Field& u, const Boundaries& b) {
  const int nx = u.grid().nx;
  const int ny = u.grid().ny;
  for (int i = -1; i <= nx + 1; ++i) {
    if (b.periodic_y()) {
      u(i, -1) = u(i, ny - 1);
      u(i, ny) = u(i, 0);
      continue;
    }
    u(i, -1) = tangential_ghost(b.south, u(i, 0), b.south.velocity_m_per_s.x);
    u(i, ny) = tangential_ghost(b.north, u(i, ny - 1), b.north.velocity_m_per_s.x);
  }
}

void apply_boundaries(Velocity& vel, const Boundaries& b, bool copy_outflow) {
  // Normal components first (they sit on the sides), then the tangential ghosts, which may read
  // normal values near the corners.
  apply_normal_u(vel.u, b, copy_outflow);
  apply_normal_v(vel.v, b, copy_outflow);
  apply_tangential_v(vel.v, b);
  apply_tangential_u(vel.u, b);
}

}  // namespace

void apply_velocity_boundaries(Velocity& vel, const Boundaries& b) { apply_boundaries(vel, b, true); }

void refresh_velocity_ghosts(Velocity& vel, const Boundaries& b) { apply_boundaries(vel, b, false); }

}  // namespace jellysim::fluid
