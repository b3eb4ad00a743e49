#include "jellysim/sph/fluid.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace jellysim::sph {

namespace {

void require(bool ok, const char* field, double value, const char* range) {
  if (ok) return;
  std::ostringstream m;
  m << "fluid." << field << " = " << value << " is out of range " << range;
  throw std::invalid_argument(m.str());
}

}  // namespace

void validate(const SphParameters& p) {
  require(p.smoothing_radius_m > 0.0 && std::isfinite(p.smoothing_radius_m), "smoothing_radius", p.smoothing_radius_m,
          "(0, inf)");
  require(p.rest_density >= 0.0 && std::isfinite(p.rest_density), "rest_density", p.rest_density, "[0, inf)");
  require(p.gas_constant >= 0.0 && std::isfinite(p.gas_constant), "gas_constant", p.gas_constant, "[0, inf)");
  require(p.viscosity >= 0.0 && std::isfinite(p.viscosity), "viscosity", p.viscosity, "[0, inf)");
}

SphFluid::SphFluid(SphParameters parameters, std::vector<Wall> walls, int threads)
    : parameters_(parameters),
      kernels_((validate(parameters), parameters.smoothing_radius_m)),
      walls_(std::move(walls)),
      pool_(std::make_unique<WorkerPool>(threads)),
      reach_((1.0 + kListSkin) * parameters.smoothing_radius_m),
      parts_(static_cast<std::size_t>(threads)) {
  // A particle near k mirroring walls gets at most k twins plus one per pair (corners).
  for (const Wall& w : walls_) {
    if (w.mirror) mirror_walls_.push_back(&w);
  }
  const std::size_t k = mirror_walls_.size();
  max_mirrors_per_particle_ = k + k * (k - 1) / 2;
}

std::size_t SphFluid::mirrored_count() const {
  std::size_t count = 0;
  for (const Part& part : parts_) count += part.active_twins;
  return count;
}

// Sizes every buffer for n real particles and the most twins they can have, so the parallel
// phases never allocate shared memory.
void SphFluid::prepare(std::size_t n) {
  if (n != listed_count_ || !lists_valid_) {
    force_rebuild_ = true;
    split_ = next_split_ = load_split_ = next_load_split_ = equal_split(n);
  }
  real_count_ = n;
  const std::size_t capacity = n * (1 + max_mirrors_per_particle_);
  if (all_x_.size() < capacity) {
    all_x_.resize(capacity);
    all_v_.resize(capacity);
    all_m_.resize(capacity);
    origin_.resize(capacity);
    active_.resize(capacity);
  }
  reference_x_.resize(n);
  rho_.resize(n);
  p_.resize(n);
  m_over_rho_.resize(n);
  first_.resize(n);
  count_.resize(n);
  candidates_first_.resize(n);
  candidates_count_.resize(n);
  grid_.reserve(capacity, 2 * parts_.size());
  slots_.reserve(2 * parts_.size());
}

std::vector<std::size_t> SphFluid::equal_split(std::size_t n) const {
  std::vector<std::size_t> split(parts_.size() + 1);
  for (std::size_t p = 0; p < split.size(); ++p) split[p] = pool_->range(n, static_cast<int>(p)).first;
  split.back() = n;
  return split;
}

namespace {

/// Work units of a particle: its Verlet list (the density pass tests every entry, the force pass
/// the closer ~64 %), plus a little for loading it.
constexpr std::uint64_t kLoadCost = 2;

/// Exponential smoothing of a noisy timing; the first measurement is taken as it is.
double smooth(double old, double measured) { return old > 0.0 ? 0.7 * old + 0.3 * measured : measured; }

}  // namespace

void SphFluid::update_speeds() {
  speed_.resize(parts_.size(), 0.0);
  load_rate_.resize(parts_.size(), 0.0);
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    Part& part = parts_[p];
    if (part.work_seconds > 0.0 && part.work_cost > 0) {
      speed_[p] = smooth(speed_[p], static_cast<double>(part.work_cost) / part.work_seconds);
    }
    if (part.load_seconds > 0.0 && part.loaded > 0) {
      load_rate_[p] = smooth(load_rate_[p], part.load_seconds / static_cast<double>(part.loaded));
      if (p == 0) side_time_ = smooth(side_time_, part.side_seconds / static_cast<double>(part.loads));
    }
    part.work_seconds = part.load_seconds = part.side_seconds = 0.0;
    part.work_cost = part.loaded = part.loads = 0;
  }
}

