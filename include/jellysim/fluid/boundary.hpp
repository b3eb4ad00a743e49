#pragma once
// Boundary conditions per side of the rectangular domain (thesis §4.1.3, Figure 4.2), in the
// staggered-grid form of Griebel, Dornseifer & Neunhoeffer: the velocity component normal to a
// side lives on the side itself and is set directly; the tangential component gets a ghost value
// half a cell outside so that the linear interpolation onto the side gives the wanted value.
#include <algorithm>
#include <array>
#include <optional>
#include <string_view>

#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid {

enum class BoundaryType {
  no_slip,    ///< solid wall, fluid moves with the wall velocity (a moving lid if non-zero)
  free_slip,  ///< solid wall without friction: normal velocity = wall's, tangential free
  outflow,    ///< open side: zero normal derivative of the velocity, pressure 0 (Dirichlet)
  inflow,     ///< open side with a prescribed velocity (set like no-slip, Figure 4.2)
  periodic,   ///< wraps onto the opposite side; both opposite sides must be periodic
};

std::string_view to_string(BoundaryType type);
/// Parses "no-slip", "free-slip", "outflow", "inflow", "periodic"; nullopt otherwise.
std::optional<BoundaryType> boundary_type_from_string(std::string_view name);

enum class Side { west = 0, east = 1, south = 2, north = 3 };

struct BoundaryCondition {
  BoundaryType type = BoundaryType::no_slip;
  Vec2 velocity_m_per_s{};  ///< wall or in-flow velocity (ignored for outflow and periodic)
};

/// One condition per side. validate() throws std::invalid_argument when a periodic side is
/// paired with a non-periodic one.
struct Boundaries {
  BoundaryCondition west, east, south, north;

  const BoundaryCondition& operator[](Side s) const;
  void validate() const;
  bool periodic_x() const { return west.type == BoundaryType::periodic; }
  bool periodic_y() const { return south.type == BoundaryType::periodic; }
  /// The same sides with every prescribed velocity set to zero (for corrections of a solution).
  Boundaries homogeneous() const;

  static Boundaries all(BoundaryType type);
  /// The driven cavity of §8.1.3: no-slip walls, the north side moving tangentially.
  static Boundaries lid_driven_cavity(double lid_speed_m_per_s);
};

/// How the pressure is constrained on a side in the Poisson equation.
enum class PressureBoundary {
  neumann,    ///< zero normal derivative (walls, in-flow): eq. 4.10's zero edge coefficient
  dirichlet,  ///< p = 0 on the side (outflow)
  periodic,
};
PressureBoundary pressure_boundary_for(BoundaryType type);
std::array<PressureBoundary, 4> pressure_boundaries(const Boundaries& b);

/// Half-open index range [i_begin, i_end) × [j_begin, j_end) of the faces of one component.
struct FaceRange {
  int i_begin, i_end, j_begin, j_end;
};
/// Faces whose velocity the momentum equation updates: not on a non-periodic side.
FaceRange interior_u_faces(const MacGrid& g, const Boundaries& b);
FaceRange interior_v_faces(const MacGrid& g, const Boundaries& b);
/// Faces that the projection corrects: the interior ones plus the faces on outflow sides.
FaceRange projected_u_faces(const MacGrid& g, const Boundaries& b);
FaceRange projected_v_faces(const MacGrid& g, const Boundaries& b);

/// Reads a field where a wide stencil (limited fluxes, cubic interpolation) reaches beyond the
/// stored ghosts: wraps along a periodic axis of `b` (period = cells), otherwise repeats the
/// outermost stored sample.
class StencilReader {
 public:
  StencilReader(const Field& f, const Boundaries& b)
      : f_(f), period_x_(b.periodic_x() ? f.grid().nx : 0), period_y_(b.periodic_y() ? f.grid().ny : 0) {}
  double operator()(int i, int j) const { return f_(index(i, f_.count_x(), period_x_), index(j, f_.count_y(), period_y_)); }

 private:
  static int index(int i, int count, int period) {
    if (i >= -1 && i <= count) return i;
    return period > 0 ? ((i % period) + period) % period : std::clamp(i, -1, count);
  }
  const Field& f_;
  int period_x_, period_y_;
};

/// Sets every boundary value of Figure 4.2: wall and in-flow normal velocities, outflow normal
/// velocities copied from the first interior face, periodic copies and all ghost values.
void apply_velocity_boundaries(Velocity& vel, const Boundaries& b);
/// Like apply_velocity_boundaries but keeps the normal velocity on outflow sides as it is (used
/// after a projection, which computed it).
void refresh_velocity_ghosts(Velocity& vel, const Boundaries& b);

}  // namespace jellysim::fluid
