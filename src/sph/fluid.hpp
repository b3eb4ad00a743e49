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
#include <functional>
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

/// Optional work run inside a parallel evaluation (see SphFluid::compute_accelerations). Each
/// callback must not throw and may touch only its own range of particles (or, for `side`, data no
/// other callback touches).
struct EvaluationHooks {
  /// Fills x, v, m on [begin, end) before they are read (called by the thread owning the range).
  std::function<void(std::size_t begin, std::size_t end)> load;
  /// Called once the accelerations on [begin, end) are final.
  std::function<void(std::size_t begin, std::size_t end)> store;
  /// Independent work (e.g. the body's spring forces), run once by the last thread while the first
  /// one builds the neighbour grid.
  std::function<void()> side;
};

/// Evaluates SPH densities and accelerations for a set of fluid particles. Holds all scratch memory,
/// so repeated evaluations do not allocate once sizes are stable. With several threads, one
/// evaluation is one parallel region of five phases (load + mirrors, grid count, grid placement,
/// density, forces); results are bit-identical for every thread count.
class SphFluid {
 public:
  /// threads in [1, 64].
  SphFluid(SphParameters parameters, std::vector<Wall> walls, int threads = 1);

  const SphParameters& parameters() const { return parameters_; }
  const Kernels& kernels() const { return kernels_; }
  const std::vector<Wall>& walls() const { return walls_; }
  int threads() const { return pool_->threads(); }

  /// Densities (eq. 5.5, including each particle's own contribution and its mirrored twins) of the
  /// particles x with masses m (kg); stored, see density().
  void compute_density(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m);
  /// Computes densities, then the SPH accelerations (m/s²) of every particle into `a` (resized):
  ///   a_i = −Σ_j m_j (p_i + p_j)/(2 ρ_i ρ_j) ∇W_spiky(x_i − x_j)          (eq. 5.6 / ρ_i)
  ///       + (μ/ρ_i) Σ_j (m_j/ρ_j) (v_j − v_i) ∇²W_visc(|x_i − x_j|)     (eq. 5.8, μ = ν ρ0)
  /// Each pair term times m_i is antisymmetric in i, j, so particle pairs conserve momentum.
  /// With hooks.load, x, v and m must already have their final size and are filled range by range
  /// inside the parallel region.
  void compute_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m,
                             std::vector<Vec2>& a, const EvaluationHooks& hooks = {});

  /// Densities of the real particles from the last evaluation (kg/m²).
  const std::vector<double>& density() const { return rho_; }
  /// Evaluations so far, and how many of them ran on all threads (see PathChooser; with one
  /// thread, or fewer than 64 particles, none do).
  std::int64_t evaluations() const { return evaluations_; }
  std::int64_t parallel_evaluations() const { return parallel_evaluations_; }
  /// Mirrored particles created in the last evaluation.
  std::size_t mirrored_count() const { return total_ - real_count_; }

 private:
  /// Neighbours (r < h, self excluded) found by the density pass, reused by the force pass.
  struct NeighbourList {
    std::vector<std::uint32_t> index;
    std::vector<double> distance;
  };
  /// What one thread owns: its mirrors before they are gathered, its bounds, its neighbour list.
  struct alignas(64) Part {
    std::vector<Vec2> mirror_x, mirror_v;
    std::vector<double> mirror_m;
    std::vector<std::uint32_t> mirror_source;
    Bounds bounds;
    GridLayout layout;
    std::size_t mirror_offset = 0;  ///< index of its first mirror in all_x_
    NeighbourList list;
  };
  struct Inputs {
    const std::vector<Vec2>* x;
    const std::vector<Vec2>* v;
    const std::vector<double>* m;
    std::vector<Vec2>* a;
    const EvaluationHooks* hooks;
  };

  void evaluate(const Inputs& in, bool accelerations);
  void prepare(std::size_t n);
  // The phases, each for part `part` (see evaluate()).
  void load_and_mirror(const Inputs& in, int part);
  void gather_and_count(int part);
  void place_and_side(const Inputs& in, int part);
  void density_range(int part);
  void acceleration_range(const Inputs& in, int part);

  void add_mirrors(Part& part, std::size_t i, Vec2 x, Vec2 v, double m) const;
  std::pair<std::size_t, std::size_t> real_range(int part) const { return pool_->range(real_count_, part); }

  SphParameters parameters_;
  Kernels kernels_;
  std::vector<Wall> walls_;
  std::vector<const Wall*> mirror_walls_;  ///< the walls with mirror = true
  std::size_t max_mirrors_per_particle_ = 0;
  std::unique_ptr<WorkerPool> pool_;
  PathChooser chooser_;
  std::int64_t evaluations_ = 0, parallel_evaluations_ = 0;
  NeighbourGrid grid_;
  std::size_t real_count_ = 0, total_ = 0;
  // Real particles followed by mirrored ones (SoA); sized for the most mirrors possible.
  std::vector<Vec2> all_x_, all_v_;
  std::vector<double> all_m_;
  std::vector<std::uint32_t> origin_;  ///< the real particle each entry is (or mirrors)
  std::vector<double> rho_, p_;        ///< per real particle
  std::vector<Part> parts_;            ///< one per thread
  std::vector<NeighbourGrid::Slot> slots_;  ///< every part's real and mirror slot, for the placement
  std::vector<std::uint32_t> first_, count_;  ///< per real particle: its slice of its part's list
};

}  // namespace jellysim::sph
