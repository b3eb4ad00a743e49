#pragma once
// The jellyfish swimming in 3D water (issue 40 part 4, docs/three-d.md "Part 4"): the elastic shell
// bell (shell::ShellBell) as the markers of the 3D immersed boundary (ib3d, semi-implicit by
// default) in a tank of free-slip walls, stepped on a frame clock, with the swimming figures of a
// 3D body — where its surface's centroid goes, and where its axis points.
//
// Frame of the tank: x across, y up, z in depth; the tank spans x ∈ [−W/2, W/2], y ∈ [0, H],
// z ∈ [−D/2, D/2], the bell's axis on the vertical line x = z = 0 with its aperture centre at
// height `aperture_height_m`. The water is solved on
//  * the quarter tank x ≥ 0, z ≥ 0 (mirror planes x = 0 and z = 0) when the stroke is symmetric;
//  * the half tank z ≥ 0 (mirror plane z = 0, the plane of the pacemaker's azimuth 0 or π) when a
//    pacemaker fires one side first: the bell then turns in the x–y plane;
//  * the whole tank otherwise (symmetry = none).
// The markers are always the whole bell; the mirror planes fold what lands beyond them (ib3d).
//
// Figures per frame: the centroid of the bell's surface vertices and their mean velocity, the
// cavity's volume, and the bell's axis a = (apex − the margin ring's centroid)/|…| with
//   heading = atan2(−a_x, a_y)  (deg, the swimming direction in the x–y plane from +y,
//             counter-clockwise: the slice's tilt_deg convention, the pacemaker's turn),
//   tilt    = acos(a_y)        (deg, the axis's angle from the vertical, whichever way).
// Per cycle (cycles start at t = k / f): the centroid's displacement along the starting axis and the
// heading's change; the distance per cycle is the mean over the cycles after the first (the 2D
// convergence study's definition, docs/convergence.md).
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "jellysim/fluid3d/fluid_solver_3d.hpp"
#include "jellysim/ib3d/immersed_boundary_3d.hpp"
#include "jellysim/shell/shell_bell.hpp"
#include "jellysim/swim3d/shell_forces_3d.hpp"

namespace jellysim::swim3d {

using ib3d::Vec3;

enum class TankSymmetry3d {
  automatic,  ///< quarter without a pacemaker; half with one at azimuth 0 or π; none otherwise
  none,
  half,     ///< mirror plane z = 0
  quarter,  ///< mirror planes x = 0 and z = 0
};
std::string_view to_string(TankSymmetry3d s);

struct Swim3dSpec {
  shell::ShellBellSpec bell{};
  Vec3 tank_size_m{0.16, 0.20, 0.16};  ///< W (x), H (y), D (z) of the whole tank
  fluid3d::Index3 cells{64, 80, 64};   ///< cells of the whole tank; even across a mirror plane
  double aperture_height_m = 0.05;     ///< the aperture centre's height above the floor
  TankSymmetry3d symmetry = TankSymmetry3d::automatic;
  double density_kg_per_m3 = 1000.0;
  double viscosity_m2_per_s = 1.304e-5;  ///< the built-in scene's ν (docs/jellyfish.md)
  fluid3d::FluidMethod3d method = fluid3d::FluidMethod3d::eulerian;
  fluid::ConvectionScheme convection = fluid::ConvectionScheme::koren;
  double max_time_step_s = 0.005;  ///< the coupled step's largest Δt; the fluid's limit may cut it
  int frames_per_cycle = 24;       ///< frames recorded per contraction cycle (and one at t = 0)
  ib3d::CouplingSettings3d coupling{};
  int threads = 1;  ///< the fluid's and the transfer's pools (0: all cores); the bits do not depend on it
};

/// Throws std::invalid_argument naming the field and its range.
void validate(const Swim3dSpec& spec);
/// The mirror planes the spec's symmetry (resolved) puts in the tank.
TankSymmetry3d resolved_symmetry(const Swim3dSpec& spec);
/// The grid the water is solved on: the whole tank, its half or its quarter.
fluid3d::Grid3d solved_grid(const Swim3dSpec& spec);
/// The fluid settings of that grid: free-slip walls (mirror planes) on every side.
fluid3d::FluidSettings3d fluid_settings(const Swim3dSpec& spec);

/// What one frame records.
struct Frame3d {
  double time_s = 0.0;
  std::vector<Vec3> points;  ///< every shell point (the surface's vertices, then the tentacles' nodes), m
  Vec3 centroid{};           ///< of the surface's vertices (m)
  Vec3 velocity{};           ///< their mean velocity (m/s)
  Vec3 axis{};               ///< unit: from the margin's centroid to the apex
  double heading_deg = 0.0;
  double tilt_deg = 0.0;
  double cavity_volume_m3 = 0.0;
  int steps = 0;             ///< coupled steps taken so far
  int krylov_iterations = 0; ///< GMRES applications in the steps since the last frame
};

/// The axis, heading and tilt of a bell at positions x (every shell point).
struct BellPose {
  Vec3 centroid{}, axis{};
  double heading_deg = 0.0, tilt_deg = 0.0;
};
BellPose bell_pose(const shell::ShellBell& bell, std::span<const Vec3> x);

/// Wall-clock seconds spent so far, by part (measurements, never results).
struct Swim3dTimings {
  double transfer_s = 0.0, fluid_s = 0.0, krylov_s = 0.0, total_s = 0.0;
  int steps = 0, krylov_iterations = 0;
};

class Swimmer3d {
 public:
  /// Builds the bell, the water and the coupling; throws std::invalid_argument for a bad spec and
  /// InputError when the fluid's memory estimate exceeds the budget.
  explicit Swimmer3d(const Swim3dSpec& spec);
  ~Swimmer3d();
  Swimmer3d(const Swimmer3d&) = delete;
  Swimmer3d& operator=(const Swimmer3d&) = delete;

