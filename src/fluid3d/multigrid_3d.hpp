#pragma once
// The multigrid pressure solver of the 3D fluid (pressure_3d.hpp, "multigrid"), private to the module.
#include <memory>

#include "jellysim/fluid3d/pressure_3d.hpp"

namespace jellysim::fluid3d {

std::unique_ptr<PressureSolver3d> make_multigrid_pressure_3d(const Grid3d& g, const Boundaries3d& b,
                                                             const PressureSettings3d& settings);

}  // namespace jellysim::fluid3d
