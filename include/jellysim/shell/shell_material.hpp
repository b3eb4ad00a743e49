#pragma once
// The shell's material in SI quantities (docs/three-d.md, "Part 3"): Young's modulus E, Poisson's
// ratio ν, thickness h and density ρ; the membrane, bending and mass per area follow from them:
//   membrane (plane stress):  2D Lamé constants μ h = E h / (2(1 + ν)), λ h = E h ν / (1 − ν²)
//   stretching stiffness      S = E h / (1 − ν²)
//   bending rigidity          D = E h³ / (12 (1 − ν²))
//   mass per area             ρ h
#include "jellysim/jellyfish/jellyfish.hpp"

namespace jellysim::shell {

struct ShellMaterial {
  double youngs_modulus_pa = 1.0e6;
  double poisson_ratio = 0.3;
  double thickness_m = 1.0e-3;
  double density_kg_per_m3 = 1000.0;

  /// S = E h / (1 − ν²) (N/m): the tension per unit strain of a strip held at zero strain across.
  double stretching_n_per_m() const { return youngs_modulus_pa * thickness_m / (1.0 - poisson_ratio * poisson_ratio); }
  /// D = E h³ / (12(1 − ν²)) (N·m): Kirchhoff's plate rigidity.
  double bending_n_m() const { return stretching_n_per_m() * thickness_m * thickness_m / 12.0; }
  /// μ h (N/m), the membrane's shear stiffness.
  double membrane_mu_n_per_m() const { return youngs_modulus_pa * thickness_m / (2.0 * (1.0 + poisson_ratio)); }
  /// λ h (N/m) of plane stress, E h ν / (1 − ν²).
  double membrane_lambda_n_per_m() const { return stretching_n_per_m() * poisson_ratio; }
  double mass_per_area_kg_per_m2() const { return density_kg_per_m3 * thickness_m; }
};

/// Throws std::invalid_argument naming the quantity unless E > 0, −1 < ν < ½ (ν = ½ allowed:
/// plane stress stays finite), h > 0, ρ > 0.
void validate(const ShellMaterial& m);

/// The slice's continuum material (per metre of slice depth, docs/jellyfish.md) as a shell: the
/// slice is a strip of the shell held at zero strain across (plane strain through the depth), whose
/// tension per unit strain is S = E h / (1 − ν²) and whose bending rigidity is B = E h³ / (12(1 − ν²)).
/// So h = √(12 B / S), E = S (1 − ν²) / h, ρ = (line density) / h: the shell's meridional strip is
/// the slice, whatever ν. The default bell: h = 13.4 mm, ρ h = 0.8166 kg/m².
ShellMaterial shell_material_from_continuum(const jellyfish::ContinuumMaterial& c, double poisson_ratio);

}  // namespace jellysim::shell
