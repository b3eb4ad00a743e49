#pragma once
// Smoothed particle hydrodynamics in 2D (thesis §5.1, after Müller et al. 2003): density by eq. 5.5,
// pressure by the equation of state p = κ_p (ρ − ρ0) and the symmetrised pressure force of eq. 5.6
// (with the minus sign the thesis drops), viscosity by eq. 5.8 with the velocity difference
// v_j − v_i. Walls mirror particles within h (§5.1.3). 2D densities are per unit area (kg/m²).
#include "jellysim/math/vec2.hpp"
#include "jellysim/sph/smoothing_kernels.hpp"
#include "jellysim/sph/neighbour_grid.hpp"
#include "jellysim/core/parallel.hpp"
#include "jellysim/sph/walls.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace jellysim::sph {

/// Makes `v` hold at least n entries (growing geometrically: used as a buffer whose first entries
/// count, so that loops write without push_back's capacity test).
template <class T>
void grow_to(std::vector<T>& v, std::size_t n) {
  if (v.size() < n) v.resize(std::max(n, 2 * v.size()));
}

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
  /// Writes the positions (m) and velocities (m/s) of particles [begin, end) into x[i] and v[i]
  /// (arrays indexed by particle, owned by the fluid) before they are read; called by the thread
  /// owning the range. Writing straight into the fluid's arrays spares a copy through caller-side
  /// vectors (and the cache lines that copy would share between cores).
  std::function<void(std::size_t begin, std::size_t end, Vec2* x, Vec2* v)> load;
  /// Called once the accelerations on [begin, end) are final.
  std::function<void(std::size_t begin, std::size_t end)> store;
  /// Independent work (e.g. the body's spring forces), run once per evaluation by the first thread,
  /// in the load phase after its own range.
  std::function<void()> side;
};

