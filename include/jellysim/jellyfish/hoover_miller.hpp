#pragma once
#include <vector>
// The Hoover–Miller jellyfish bell as IB2d ships it (IB2d's Make_Jelly_Geometry.m, "courtesy of
// Alexander P. Hoover", converted from IBAMR; Hoover & Miller 2015; the convergence study of
// Battista & Mizuhara 2019): generated here from its description, not copied. An elliptical bell
// (semi-axes 0.5 m across, 0.75 m up) cut at 0.25 m below its centre, markers half a cell apart,
// a chain of stiff springs and non-invariant beams along it, separate muscle markers on the lower
// part of each side joined across the bell by muscle springs, and a row of target points near the
// top of the periodic domain (IB2d's "flow blocker"). Knows nothing of files.
#include "jellysim/elastic/ib2d_structure.hpp"

namespace jellysim::jellyfish {

/// IB2d's parameters of the bell. `resolution` is IB2d's N: the mesh width is 8/N m (its
/// "virtual" height of 8 m over N cells) on a 3 × 10 m domain of 0.375 N × 1.25 N cells.
struct HooverMillerSpec {
  int resolution = 256;
  double semi_axis_across_m = 0.5;
  double semi_axis_up_m = 0.75;
  double cut_m = -0.25;                 ///< the bell ends where y − centre = cut
  Vec2 centre_m{1.5, 2.0};              ///< the ellipse's centre in the domain
  double domain_width_m = 3.0, domain_height_m = 10.0;
  double spring_stiffness = 1e7;        ///< κ_s: bell springs get κ_s/ds (IB2d units)
  double beam_stiffness = 2.5e5;        ///< κ_b: non-invariant beams get κ_b/ds³
  double muscle_stiffness = 1e5;        ///< muscle springs (IB2d: not scaled by ds)
  /// The consistent variant ("hoover-miller-consistent", docs/ib2d.md): each muscle spring stands for
  /// ds of bell, so its stiffness is muscle_stiffness · ds / ds₂₅₆ (IB2d's value at N = 256) and the
  /// muscles' total pull no longer grows with the resolution. IB2d's own files keep it fixed.
  bool muscles_per_length = false;
  double target_stiffness = 2.5e6;      ///< flow-blocker targets (not scaled by ds)

  double mesh_width_m() const { return 8.0 / resolution; }
  double marker_spacing_m() const { return 0.5 * mesh_width_m(); }  ///< ds
  /// The stiffness each muscle spring gets (see muscles_per_length).
  double muscle_spring_stiffness() const { return muscles_per_length ? muscle_stiffness * 256.0 / resolution : muscle_stiffness; }
  int cells_x() const;  ///< 0.375 N
  int cells_y() const;  ///< 1.25 N
};

/// The generated structure and where its parts are.
struct HooverMillerBell {
  elastic::Ib2dStructure structure;
  int bell_points = 0;     ///< points 0 … bell_points − 1: the bell, apex first, then the west side, then the east
  int muscle_points = 0;   ///< the next 2·muscle_points: the west muscle markers, then the east ones
  int first_muscle_spring = 0;  ///< springs first_muscle_spring … end are the muscles (rest length scheduled)
  int target_points = 0;   ///< the last points: the flow blocker
};

/// Throws std::invalid_argument for a resolution outside [16, 4096] or one not divisible by 8.
HooverMillerBell hoover_miller_bell(const HooverMillerSpec& spec = {});

/// The bell's swim per cycle (1 s at IB2d's 1 Hz): the centroid's displacement y(k) − y(k − 1) over
/// each full cycle k = 1 … cycles, from frames (t_s, y_m) within tolerance_s of the whole seconds; a
/// cycle without both frames is left out.
std::vector<double> cycle_displacements(const std::vector<double>& t_s, const std::vector<double>& y_m, int cycles,
                                        double tolerance_s);

/// The mean displacement of cycles 2 and 3 (the first starts from rest); 0 without them.
double later_cycle_displacement(const std::vector<double>& per_cycle);

}  // namespace jellysim::jellyfish
