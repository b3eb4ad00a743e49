#pragma once
// Shared by the fluid tests: every boundary-condition mix the solvers must handle, and random
// velocity fields.
#include <random>
#include <string>
#include <vector>

#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"

namespace jellysim::fluid::testing {

struct Mix {
  std::string name;
  Boundaries b;
};

inline BoundaryCondition bc(BoundaryType t, Vec2 v = {}) { return {t, v}; }

inline std::vector<Mix> boundary_mixes() {
  using T = BoundaryType;
  return {
      {"all-no-slip", Boundaries::all(T::no_slip)},
      {"all-free-slip", Boundaries::all(T::free_slip)},
      {"lid-driven-cavity", Boundaries::lid_driven_cavity(1.0)},
      {"periodic-x-walls-y", {bc(T::periodic), bc(T::periodic), bc(T::no_slip), bc(T::free_slip)}},
      {"periodic-both", Boundaries::all(T::periodic)},
      {"inflow-outflow-channel", {bc(T::inflow, {1.0, 0.0}), bc(T::outflow), bc(T::no_slip), bc(T::no_slip)}},
      {"all-outflow", Boundaries::all(T::outflow)},
      {"mixed", {bc(T::inflow, {0.5, 0.2}), bc(T::outflow), bc(T::free_slip), bc(T::no_slip, {0.3, 0.0})}},
      {"periodic-y-inflow-outflow", {bc(T::inflow, {1.0, 0.0}), bc(T::outflow), bc(T::periodic), bc(T::periodic)}},
  };
}

inline void randomise(Velocity& vel, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (double& x : vel.u.raw()) x = d(rng);
  for (double& x : vel.v.raw()) x = d(rng);
}

}  // namespace jellysim::fluid::testing
