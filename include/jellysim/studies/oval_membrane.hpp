#pragma once
// The oval membrane test of Stockie & Wetton (thesis §8.1.3, Figures 8.8/8.9): a closed elastic
// membrane of stretched springs in a fluid box pulls itself toward a circle; the enclosed area
// should stay constant, so its change measures how much fluid leaks through the boundary.
#include <functional>
#include <string>
#include <vector>

#include "jellysim/coupling/immersed_boundary.hpp"

namespace jellysim::studies {

struct OvalMembraneSettings {
  std::string solver = "eulerian";  ///< fluid solver
  int cells = 30;                   ///< cells per side of the unit box
  double box_m = 1.0;
  double viscosity_m2_per_s = 0.0;
  double density_kg_per_m3 = 1.0;
  double stiffness = 10.0;          ///< κ_l of every spring (rest length 0: pure tension)
  double semi_axis_x_m = 0.35;
  double semi_axis_y_m = 0.25;
  double spacing_fraction = 0.5;    ///< marker spacing as a fraction of Δx (Peskin: ≤ 0.5)
  double dt_s = 0.002;
  double duration_s = 2.0;
  double frame_interval_s = 0.05;
  coupling::CouplingSettings coupling{};      ///< its max_time_step_s is ignored: dt_s is used
  std::string pressure_solver = "multigrid";
};

struct MembraneFrame {
  double t = 0.0;
  double area = 0.0;          ///< enclosed area (m²), shoelace formula
  double aspect_ratio = 0.0;  ///< largest / smallest distance of a marker from the centroid
  std::vector<Vec2> points;
};

struct MembraneRun {
  std::vector<MembraneFrame> frames;
  std::string failure;  ///< non-empty when the run became unstable
  long steps = 0;
  double wall_seconds = 0.0;
};

/// The membrane body: markers around the ellipse centred in the box, joined in a ring.
elastic::Body make_oval_membrane(const OvalMembraneSettings& s);
/// Signed polygon area (positive counter-clockwise).
double polygon_area(const std::vector<Vec2>& ring);
double ring_aspect_ratio(const std::vector<Vec2>& ring);

/// Runs the test, calling on_frame (may be empty) for every recorded frame.
MembraneRun run_oval_membrane(const OvalMembraneSettings& s,
                              const std::function<void(const MembraneFrame&)>& on_frame = {});

}  // namespace jellysim::studies
