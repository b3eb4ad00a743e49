// The control for fluid_includes_coupling.cpp: the same include compiles in a module that depends
// on coupling, so the other probe fails for the layering and not for a missing header.
#include "jellysim/coupling/transfer_kernels.hpp"
#include "jellysim/fluid/grid.hpp"

int layering_probe() { return jellysim::coupling::kernel_radius(jellysim::coupling::Kernel::bilinear); }