std::vector<std::size_t> SphFluid::balanced_load_split() const {
  const std::size_t n = real_count_, parts = parts_.size();
  const bool timed = load_rate_.size() == parts && std::all_of(load_rate_.begin(), load_rate_.end(), [](double r) { return r > 0.0; });
  if (!timed) return equal_split(n);
  // Part p loads c_p particles in c_p r_p (+ the side time for p = 0); equal times T with Σ c_p = n.
  double inverse_rates = 0.0, side_particles = side_time_ / load_rate_[0];
  for (double r : load_rate_) inverse_rates += 1.0 / r;
  const double target = (static_cast<double>(n) + side_particles) / inverse_rates;
  std::vector<std::size_t> split(parts + 1, n);
  split[0] = 0;
  double at = 0.0;
  for (std::size_t p = 0; p + 1 < parts; ++p) {
    const double own = std::max(0.0, target / load_rate_[p] - (p == 0 ? side_particles : 0.0));
    // Never below half an equal share: a part loads entries of y' that the force phase of another
    // part wrote, and a far shift would move many of them between cores.
    at += std::max(own, 0.5 * static_cast<double>(n) / static_cast<double>(parts));
    split[p + 1] = std::min(n, static_cast<std::size_t>(std::llround(at)));
    split[p + 1] = std::max(split[p + 1], split[p]);
  }
  return split;
}

std::vector<std::size_t> SphFluid::balanced_split() const {
  const std::size_t n = real_count_, parts = parts_.size();
  // Shares in proportion to speed, kept within [1/2, 3/2] of an equal share.
  std::vector<double> share(parts, 1.0 / static_cast<double>(parts));
  const bool timed = speed_.size() == parts && std::all_of(speed_.begin(), speed_.end(), [](double v) { return v > 0.0; });
  if (timed) {
    double sum = 0.0;
    for (double v : speed_) sum += v;
    double clamped = 0.0;
    for (std::size_t p = 0; p < parts; ++p) {
      share[p] = std::clamp(speed_[p] / sum, 0.5 / static_cast<double>(parts), 1.5 / static_cast<double>(parts));
      clamped += share[p];
    }
    for (double& v : share) v /= clamped;
  }
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) total += static_cast<double>(kLoadCost + candidates_count_[i]);
  std::vector<std::size_t> split(parts + 1, n);
  split[0] = 0;
  double done = 0.0, target = total * share[0];
  for (std::size_t i = 0, p = 1; i < n && p < parts; ++i) {
    while (p < parts && done >= target) {
      split[p] = i;
      target += total * share[p++];
    }
    done += static_cast<double>(kLoadCost + candidates_count_[i]);
  }
  return split;
}

bool SphFluid::rebuilding() const {
  return force_rebuild_ || std::any_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.moved; });
}