  const Swim3dSpec& spec() const { return spec_; }
  const shell::ShellBell& bell() const { return *bell_; }
  const fluid3d::FluidSolver3d& fluid() const { return *fluid_; }
  const ib3d::Markers3d& markers() const { return markers_; }
  double time_s() const { return coupling_->time_s(); }
  double frame_interval_s() const;
  /// The frame at the present time (no step taken).
  Frame3d frame() const;
  /// Steps to the next frame's time (equal coupled steps within max_time_step_s and the fluid's
  /// limit) and records it. Throws std::runtime_error when the flow stops being finite or GMRES
  /// does not converge.
  Frame3d advance_frame();
  /// One coupled step of those advance_frame takes (the same steps, one at a time, for a viewer
  /// that draws between them); true when it reached the next frame's time, whose figures frame()
  /// then gives. Throws as advance_frame does.
  bool step_toward_frame();
  const Swim3dTimings& timings() const { return timings_; }
  /// Saves or restores the run's state for a checkpoint (issue 23): the water, the coupling and
  /// its markers, the frame clock, the step statistics. The bell's muscles follow the clock alone.
  void archive(core::StateArchive& a);

 private:
  Swim3dSpec spec_;
  std::unique_ptr<shell::ShellBell> bell_;
  std::unique_ptr<ShellForces3d> forces_;
  std::unique_ptr<fluid3d::FluidSolver3d> fluid_;
  ib3d::Markers3d markers_;
  std::unique_ptr<ib3d::ImmersedBoundary3d> coupling_;
  std::int64_t frame_index_ = 0;   ///< the last frame reached
  int krylov_since_frame_ = 0;
  bool frame_reached_ = true;      ///< the next step starts a new frame
  Swim3dTimings timings_;
};

/// The swimming figures of recorded frames (frames_per_cycle apart, the first at t = 0).
struct SwimSummary3d {
  std::vector<double> cycle_distance_m;     ///< the centroid's displacement along the first axis, per cycle
  std::vector<double> cycle_heading_deg;    ///< the heading's change over each cycle
  double first_cycle_m = 0.0;
  double distance_per_cycle_m = 0.0;        ///< mean over the cycles after the first (NaN with one cycle)
  double heading_change_deg_per_cycle = 0.0;///< mean over the cycles after the first (the first's with one)
  double final_heading_deg = 0.0, final_tilt_deg = 0.0;
  double sideways_m = 0.0;                  ///< the centroid's last distance from the starting axis
};
SwimSummary3d summarize(const std::vector<Frame3d>& frames, int frames_per_cycle);

}  // namespace jellysim::swim3d
