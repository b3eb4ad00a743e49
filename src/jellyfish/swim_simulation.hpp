#pragma once
// A jellyfish slice swimming in a grid fluid through the immersed boundary method (thesis §7.1,
// §8.1.4–8.2.1): the tank (fluid grid, boundaries, tracers), the jellyfish, the coupling and the
// stability checks, stepped to each output frame. Knows nothing of files.
#include <functional>
#include <memory>
#include <string>

#include "coupling/immersed_boundary.hpp"
#include "fluid/tracers.hpp"
#include "jellyfish/jellyfish.hpp"
#include "sim/time_stepping.hpp"

namespace jellysim::jellyfish {

struct TankSpec {
  double width_m = 0.8;
  double height_m = 0.8;
  int cells_x = 60;
  int cells_y = 60;
  std::string solver = "semi-lagrangian";
  std::string pressure_solver = "multigrid";
  double pressure_tolerance = 1e-8;  ///< relative max-norm residual of every pressure solve
  double viscosity_m2_per_s = 1.304e-5;
  double density_kg_per_m3 = 1000.0;
  fluid::Boundaries boundaries = fluid::Boundaries::all(fluid::BoundaryType::free_slip);
  int tracers_per_side = 0;  ///< marker particles on a lattice over the whole tank (Figs 8.11/8.12)
};

struct SwimSettings {
  TankSpec tank;
  JellyfishSpec jellyfish;
  coupling::CouplingSettings coupling;
  coupling::StabilityLimits limits;
  double duration_s = 10.0;
  double frame_interval_s = 1.0 / 30.0;
};

struct SwimRunStats {
  long steps = 0;
  double simulated_seconds = 0.0;
  double wall_seconds = 0.0;
  double smallest_step_s = 0.0;
  double largest_step_s = 0.0;
  long krylov_iterations = 0;
  std::string failure;  ///< "numerical instability: …" or "structural instability: …" with when/where
};

class SwimSimulation {
 public:
  explicit SwimSimulation(const SwimSettings& settings);

  /// Called at t = 0 and at every frame time; a non-empty return stops the run with that failure.
  using FrameCallback = std::function<std::string(const SwimSimulation&)>;
  SwimRunStats run(const FrameCallback& on_frame, const sim::ProgressCallback& progress = {});

  double time_s() const { return coupling_->time_s(); }
  const SwimSettings& settings() const { return settings_; }
  const Jellyfish& jellyfish() const { return *jellyfish_; }
  const fluid::FlowState& flow() const { return fluid_->state(); }
  const fluid::Tracers& tracers() const { return tracers_; }
  /// The problem that should stop the run now, or "".
  std::string check() const;

 private:
  SwimSettings settings_;
  std::unique_ptr<fluid::FluidSolver> fluid_;
  std::unique_ptr<Jellyfish> jellyfish_;
  std::unique_ptr<coupling::ImmersedBoundary> coupling_;
  fluid::Tracers tracers_;
  std::vector<double> strain_reference_;  ///< rest lengths at build time (muscles uncontracted)
};

/// The largest marker spacing Peskin's rule allows on a tank: half the smaller cell size.
double peskin_spacing(const TankSpec& tank);

}  // namespace jellysim::jellyfish