// One evaluation as phases separated by barriers (WorkerPool::run_phases):
//   1. load the part's particles into all_*, test how far they moved since the last rebuild, move
//      their twins (§5.1.3); the first part also runs the side work (the body's forces);
//   only when the lists are rebuilt (rebuilding() after phase 1):
//   2. the twin table of the part's particles (those within h + skin/2 of a mirroring wall);
//   3. gather the twins after the real particles, histogram the grid cells of the part's points;
//   4. place every point in the grid (counting sort) on the first thread (a placement shared by the
//      threads cost each twice the whole serial one: every thread needs the full (cell, slot)
//      prefix, and both write into the same cache lines of the sorted index);
//   always:
//   5. densities and pressures of the part's particles (eq. 5.5, p = κ_p (ρ − ρ0)), from the grid
//      when rebuilding (which also fills the part's Verlet lists), from the lists otherwise;
//   6. accelerations of the part's particles (eqs. 5.6, 5.8).
void SphFluid::evaluate(const Inputs& in, bool accelerations) {
  prepare(in.m.size());
  using Phase = WorkerPool::Phase;
  using Gate = WorkerPool::Gate;
  const std::array<Phase, 6> phases{
      Phase([&](int part) { load_and_check(in, part); }), Phase([&](int part) { find_twins(part); }),
      Phase([&](int part) { gather_and_count(part); }),   Phase([&](int part) { place(part); }),
      Phase([&](int part) { density_range(part); }),      Phase([&](int part) { acceleration_range(in, part); })};
  const Gate when_rebuilding([this] { return rebuilding(); });
  const std::array<Gate, 6> gates{Gate(), when_rebuilding, when_rebuilding, when_rebuilding, Gate(), Gate()};
  const std::size_t count = accelerations ? phases.size() : phases.size() - 1;
  const std::span<const Phase> run(phases.data(), count);
  const std::span<const Gate> gated(gates.data(), count);
  ++evaluations_;
  lists_valid_ = false;  // until the evaluation completes
  const bool serial = pool_->threads() == 1 || real_count_ < 64;  // one thread, or too little work to share
  const bool parallel = !serial && chooser_.parallel();
  timing_ = parallel;
  const auto start = std::chrono::steady_clock::now();
  pool_->run_phases(run, gated, parallel);
  const bool rebuilt = rebuilding();
  if (rebuilt) {
    ++list_rebuilds_;
    listed_count_ = real_count_;
    split_ = next_split_;
    load_split_ = next_load_split_;
    update_speeds();
    next_split_ = balanced_split();
    next_load_split_ = balanced_load_split();
  }
  force_rebuild_ = false;
  for (Part& part : parts_) part.moved = false;
  lists_valid_ = true;
  if (serial) return;
  parallel_evaluations_ += parallel ? 1 : 0;
  // A rebuild costs several evaluations: it would decide the comparison for whichever path it fell on.
  if (!rebuilt) chooser_.record(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

Vec2 SphFluid::twin_position(const Twin& t, Vec2 x) const {
  const Vec2 once = walls_[static_cast<std::size_t>(t.a)].mirror_position(x);
  return t.b < 0 ? once : walls_[static_cast<std::size_t>(t.b)].mirror_position(once);
}

Vec2 SphFluid::twin_velocity(const Twin& t, Vec2 v) const {
  const Vec2 once = walls_[static_cast<std::size_t>(t.a)].mirror_velocity(v);
  return t.b < 0 ? once : walls_[static_cast<std::size_t>(t.b)].mirror_velocity(once);
}

// §5.1.3: a particle within h of a mirroring wall sees its twin across it; within h of two walls
// also the twin across both.
bool SphFluid::twin_active(const Twin& t, Vec2 x) const {
  const double h = kernels_.h();
  return walls_[static_cast<std::size_t>(t.a)].distance(x) < h &&
         (t.b < 0 || walls_[static_cast<std::size_t>(t.b)].distance(x) < h);
}

void SphFluid::write_twins(Part& part) {
  std::size_t active = 0;
  for (std::size_t k = 0; k < part.twins.size(); ++k) {
    const Twin& t = part.twins[k];
    const std::size_t at = part.twin_offset + k, i = t.source;
    all_x_[at] = twin_position(t, all_x_[i]);
    all_v_[at] = twin_velocity(t, all_v_[i]);
    all_m_[at] = all_m_[i];
    origin_[at] = t.source;
    const bool on = twin_active(t, all_x_[i]);
    active_[at] = on ? 1 : 0;
    active += on ? 1 : 0;
  }
  part.active_twins = active;
}

void SphFluid::load_and_check(const Inputs& in, int part_index) {
  const auto [begin, end] = part_range(load_split_, part_index);
  using Clock = std::chrono::steady_clock;
  const auto start = timing_ ? Clock::now() : Clock::time_point{};
  Part& part = parts_[static_cast<std::size_t>(part_index)];
  if (in.x == nullptr) {
    in.hooks->load(begin, end, all_x_.data(), all_v_.data());
  } else {
    std::copy(in.x->begin() + static_cast<std::ptrdiff_t>(begin), in.x->begin() + static_cast<std::ptrdiff_t>(end),
              all_x_.begin() + static_cast<std::ptrdiff_t>(begin));
    std::copy(in.v->begin() + static_cast<std::ptrdiff_t>(begin), in.v->begin() + static_cast<std::ptrdiff_t>(end),
              all_v_.begin() + static_cast<std::ptrdiff_t>(begin));
  }
  const double half_skin = 0.5 * (reach_ - kernels_.h()), limit2 = half_skin * half_skin;
  bool moved = false;
  for (std::size_t i = begin; i < end; ++i) {
    all_m_[i] = in.m[i];
    moved |= !(norm_squared(all_x_[i] - reference_x_[i]) < limit2);  // NaN counts as moved
  }
  part.moved = moved;
  if (!force_rebuild_) write_twins(part);  // a rebuild writes them again from new tables
  const auto loaded = timing_ ? Clock::now() : Clock::time_point{};
  if (part_index == 0 && in.hooks != nullptr && in.hooks->side) in.hooks->side();
  if (timing_) {
    part.load_seconds += std::chrono::duration<double>(loaded - start).count();
    part.side_seconds += std::chrono::duration<double>(Clock::now() - loaded).count();
    part.loaded += end - begin;
    ++part.loads;
  }
}

// Rebuild, phase 2: the twins of the part's particles within h + skin/2 of mirroring walls (a
// source moves less than skin/2 before the next rebuild, so no twin can be missing), the reference
// positions and the part's bounds (twins included, at their current positions).
void SphFluid::find_twins(int part_index) {
  const auto [begin, end] = part_range(next_load_split_, part_index);
  Part& part = parts_[static_cast<std::size_t>(part_index)];
  part.twins.clear();
  part.bounds = {};
  const double reach = kernels_.h() + 0.5 * (reach_ - kernels_.h());
  for (std::size_t i = begin; i < end; ++i) {
    const Vec2 xi = all_x_[i];
    reference_x_[i] = xi;
    active_[i] = 1;
    origin_[i] = static_cast<std::uint32_t>(i);
    part.bounds.add(xi);
    bool near_wall = false;  // most particles are not: skip the twin construction for them
    for (const Wall* w : mirror_walls_) near_wall |= w->distance(xi) < reach;
    if (!near_wall) continue;
    for (std::size_t a = 0; a < walls_.size(); ++a) {
      const Wall& wa = walls_[a];
      if (!wa.mirror || !(wa.distance(xi) < reach)) continue;
      const auto source = static_cast<std::uint32_t>(i);
      part.twins.push_back({source, static_cast<std::int32_t>(a), -1});
      for (std::size_t b = a + 1; b < walls_.size(); ++b) {
        const Wall& wb = walls_[b];
        if (wb.mirror && wb.distance(xi) < reach && std::abs(dot(wa.normal, wb.normal)) < 0.999) {
          part.twins.push_back({source, static_cast<std::int32_t>(a), static_cast<std::int32_t>(b)});
        }
      }
    }
  }
  for (const Twin& t : part.twins) part.bounds.add(twin_position(t, all_x_[t.source]));
}

// Rebuild, phase 3. Twins follow the real particles in part order, i.e. in the order of their
// sources, exactly as a single thread would create them. Grid slots: part p owns slot p (its real
// particles) and slot P + p (its twins); slots are consecutive index ranges in that order. The
// cells are (1 + skin) h wide, so the 3 × 3 cells around a point hold everything within its lists'
// radius.
void SphFluid::gather_and_count(int part_index) {
  const std::size_t parts = parts_.size(), p = static_cast<std::size_t>(part_index);
  std::size_t offset = real_count_, total = real_count_;
  Bounds bounds;
  for (std::size_t q = 0; q < parts; ++q) {
    if (q < p) offset += parts_[q].twins.size();
    total += parts_[q].twins.size();
    bounds.merge(parts_[q].bounds);
  }
  Part& part = parts_[p];
  part.twin_offset = offset;
  part.layout = GridLayout::make(bounds, reach_, total);
  write_twins(part);
  const auto [begin, end] = part_range(next_split_, part_index);
  grid_.count(part.layout, all_x_.data(), begin, end, p);
  grid_.count(part.layout, all_x_.data(), offset, offset + part.twins.size(), parts + p);
}

void SphFluid::place(int part_index) {
  if (part_index != 0) return;
  const std::size_t parts = parts_.size();
  slots_.clear();
  for (std::size_t p = 0; p < parts; ++p) {
    const auto [begin, end] = part_range(next_split_, static_cast<int>(p));
    slots_.push_back({p, begin, end});
  }
  for (std::size_t p = 0; p < parts; ++p) {
    const Part& part = parts_[p];
    slots_.push_back({parts + p, part.twin_offset, part.twin_offset + part.twins.size()});
  }
  grid_.place(parts_[0].layout, slots_, 2 * parts);
}

void SphFluid::density_range(int part_index) {
  const auto [begin, end] = part_range(work_split(), part_index);
  Part& part = parts_[static_cast<std::size_t>(part_index)];
  NeighbourList& list = part.list;
  list.size = 0;
  const bool rebuild = rebuilding();
  const bool timed = timing_ && !rebuild;  // a rebuild's search is not the usual work
  const auto start = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  if (rebuild) {
    part.candidate_count = 0;
  } else {
    list.make_room(part.candidate_count);  // a list holds some of its particle's candidates
  }
  std::uint64_t cost = 0;
  for (std::size_t i = begin; i < end; ++i) {
    if (rebuild) {
      candidates_first_[i] = static_cast<std::uint32_t>(part.candidate_count);
      find_candidates(i, part);
      candidates_count_[i] = static_cast<std::uint32_t>(part.candidate_count) - candidates_first_[i];
      list.make_room(candidates_count_[i]);
    }
    first_[i] = static_cast<std::uint32_t>(list.size);
    density_over(i, part.candidates.data() + candidates_first_[i], candidates_count_[i], list);
    count_[i] = static_cast<std::uint32_t>(list.size) - first_[i];
    cost += kLoadCost + candidates_count_[i];
  }
  if (timed) {
    part.work_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    part.work_cost += cost;
  }
}

// The grid search for particle i's Verlet list: the points of the 3 × 3 cells around it within the
// lists' radius (NaN distances kept, as in density_over), in grid order, appended to the part's
// candidates. Without a branch on the test (about a third of the points pass, in no pattern the
// predictor could follow): every point is written, and stays when it passes.
void SphFluid::find_candidates(std::size_t i, Part& part) const {
  const Vec2* x = all_x_.data();
  const Vec2 xi = x[i];
  const double reach2 = reach_ * reach_;
  grid_.for_each_candidate_row(xi, [&](const std::uint32_t* first, const std::uint32_t* last) {
    grow_to(part.candidates, part.candidate_count + static_cast<std::size_t>(last - first));
    std::uint32_t* out = part.candidates.data() + part.candidate_count;
    std::size_t kept = 0;
    for (const std::uint32_t* k = first; k < last; ++k) {
      const std::uint32_t j = *k;
      out[kept] = j;
      kept += static_cast<std::size_t>((j != i) & !(norm_squared(x[j] - xi) >= reach2));  // `&`: no branch
    }
    part.candidate_count += kept;
  });
}

void SphFluid::density_over(std::size_t i, const std::uint32_t* candidate, std::uint32_t count, NeighbourList& list) {
  const double h2 = kernels_.h2(), poly6 = kernels_.poly6_r2(0.0) / (h2 * h2 * h2);
  // Local pointers: the list writes below could otherwise alias them and force reloads.
  const Vec2* x = all_x_.data();
  const double* m = all_m_.data();
  const std::uint8_t* active = active_.data();
  std::uint32_t* index = list.index.data() + list.size;
  double* distance = list.distance.data() + list.size;
  const Vec2 xi = x[i];
  double rho = m[i] * poly6 * h2 * h2 * h2;  // the particle itself
  std::uint32_t kept = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t j = candidate[k];
    const double r2 = norm_squared(x[j] - xi);
    // Pairs closer than h (NaN distances included, so a broken state spreads and is caught). In
    // the larva's run 93 % of the candidates pass, so this branch is well predicted.
    if (r2 >= h2 || active[j] == 0) continue;
    const double d = h2 - r2;
    rho += m[j] * poly6 * (d * d * d);  // eq. 5.5
    index[kept] = j;
    distance[kept] = std::sqrt(r2);
    ++kept;
  }
  list.size += kept;
  rho_[i] = rho;
  p_[i] = parameters_.gas_constant * (rho - parameters_.rest_density);  // equation of state
  m_over_rho_[i] = m[i] / rho;
}

void SphFluid::acceleration_range(const Inputs& in, int part_index) {
  const auto [begin, end] = part_range(work_split(), part_index);
  std::vector<Vec2>& a = *in.a;
  const double h = kernels_.h();
  const double mu = parameters_.viscosity * parameters_.rest_density;  // μ = ν ρ0
  // a = −(1/ρ_i) Σ ... ∇W: the kernel's −30/(π h⁵) and the minus sign of the force give +30/(π h⁵).
  const double spiky_gradient = -kernels_.spiky_derivative(0.0) / (h * h);
  const double viscosity_laplacian = kernels_.viscosity_laplacian(0.0) / h;
  Part& part = parts_[static_cast<std::size_t>(part_index)];
  const bool timed = timing_ && !rebuilding();
  const auto start = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  const NeighbourList& list = part.list;
  for (std::size_t i = begin; i < end; ++i) {
    const Vec2 xi = all_x_[i], vi = all_v_[i];
    const double p_i = p_[i];
    Vec2 pressure{}, viscous{};
    const std::uint32_t k0 = first_[i], k1 = first_[i] + count_[i];
    for (std::uint32_t k = k0; k < k1; ++k) {
      const std::size_t j = list.index[k], o = origin_[j];  // a mirror has its source's m, ρ and p
      const double r = list.distance[k], q = h - r;
      const double mj_rhoj = m_over_rho_[o];
      // eq. 5.6: ∇W_spiky = −30/(π h⁵) (h − r)² x̂ (constant applied below); r = 0 pairs add nothing.
      const double inv_r = r > 0.0 ? 1.0 / r : 0.0;
      pressure += (xi - all_x_[j]) * (q * q * inv_r * mj_rhoj * 0.5 * (p_i + p_[o]));
      // eq. 5.8: ∇²W_visc = 40/(π h⁵) (h − r), with v_j − v_i.
      viscous += (all_v_[j] - vi) * (mj_rhoj * q);
    }
    const double rho_i = rho_[i];
    a[i] = pressure * (spiky_gradient / rho_i) + viscous * (mu * viscosity_laplacian / rho_i);
  }
  if (in.hooks != nullptr && in.hooks->store) in.hooks->store(begin, end);
  if (timed) part.work_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {

void require_same_sizes(std::size_t x, std::size_t v, std::size_t m) {
  if (x != v || x != m) throw std::invalid_argument("SphFluid: positions, velocities and masses differ in size");
}

}  // namespace

void SphFluid::compute_density(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m) {
  require_same_sizes(x.size(), v.size(), m.size());
  evaluate({&x, &v, m, nullptr, nullptr}, false);
}

void SphFluid::compute_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                                     const std::vector<double>& m, std::vector<Vec2>& a, const EvaluationHooks& hooks) {
  require_same_sizes(x.size(), v.size(), m.size());
  if (hooks.load) throw std::invalid_argument("SphFluid: a load hook needs the overload without x and v");
  a.resize(x.size());
  evaluate({&x, &v, m, &a, &hooks}, true);
}

void SphFluid::compute_accelerations(std::span<const double> m, std::vector<Vec2>& a, const EvaluationHooks& hooks) {
  if (!hooks.load) throw std::invalid_argument("SphFluid: this overload needs a load hook");
  a.resize(m.size());
  evaluate({nullptr, nullptr, m, &a, &hooks}, true);
}

}  // namespace jellysim::sph
