#pragma once
// Flows shared by the tests of the fluid's outputs (pictures in tests/fluid, VTK in tests/io).
#include "jellysim/fluid/boundary.hpp"
#include "jellysim/fluid/grid.hpp"
#include "jellysim/fluid/reference_data.hpp"

namespace jellysim::testing {

/// A Taylor-Green vortex array on an n × n grid over a 2 m square, free-slip ghosts filled.
inline fluid::FlowState vortex_state(int n) {
  fluid::FlowState s(fluid::MacGrid(n, n, 2.0, 2.0));
  s.velocity = fluid::TaylorGreen{2.0, 1.0, 0.0}.sample(s.grid, 0.0);
  fluid::apply_velocity_boundaries(s.velocity, fluid::Boundaries::all(fluid::BoundaryType::free_slip));
  return s;
}

}  // namespace jellysim::testing
