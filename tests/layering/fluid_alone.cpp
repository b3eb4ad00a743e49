// The control for fluid_includes_coupling.cpp: the fluid module's own headers compile with its
// include tree alone.
#include "jellysim/fluid/grid.hpp"

int layering_probe() { return static_cast<int>(jellysim::fluid::MacGrid(4, 4, 1.0, 1.0).dx()); }
