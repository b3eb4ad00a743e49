#pragma once
// An elastic body as a spring-mass system (thesis ch. 2) in structure-of-arrays form.
#include "jellysim/math/vec2.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace jellysim::elastic {

enum class PointKind : std::uint8_t {
  Free,        ///< finite mass, integrated
  Pinned,      ///< infinite mass: never moves
  Prescribed,  ///< position is a given function of time (e.g. driven attachment)
};

/// Position, velocity and acceleration of a prescribed point at time t.
struct PrescribedState {
  Vec2 position, velocity, acceleration;
};
using PrescribedMotion = std::function<PrescribedState(double t)>;

/// Point masses, one entry per point in each array.
struct PointMasses {
  std::vector<Vec2> position;         ///< m
  std::vector<Vec2> velocity;         ///< m/s
  std::vector<double> mass;           ///< kg (ignored for pinned/prescribed points)
  std::vector<PointKind> kind;
  std::vector<int> motion;            ///< index into Body::prescribed for Prescribed points, else -1

  std::size_t size() const { return position.size(); }
};

struct LinearSprings {
  std::vector<int> i, j;
  std::vector<double> stiffness;      ///< κ_l, N/m
  std::vector<double> rest_length;    ///< l_r, m
  std::size_t size() const { return i.size(); }
};

struct AngularSprings {
  std::vector<int> i, j, k;           ///< j is the vertex
  std::vector<double> stiffness;      ///< κ_θ, N·m/rad
  std::vector<double> rest_angle;     ///< θ_r, rad (signed turning angle, see forces.hpp)
  std::size_t size() const { return i.size(); }
};

// IB2d's structural laws (see forces.hpp and ib2d_structure.hpp).

/// Torsional beams (IB2d ".beam"): E = ½ k (c − C)², c = (x_k − x_j) × (x_j − x_i).
struct TorsionalBeams {
  std::vector<int> i, j, k;           ///< j is the middle point
  std::vector<double> stiffness;      ///< k, N/m³ (= J/m⁴, as c is in m²)
  std::vector<double> curvature;      ///< C, m²
  std::size_t size() const { return i.size(); }
};

/// Non-invariant beams (IB2d ".nonInv_beam"): E = ½ k |x_i − 2 x_j + x_k − C|².
struct NonInvariantBeams {
  std::vector<int> i, j, k;           ///< j is the middle point
  std::vector<double> stiffness;      ///< k, N/m
  std::vector<Vec2> curvature;        ///< C, m
  std::size_t size() const { return i.size(); }
};

/// Power-law springs (IB2d ".spring" with degree α): E = ½ k |l − l_r|^(α+1).
struct PowerSprings {
  std::vector<int> i, j;
  std::vector<double> stiffness;      ///< k, N/m^α
  std::vector<double> rest_length;    ///< l_r, m
  std::vector<double> degree;         ///< α ∈ [1, 10]
  std::size_t size() const { return i.size(); }
};

/// Dashpots along the line between two points (for IB2d ".d_spring"): F_i = b ((v_j − v_i)·d̂) d̂.
struct Dashpots {
  std::vector<int> i, j;
  std::vector<double> coefficient;    ///< b, kg/s
  std::size_t size() const { return i.size(); }
};

/// Local fluid velocity at a point (drag hook, eq. 2.17); empty = still fluid.
using FluidVelocityField = std::function<Vec2(Vec2 position, double t)>;

struct Body {
  PointMasses points;
  LinearSprings linear;
  AngularSprings angular;
  TorsionalBeams torsional;
  NonInvariantBeams non_invariant;
  PowerSprings power;
  Dashpots dashpots;
  double drag_coefficient = 0.0;      ///< κ_d, kg/s
  Vec2 gravity{0.0, 0.0};             ///< m/s²
  FluidVelocityField fluid_velocity;  ///< may be empty
  std::vector<PrescribedMotion> prescribed;

  int add_point(Vec2 position, double mass, PointKind kind = PointKind::Free, Vec2 velocity = {});
  int add_prescribed_point(PrescribedMotion motion);
  /// Adds a linear spring whose rest length is the current distance when rest_length < 0.
  void add_linear_spring(int i, int j, double stiffness, double rest_length = -1.0);
  /// Adds an angular spring whose rest angle is the current turning angle when rest_angle is NaN.
  void add_angular_spring(int i, int j, int k, double stiffness, double rest_angle);
  /// Adds a torsional beam through i, j (middle), k whose preferred cross product is the current
  /// one when curvature is NaN.
  void add_torsional_beam(int i, int j, int k, double stiffness, double curvature);
  /// Adds a non-invariant beam through i, j (middle), k whose preferred second difference is the
  /// current one when both components of curvature are NaN.
  void add_non_invariant_beam(int i, int j, int k, double stiffness, Vec2 curvature);
  /// Adds a power-law spring of degree α ∈ [1, 10] whose rest length is the current distance when
  /// rest_length < 0.
  void add_power_spring(int i, int j, double stiffness, double rest_length, double degree);
  /// Adds a dashpot of coefficient b ≥ 0 between two distinct points.
  void add_dashpot(int i, int j, double coefficient);
};

/// Energies of a body in a given state (for energy plots and tests).
struct Energy {
  double kinetic = 0.0;
  double elastic = 0.0;   ///< linear, angular and power springs, torsional and non-invariant beams
  double gravity = 0.0;   ///< -Σ m g·x over free points
  double total() const { return kinetic + elastic + gravity; }
};
Energy energy(const Body& body);

/// Sums all forces (springs and beams, dashpots, drag, gravity) on every point into `force` (resized to the point
/// count). Forces on pinned and prescribed points are computed too but are not used for motion.
void accumulate_forces(const Body& body, const std::vector<Vec2>& position, const std::vector<Vec2>& velocity,
                       double t, std::vector<Vec2>& force);

}  // namespace jellysim::elastic
