#pragma once
// The FFT pressure solver of the 3D fluid (pressure_3d.hpp, "fft"), private to the module.
#include <memory>

#include "jellysim/core/parallel.hpp"
#include "jellysim/fluid3d/pressure_3d.hpp"

namespace jellysim::fluid3d {

std::unique_ptr<PressureSolver3d> make_fft_pressure_3d(const Grid3d& g, const Boundaries3d& b, WorkerPool* pool);

}  // namespace jellysim::fluid3d