/// Evaluates SPH densities and accelerations for a set of fluid particles. Holds all scratch memory,
/// so repeated evaluations do not allocate once sizes are stable.
///
/// Neighbours come from Verlet lists: every particle keeps the points within h + skin found by the
/// cell grid at the last rebuild, and later evaluations test only those. The lists stay complete
/// while no particle has moved skin/2 or more since the rebuild (a pair within h now was within
/// h + skin then); the first evaluation that finds such a particle (or a new particle count, or a
/// changed set of points) rebuilds them. Mirrored twins (§5.1.3) are kept the same way: built for
/// particles within h + skin/2 of a mirroring wall, moved with their sources every evaluation, and
/// counted only while the source is within h (exactly the twins of a fresh search).
///
/// With several threads, one evaluation is one parallel region: load (+ twins and the displacement
/// test), then, only when rebuilding, twin tables, grid count and grid placement, then densities and
/// accelerations. Every particle's sums run over its list in the list's (grid) order on one thread,
/// so results are bit-identical for every thread count.
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
  /// hooks.load must be empty here (see the overload below); hooks.store and hooks.side may be set.
  void compute_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m,
                             std::vector<Vec2>& a, const EvaluationHooks& hooks = {});
  /// The same for m.size() particles whose positions and velocities hooks.load (required) writes
  /// inside the parallel region, each thread for its own range.
  void compute_accelerations(std::span<const double> m, std::vector<Vec2>& a, const EvaluationHooks& hooks);

  /// Densities of the real particles from the last evaluation (kg/m²).
  const std::vector<double>& density() const { return rho_; }
  /// Evaluations so far, and how many of them ran on all threads (see PathChooser; with one
  /// thread, or fewer than 64 particles, none do).
  std::int64_t evaluations() const { return evaluations_; }
  std::int64_t parallel_evaluations() const { return parallel_evaluations_; }
  /// Mirrored twins in the last evaluation (sources within h of a mirroring wall).
  std::size_t mirrored_count() const;
  /// How many evaluations rebuilt the neighbour lists (grid search) so far.
  std::int64_t list_rebuilds() const { return list_rebuilds_; }
  /// The lists' skin as a fraction of h: they hold every point within (1 + kListSkin) h.
  static constexpr double kListSkin = 0.25;

 private:
  /// Neighbours (r < h, self excluded) found by the density pass, reused by the force pass: the
  /// first `size` entries (the arrays only grow, so the density loop writes without push_back).
  struct NeighbourList {
    std::vector<std::uint32_t> index;
    std::vector<double> distance;
    std::size_t size = 0;
    /// Room for `more` entries after the first `size`.
    void make_room(std::size_t more) {
      grow_to(index, size + more);
      distance.resize(index.size());
    }
  };
  /// A mirrored twin: its source reflected across wall `a`, then across wall `b` when b >= 0
  /// (a corner); indices into walls_.
  struct Twin {
    std::uint32_t source;
    std::int32_t a, b;
  };
  /// What one thread owns: the twins of its particles, its bounds, its lists.
  struct alignas(64) Part {
    std::vector<Twin> twins;        ///< from the last rebuild, in source order
    std::size_t twin_offset = 0;    ///< index of its first twin in all_x_
    std::size_t active_twins = 0;   ///< twins whose sources are within h of their walls now
    bool moved = false;             ///< a particle moved skin/2 or more since the rebuild
    Bounds bounds;
    GridLayout layout;
    std::vector<std::uint32_t> candidates;  ///< Verlet lists of its particles, back to back (the
    std::size_t candidate_count = 0;        ///< first candidate_count entries; the rest is scratch)
    double work_seconds = 0.0;              ///< its density and force phases since the last rebuild
    std::uint64_t work_cost = 0;            ///< the work units (see balanced_split) they did
    double load_seconds = 0.0;              ///< its load phases since the last rebuild, side work apart
    double side_seconds = 0.0;              ///< the side work it ran in them
    std::uint64_t loaded = 0, loads = 0;    ///< particles it loaded in them, and how many phases
    NeighbourList list;
  };
  struct Inputs {
    const std::vector<Vec2>* x;  ///< null when hooks->load writes the positions and velocities
    const std::vector<Vec2>* v;
    std::span<const double> m;
    std::vector<Vec2>* a;
    const EvaluationHooks* hooks;
  };

  void evaluate(const Inputs& in, bool accelerations);
  void prepare(std::size_t n);
  /// True when this evaluation rebuilds the lists (the same answer on every thread once the load
  /// phase is done).
  bool rebuilding() const;
  // The phases, each for part `part` (see evaluate()).
  void load_and_check(const Inputs& in, int part);
  void find_twins(int part);
  void gather_and_count(int part);
  void place(int part);
  void density_range(int part);
  /// Density of real particle i (eq. 5.5: itself, then its candidates in order) and its pressure;
  /// the candidates within h go into `list` (which must have room for `count` more).
  void density_over(std::size_t i, const std::uint32_t* candidate, std::uint32_t count, NeighbourList& list);
  /// Appends particle i's Verlet list (the grid search) to the part's candidates.
  void find_candidates(std::size_t i, Part& part) const;
  void acceleration_range(const Inputs& in, int part);

  /// Writes the part's twins after the real particles (position, velocity, mass, source, active).
  void write_twins(Part& part);
  Vec2 twin_position(const Twin& t, Vec2 x) const;
  Vec2 twin_velocity(const Twin& t, Vec2 v) const;
  bool twin_active(const Twin& t, Vec2 x) const;
  /// The real particles of part `part` under the split points `split` (parts_.size() + 1 of them).
  static std::pair<std::size_t, std::size_t> part_range(const std::vector<std::size_t>& split, int part) {
    return {split[static_cast<std::size_t>(part)], split[static_cast<std::size_t>(part) + 1]};
  }
  /// The split the density and force phases use in this evaluation (the next one when rebuilding).
  const std::vector<std::size_t>& work_split() const { return rebuilding() ? next_split_ : split_; }
  /// Equal particle counts per part.
  std::vector<std::size_t> equal_split(std::size_t n) const;
  /// Work units per part in proportion to its measured speed (equal work until the parts were
  /// timed), a particle's units being its Verlet list's length plus a little for loading it.
  std::vector<std::size_t> balanced_split() const;
  /// Folds the parts' timings since the last rebuild into speed_ (units per second) and
  /// load_rate_ / side_time_.
  void update_speeds();
  /// Particles per part for the load phase such that each part's load, plus the side work on the
  /// first one, takes the same time (equal counts until the parts were timed).
  std::vector<std::size_t> balanced_load_split() const;

  SphParameters parameters_;
  Kernels kernels_;
  std::vector<Wall> walls_;
  std::vector<const Wall*> mirror_walls_;  ///< the walls with mirror = true
  std::size_t max_mirrors_per_particle_ = 0;
  std::unique_ptr<WorkerPool> pool_;
  PathChooser chooser_;
  std::int64_t evaluations_ = 0, parallel_evaluations_ = 0;
  NeighbourGrid grid_;
  double reach_ = 0.0;  ///< (1 + kListSkin) h: the lists' radius
  bool force_rebuild_ = true, lists_valid_ = false;
  std::size_t listed_count_ = 0;  ///< particles at the last rebuild
  std::int64_t list_rebuilds_ = 0;
  std::size_t real_count_ = 0;
  // Real particles followed by their twins (SoA); sized for the most twins possible.
  std::vector<Vec2> all_x_, all_v_;
  std::vector<double> all_m_;
  std::vector<std::uint32_t> origin_;  ///< the real particle each entry is (or mirrors)
  std::vector<std::uint8_t> active_;   ///< 0 for a twin whose source is h or more from its walls
  std::vector<Vec2> reference_x_;      ///< positions at the last rebuild
  std::vector<double> rho_, p_;        ///< per real particle
  std::vector<double> m_over_rho_;     ///< m_i / ρ_i per real particle (a twin has its source's)
  std::vector<Part> parts_;            ///< one per thread
  /// Which real particles each part owns in the density and force phases: split_[p] ..
  /// split_[p + 1]. A part's Verlet lists belong to these particles, so the split changes only at a
  /// rebuild, to next_split_ (balanced_split: densities differ across the fluid, and with them the
  /// work per particle).
  std::vector<std::size_t> split_, next_split_;
  /// Work units per second of each part in parallel runs (0 until measured). The parts need not be
  /// equally fast: the first one also runs the body's forces and the integrator between
  /// evaluations, and a virtual core may be slowed by its neighbours.
  std::vector<double> speed_;
  /// The load phase has its own split: the first part also runs the side work (the body's forces,
  /// a few microseconds), which its other phases cannot make up for. Twin tables follow this split.
  std::vector<std::size_t> load_split_, next_load_split_;
  std::vector<double> load_rate_;  ///< seconds per particle loaded, per part (0 until measured)
  double side_time_ = 0.0;         ///< seconds of side work per evaluation
  bool timing_ = false;  ///< this evaluation runs in parallel: the parts time their work
  std::vector<NeighbourGrid::Slot> slots_;  ///< every part's real and twin slot, for the placement
  std::vector<std::uint32_t> first_, count_;  ///< per real particle: its slice of its part's list
  std::vector<std::uint32_t> candidates_first_, candidates_count_;  ///< per real particle: its Verlet list
};

}  // namespace jellysim::sph
