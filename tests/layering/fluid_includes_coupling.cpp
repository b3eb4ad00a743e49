// Must not compile: the fluid module does not depend on the coupling module, so its include tree
// has no jellysim/coupling (tests/layering/CMakeLists.txt builds this and expects failure).
#include "jellysim/coupling/transfer_kernels.hpp"
#include "jellysim/fluid/grid.hpp"

int layering_probe() { return 0; }
