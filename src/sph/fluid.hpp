#pragma once
// Smoothed particle hydrodynamics in 2D (thesis §5.1, after Müller et al. 2003): density by eq. 5.5,
// pressure by the equation of state p = κ_p (ρ − ρ0) and the symmetrised pressure force of eq. 5.6
// (with the minus sign the thesis drops), viscosity by eq. 5.8 with the velocity difference
// v_j − v_i. Walls mirror particles within h (§5.1.3). 2D densities are per unit area (kg/m²).
#include "math/vec2.hpp"
#include "sph/kernels.hpp"
#include "sph/neighbour_grid.hpp"
#include "sph/parallel.hpp"
#include "sph/walls.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace jellysim::sph {

struct SphParameters {
  double smoothing_radius_m = 0.05;  ///< h
  double rest_density = 2000.0;      ///< ρ0, kg/m²
  double gas_constant = 40.0;        ///< κ_p, m²/s² (p = κ_p (ρ − ρ0), pressure per unit length N/m)
  double viscosity = 8.9e-3;         ///< ν, m²/s; dynamic viscosity μ = ν ρ0
};

/// Throws std::invalid_argument naming the field and its range when a parameter is invalid.
void validate(const SphParameters& p);

/// Evaluates SPH densities and accelerations for a set of fluid particles. Holds all scratch memory,
/// so repeated evaluations do not allocate once sizes are stable.
class SphFluid {
 public:
  SphFluid(SphParameters parameters, std::vector<Wall> walls, int threads = 1);

  const SphParameters& parameters() const { return parameters_; }
  const Kernels& kernels() const { return kernels_; }
  const std::vector<Wall>& walls() const { return walls_; }

  /// Densities (eq. 5.5, including each particle's own contribution and its mirrored twins) of the
  /// particles x with masses m (kg); stored, see density().
  void compute_density(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m);
  /// Computes densities, then the SPH accelerations (m/s²) of every particle into `a` (resized):
  ///   a_i = −Σ_j m_j (p_i + p_j)/(2 ρ_i ρ_j) ∇W_spiky(x_i − x_j)          (eq. 5.6 / ρ_i)
  ///       + (μ/ρ_i) Σ_j (m_j/ρ_j) (v_j − v_i) ∇²W_visc(|x_i − x_j|)     (eq. 5.8, μ = ν ρ0)
  /// Each pair term times m_i is antisymmetric in i, j, so particle pairs conserve momentum.
  void compute_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m,
                             std::vector<Vec2>& a);

  /// Densities of the real particles from the last evaluation (kg/m²).
  const std::vector<double>& density() const { return density_; }
  /// Mirrored particles created in the last evaluation.
  std::size_t mirrored_count() const { return all_x_.size() - real_count_; }

 private:
  void build_mirrors(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m);
  void add_mirror(std::size_t source, Vec2 x, Vec2 v, double m);
  void density_range(std::size_t begin, std::size_t end, int part);
  void acceleration_range(std::size_t begin, std::size_t end, int part, std::vector<Vec2>& a) const;

  /// Neighbours (r < h, self excluded) found by the density pass, reused by the force pass. Each
  /// thread fills its own list for its own particle range.
  struct NeighbourList {
    std::vector<std::uint32_t> index;
    std::vector<double> distance;
  };

  SphParameters parameters_;
  Kernels kernels_;
  std::vector<Wall> walls_;
  std::unique_ptr<WorkerPool> pool_;
  NeighbourGrid grid_;
  std::size_t real_count_ = 0;
  // Real particles followed by mirrored ones (SoA).
  std::vector<Vec2> all_x_, all_v_;
  std::vector<double> all_m_, all_rho_, all_p_;
  std::vector<std::size_t> source_;  ///< for each mirror: its real particle
  std::vector<NeighbourList> lists_;  ///< one per thread
  std::vector<std::uint32_t> first_, count_;  ///< per real particle: its slice of its thread's list
  std::vector<double> density_;
};

}  // namespace jellysim::sph
