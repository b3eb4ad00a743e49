#include "jellysim/shell/shell_material.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace jellysim::shell {

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("shell material: " + what);
}
}  // namespace

void validate(const ShellMaterial& m) {
  require(m.youngs_modulus_pa > 0 && std::isfinite(m.youngs_modulus_pa), "Young's modulus must be in (0, inf) Pa");
  require(m.poisson_ratio > -1.0 && m.poisson_ratio <= 0.5, "Poisson's ratio must be in (-1, 0.5]");
  require(m.thickness_m > 0 && std::isfinite(m.thickness_m), "thickness must be in (0, inf) m");
  require(m.density_kg_per_m3 > 0 && std::isfinite(m.density_kg_per_m3), "density must be in (0, inf) kg/m³");
}

ShellMaterial shell_material_from_continuum(const jellyfish::ContinuumMaterial& c, double poisson_ratio) {
  require(c.stretching_n_per_m > 0 && c.bending_n_m > 0, "the continuum material needs S > 0 and B > 0");
  ShellMaterial m;
  m.poisson_ratio = poisson_ratio;
  m.thickness_m = std::sqrt(12.0 * c.bending_n_m / c.stretching_n_per_m);
  m.youngs_modulus_pa = c.stretching_n_per_m * (1.0 - poisson_ratio * poisson_ratio) / m.thickness_m;
  m.density_kg_per_m3 = c.line_density_kg_per_m2 / m.thickness_m;
  validate(m);
  return m;
}

}  // namespace jellysim::shell
