#pragma once
// The fluid-free jellyfish of thesis §8.2.3: the slice's spring-mass body integrated on its own,
// with drag against still water (eq. 2.17) standing in for the fluid's resistance and a cavity
// pressure proportional to the rate of change of the bell's volume (eq. 8.1) pushing the umbrella
// outward while it contracts. In the slice the volume is the cavity's area per metre of depth:
// p = −α dA/dt (Pa), acting on every umbrella segment along its outward normal.
#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/ode/ode_system.hpp"

#include <Eigen/Sparse>

namespace jellysim::jellyfish {

struct FluidlessSettings {
  double drag_kg_per_s = 0.05;        ///< κ_d of eq. 2.17 on every marker (the thesis model; per metre of depth)
  /// The continuum model's drag per metre of bell or tentacle: a point standing for an arc s gets
  /// κ_d = this · s (40.8 is 0.05 kg/s per marker at the built-in spacing).
  double drag_kg_per_s_m2 = 40.8;
  double pressure_factor = 200.0;     ///< α of eq. 8.1, Pa·s/m²
};

class FluidlessSystem final : public ode::OdeSystem {
 public:
  /// The jellyfish is referenced: its muscles are actuated at each evaluation time.
  FluidlessSystem(Jellyfish& jellyfish, const FluidlessSettings& settings);
  Eigen::Index dimension() const override;
  Eigen::Index position_size() const override;
  bool has_jacobian() const override { return true; }
  ode::Vector pack_state() const;
  /// Writes positions and velocities of y into the jellyfish's body.
  void unpack_state(const ode::Vector& y) const;

 protected:
  void compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const override;
  /// The springs' and the drag's part of df/dy (for implicit integrators such as backward Euler).
  /// The cavity pressure's dependence on the velocities is left out: Newton's iteration then
  /// converges on it at a linear rate, its share of the force being small.
  void compute_jacobian(double t, const ode::Vector& y, ode::SparseMatrix& jac) const override;

 private:
  Jellyfish& jellyfish_;
  FluidlessSettings settings_;
  std::vector<double> point_drag_;  ///< continuum model: κ_d of each point (empty: the body's one κ_d)
  mutable std::vector<Vec2> x_, v_, f_;
};

/// Signed area of the cavity closed by the aperture chord and its rate for the given velocities:
/// A = ½ Σ x_k × x_{k+1}, dA/dt = ½ Σ (v_k × x_{k+1} + x_k × v_{k+1}).
std::pair<double, double> cavity_area_and_rate(const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                                               const std::vector<int>& ring);

}  // namespace jellysim::jellyfish
