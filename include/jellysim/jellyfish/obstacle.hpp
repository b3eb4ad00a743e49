#pragma once
// Rigid obstacles in the immersed-boundary fluid (beyond the thesis, which only had the tank's
// walls): the outline of a circle, box or polygon is a ring of massless markers, each tied by a
// stiff zero-length spring to its own target point (Peskin's "target points"). The targets are
// pinned, or follow a prescribed path; the fluid flows around the outline because any slip
// stretches the tethers, whose force the coupling spreads back into the fluid. The sum of the
// tether forces is the force the fluid exerts on the obstacle (its drag and lift).
#include <memory>
#include <string>
#include <vector>

#include "jellysim/elastic/body.hpp"
#include "jellysim/math/vec2.hpp"

namespace jellysim::jellyfish {

enum class ObstacleShape { circle, box, polygon };

/// A prescribed path of the obstacle's targets: p(t) = p0 + v t + a sin(2π f t).
struct ObstacleMotion {
  Vec2 velocity_m_per_s{};   ///< steady drift
  Vec2 amplitude_m{};        ///< oscillation amplitude
  double frequency_hz = 0.0; ///< oscillation frequency
  bool moving() const;
  Vec2 offset(double t) const;     ///< displacement from the start at time t
  Vec2 velocity(double t) const;   ///< its time derivative
};

struct ObstacleSpec {
  std::string name;            ///< for messages ("objects[2] (circle)")
  ObstacleShape shape = ObstacleShape::circle;
  Vec2 centre_m{};             ///< circle and box centre
  double radius_m = 0.0;       ///< circle
  Vec2 size_m{};               ///< box width and height
  double angle_rad = 0.0;      ///< box rotation, counter-clockwise
  std::vector<Vec2> vertices_m;///< polygon, either orientation, not self-intersecting
  /// The tethers' stiffness per metre of outline and of depth (N/m²): each marker's tether gets the
  /// share of the outline it stands for, so the obstacle gives the same under a load at any marker
  /// spacing (40,000 N/m² is 50 N/m per marker 1.25 mm apart).
  double tether_stiffness_n_per_m2 = 40000.0;
  /// Per marker and metre of depth instead (the scene field `stiffness`, IB2d's way); 0: unset.
  double tether_stiffness_n_per_m = 0.0;
  ObstacleMotion motion;
};

/// The closed outline (vertices, counter-clockwise) of an obstacle at its start position.
std::vector<Vec2> obstacle_outline(const ObstacleSpec& spec);
/// The outline resampled so that neighbouring markers are at most max_spacing_m apart.
std::vector<Vec2> obstacle_markers(const ObstacleSpec& spec, double max_spacing_m);
/// Checks the spec; throws std::invalid_argument naming the field and its allowed range.
void validate(const ObstacleSpec& spec);

/// Where an obstacle's markers and targets live in the coupled body.
struct ObstacleParts {
  std::vector<int> markers;  ///< outline markers, counter-clockwise (fluid-carried points)
  std::vector<int> targets;  ///< one pinned or prescribed target per marker
  std::vector<int> tethers;  ///< one zero-length linear spring per marker, index into body.linear
  std::shared_ptr<Vec2> shift;  ///< added to every target's path (dragging the obstacle)
};

/// Adds the obstacle's markers, targets and tethers to `body`.
ObstacleParts add_obstacle(const ObstacleSpec& spec, double max_spacing_m, elastic::Body& body);

/// The force of the fluid on the obstacle (N per metre of depth): the tethers pull the markers
/// toward the targets, and the markers pass that force to the fluid; the fluid pushes back on the
/// obstacle with the sum of the tether forces on the targets.
Vec2 obstacle_fluid_force(const ObstacleParts& parts, const elastic::Body& body);

/// True when the point lies inside the closed polygon (even–odd rule).
bool point_in_polygon(Vec2 p, const std::vector<Vec2>& polygon);
/// Signed area of a closed polygon (positive when counter-clockwise).
double polygon_area(const std::vector<Vec2>& polygon);
/// True when the two closed polygons overlap (an edge crosses or one contains the other).
bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

}  // namespace jellysim::jellyfish
