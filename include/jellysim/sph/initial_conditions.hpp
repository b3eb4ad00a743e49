#pragma once
// Initial conditions of an SPH fluid (thesis §5.1.2): triangular packing, crystalline (at rest) or
// thermalised (position noise ε_p and small opposite velocities) states, and the particle mass
// found by bisection so that the smoothed density matches the rest density ρ0.
#include "jellysim/math/vec2.hpp"
#include "jellysim/sph/fluid.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace jellysim::sph {

/// Rows of particles `spacing_m` apart, rows (√3/2) spacing apart, alternate rows shifted by half a
/// spacing (Figure 5.3, right), inside the box [lo, hi], each at least half a spacing from its
/// sides (a wall particle's mirror is then one spacing away). Order: row by row from the bottom,
/// left to right.
std::vector<Vec2> triangular_lattice(Vec2 lo, Vec2 hi, double spacing_m);

/// The first `count` points of the finest triangular lattice in [lo, hi] whose points outside the
/// excluded region (`excluded(x)` true) number at least `count`; the spacing is found by bisection.
/// Throws std::invalid_argument when count < 1 or no lattice fits.
std::vector<Vec2> triangular_lattice_with_count(Vec2 lo, Vec2 hi, std::size_t count,
                                                const std::function<bool(Vec2)>& excluded);

/// Thermalised state: adds ε_p, uniform in a disc of radius `noise_m`, to every position, and sets
/// each velocity to −ε_p × `velocity_per_noise` (1/s), opposite to the displacement (§5.1.2; the
/// thesis takes velocities about two orders of magnitude below ε_p). Deterministic for a seed.
void thermalise(std::vector<Vec2>& x, std::vector<Vec2>& v, double noise_m, double velocity_per_noise,
                std::uint64_t seed);

/// Crystalline relaxation (§5.1.2 suggests an optimal packing, e.g. by Lloyd's algorithm): moves
/// the particles (masses m) down the SPH pressure force, x += ½ τ² a with τ = 0.2 h / √κ_p, for
/// `iterations` sweeps, keeping them inside the walls. Returns the largest remaining acceleration
/// magnitude (m/s²).
double relax(std::vector<Vec2>& x, const std::vector<double>& m, const SphParameters& parameters,
             const std::vector<Wall>& walls, int iterations);

struct MassSearch {
  double mass_kg = 0.0;          ///< the mass of every particle
  double mean_density = 0.0;     ///< mean smoothed density reached (kg/m²)
  double initial_guess_kg = 0.0; ///< eq. 5.21: ρ0 V / n_p
  int iterations = 0;
};

/// Bisection on the common particle mass, starting from the guess of eq. 5.21 (`area_m2` = V), until
/// the mean smoothed density (eq. 5.5, walls mirrored as in the simulation) is within
/// `relative_tolerance` × ρ0 of ρ0. Throws std::invalid_argument for ρ0 <= 0 or empty input.
MassSearch find_particle_mass(const std::vector<Vec2>& x, double area_m2, const SphParameters& parameters,
                              const std::vector<Wall>& walls, double relative_tolerance);

}  // namespace jellysim::sph
