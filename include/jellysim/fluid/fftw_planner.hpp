#pragma once
// FFTW's planner (and its allocator, to be safe) is not thread-safe; execution of distinct plans
// is. Every FFTW plan or buffer of the project (the 2D FFT pressure solver and the 3D one, fluid3d)
// is made and destroyed under this one mutex. Recursive: a plan or buffer released while planning
// (an exception) takes it again.
#include <mutex>

namespace jellysim::fluid {

std::recursive_mutex& fftw_planner_mutex();

}  // namespace jellysim::fluid
