#include "jellysim/fluid3d/grid_3d.hpp"

#include <stdexcept>
#include <string>

namespace jellysim::fluid3d {

Grid3d::Grid3d(Index3 cells, Vec3 size_m, Vec3 origin_m) : cells_(cells), size_(size_m), origin_(origin_m) {
  for (std::size_t d = 0; d < 3; ++d) {
    if (cells_[d] < 2 || !(size_[d] > 0.0))
      throw std::invalid_argument("Grid3d: axis " + std::to_string(d) + " needs at least 2 cells and a positive size");
    spacing_[d] = size_[d] / cells_[d];
    padded_[d] = static_cast<std::size_t>(cells_[d] + 1 + 2 * ghosts);
  }
  stride_ = {1, padded_[0], padded_[0] * padded_[1]};
}

std::size_t Grid3d::cell_count() const {
  return static_cast<std::size_t>(cells_[0]) * static_cast<std::size_t>(cells_[1]) * static_cast<std::size_t>(cells_[2]);
}

Vec3 Grid3d::position(int c, int i, int j, int k) const {
  const Index3 idx{i, j, k};
  Vec3 x{};
  for (std::size_t d = 0; d < 3; ++d) {
    const double offset = static_cast<int>(d) == c ? 0.0 : 0.5;  // faces of c sit on whole indices along c
    x[d] = origin_[d] + (idx[d] + offset) * spacing_[d];
  }
  return x;
}

}  // namespace jellysim::fluid3d
