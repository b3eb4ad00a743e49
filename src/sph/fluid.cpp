#include "sph/fluid.hpp"

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
      parts_(static_cast<std::size_t>(threads)) {
  // A particle near k mirroring walls gets at most k twins plus one per pair (corners).
  for (const Wall& w : walls_) {
    if (w.mirror) mirror_walls_.push_back(&w);
  }
  const std::size_t k = mirror_walls_.size();
  max_mirrors_per_particle_ = k + k * (k - 1) / 2;
}

// Sizes every buffer for n real particles and the most mirrors they can have, so the parallel
// phases never allocate shared memory.
void SphFluid::prepare(std::size_t n) {
  real_count_ = n;
  const std::size_t capacity = n * (1 + max_mirrors_per_particle_);
  if (all_x_.size() < capacity) {
    all_x_.resize(capacity);
    all_v_.resize(capacity);
    all_m_.resize(capacity);
    origin_.resize(capacity);
  }
  rho_.resize(n);
  p_.resize(n);
  first_.resize(n);
  count_.resize(n);
  grid_.reserve(capacity, 2 * parts_.size());
  slots_.reserve(2 * parts_.size());
}

// One evaluation as phases separated by barriers (WorkerPool::run_phases):
//   1. load the part's particles, copy them into all_*, create their mirrors (§5.1.3);
//   2. gather the mirrors after the real particles, histogram the grid cells of the part's points;
//   3. place every point in the grid (counting sort) on the first thread, while the last one runs
//      the independent side work (the body's forces); a placement shared by the threads cost each
//      twice the whole serial one (every thread needs the full (cell, slot) prefix, and both write
//      into the same cache lines of the sorted index);
//   4. densities and pressures of the part's particles (eq. 5.5, p = κ_p (ρ − ρ0));
//   5. accelerations of the part's particles (eqs. 5.6, 5.8).
void SphFluid::evaluate(const Inputs& in, bool accelerations) {
  prepare(in.x->size());
  using Phase = WorkerPool::Phase;
  const std::array<Phase, 5> phases{
      Phase([&](int part) { load_and_mirror(in, part); }), Phase([&](int part) { gather_and_count(part); }),
      Phase([&](int part) { place_and_side(in, part); }), Phase([&](int part) { density_range(part); }),
      Phase([&](int part) { acceleration_range(in, part); })};
  const std::size_t count = accelerations ? phases.size() : phases.size() - 1;
  const std::span<const Phase> run(phases.data(), count);
  ++evaluations_;
  if (pool_->threads() == 1 || real_count_ < 64) {  // one thread, or too little work to share
    pool_->run_phases(run, false);
    return;
  }
  const bool parallel = chooser_.parallel();
  parallel_evaluations_ += parallel ? 1 : 0;
  const auto start = std::chrono::steady_clock::now();
  pool_->run_phases(run, parallel);
  chooser_.record(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

// §5.1.3: every particle within h of a mirroring wall gets a twin reflected across it (position and
// velocity); near a corner of two walls also the twin reflected across both.
void SphFluid::add_mirrors(Part& part, std::size_t i, Vec2 x, Vec2 v, double m) const {
  const double h = kernels_.h();
  const auto push = [&](Vec2 mx, Vec2 mv) {
    part.mirror_x.push_back(mx);
    part.mirror_v.push_back(mv);
    part.mirror_m.push_back(m);
    part.mirror_source.push_back(static_cast<std::uint32_t>(i));
    part.bounds.add(mx);
  };
  for (std::size_t a = 0; a < walls_.size(); ++a) {
    const Wall& wa = walls_[a];
    if (!wa.mirror || wa.distance(x) >= h) continue;
    const Vec2 xa = wa.mirror_position(x), va = wa.mirror_velocity(v);
    push(xa, va);
    for (std::size_t b = a + 1; b < walls_.size(); ++b) {
      const Wall& wb = walls_[b];
      if (wb.mirror && wb.distance(x) < h && std::abs(dot(wa.normal, wb.normal)) < 0.999) {
        push(wb.mirror_position(xa), wb.mirror_velocity(va));
      }
    }
  }
}

void SphFluid::load_and_mirror(const Inputs& in, int part_index) {
  const auto [begin, end] = real_range(part_index);
  if (in.hooks != nullptr && in.hooks->load) in.hooks->load(begin, end);
  Part& part = parts_[static_cast<std::size_t>(part_index)];
  part.mirror_x.clear();
  part.mirror_v.clear();
  part.mirror_m.clear();
  part.mirror_source.clear();
  part.bounds = {};
  const std::vector<Vec2>& x = *in.x;
  const std::vector<Vec2>& v = *in.v;
  const std::vector<double>& m = *in.m;
  const double h = kernels_.h();
  for (std::size_t i = begin; i < end; ++i) {
    all_x_[i] = x[i];
    all_v_[i] = v[i];
    all_m_[i] = m[i];
    origin_[i] = static_cast<std::uint32_t>(i);
    part.bounds.add(x[i]);
    bool near_wall = false;  // most particles are not: skip the twin construction for them
    for (const Wall* w : mirror_walls_) near_wall |= w->distance(x[i]) < h;
    if (near_wall) add_mirrors(part, i, x[i], v[i], m[i]);
  }
}

// Mirrors follow the real particles in part order, i.e. in the order of their sources, exactly as a
// single thread would create them. Grid slots: part p owns slot p (its real particles) and slot
// P + p (its mirrors); slots are consecutive index ranges in that order.
void SphFluid::gather_and_count(int part_index) {
  const std::size_t parts = parts_.size(), p = static_cast<std::size_t>(part_index);
  std::size_t offset = real_count_, total = real_count_;
  Bounds bounds;
  for (std::size_t q = 0; q < parts; ++q) {
    if (q < p) offset += parts_[q].mirror_x.size();
    total += parts_[q].mirror_x.size();
    bounds.merge(parts_[q].bounds);
  }
  Part& part = parts_[p];
  part.mirror_offset = offset;
  part.layout = GridLayout::make(bounds, kernels_.h(), total);
  if (p == 0) total_ = total;
  for (std::size_t k = 0; k < part.mirror_x.size(); ++k) {
    all_x_[offset + k] = part.mirror_x[k];
    all_v_[offset + k] = part.mirror_v[k];
    all_m_[offset + k] = part.mirror_m[k];
    origin_[offset + k] = part.mirror_source[k];
  }
  const auto [begin, end] = real_range(part_index);
  grid_.count(part.layout, all_x_.data(), begin, end, p);
  grid_.count(part.layout, all_x_.data(), offset, offset + part.mirror_x.size(), parts + p);
}

void SphFluid::place_and_side(const Inputs& in, int part_index) {
  const std::size_t parts = parts_.size();
  if (part_index == 0) {
    slots_.clear();
    for (std::size_t p = 0; p < parts; ++p) {
      const auto [begin, end] = real_range(static_cast<int>(p));
      slots_.push_back({p, begin, end});
    }
    for (std::size_t p = 0; p < parts; ++p) {
      const Part& part = parts_[p];
      slots_.push_back({parts + p, part.mirror_offset, part.mirror_offset + part.mirror_x.size()});
    }
    grid_.place(parts_[0].layout, slots_, 2 * parts);
  }
  if (part_index + 1 == static_cast<int>(parts) && in.hooks != nullptr && in.hooks->side) in.hooks->side();
}

void SphFluid::density_range(int part_index) {
  const auto [begin, end] = real_range(part_index);
  const double h2 = kernels_.h2(), poly6 = kernels_.poly6_r2(0.0) / (h2 * h2 * h2);
  NeighbourList& list = parts_[static_cast<std::size_t>(part_index)].list;
  list.index.clear();
  list.distance.clear();
  for (std::size_t i = begin; i < end; ++i) {
    const Vec2 xi = all_x_[i];
    double rho = all_m_[i] * poly6 * h2 * h2 * h2;  // the particle itself
    first_[i] = static_cast<std::uint32_t>(list.index.size());
    grid_.for_each_candidate(xi, [&](std::size_t j) {
      const double r2 = norm_squared(all_x_[j] - xi);
      if (r2 >= h2 || j == i) return;
      const double d = h2 - r2;
      rho += all_m_[j] * poly6 * (d * d * d);  // eq. 5.5
      list.index.push_back(static_cast<std::uint32_t>(j));
      list.distance.push_back(std::sqrt(r2));
    });
    count_[i] = static_cast<std::uint32_t>(list.index.size()) - first_[i];
    rho_[i] = rho;
    p_[i] = parameters_.gas_constant * (rho - parameters_.rest_density);  // equation of state
  }
}

void SphFluid::acceleration_range(const Inputs& in, int part_index) {
  const auto [begin, end] = real_range(part_index);
  std::vector<Vec2>& a = *in.a;
  const double h = kernels_.h();
  const double mu = parameters_.viscosity * parameters_.rest_density;  // μ = ν ρ0
  // a = −(1/ρ_i) Σ ... ∇W: the kernel's −30/(π h⁵) and the minus sign of the force give +30/(π h⁵).
  const double spiky_gradient = -kernels_.spiky_derivative(0.0) / (h * h);
  const double viscosity_laplacian = kernels_.viscosity_laplacian(0.0) / h;
  const NeighbourList& list = parts_[static_cast<std::size_t>(part_index)].list;
  for (std::size_t i = begin; i < end; ++i) {
    const Vec2 xi = all_x_[i], vi = all_v_[i];
    const double p_i = p_[i];
    Vec2 pressure{}, viscous{};
    const std::uint32_t k0 = first_[i], k1 = first_[i] + count_[i];
    for (std::uint32_t k = k0; k < k1; ++k) {
      const std::size_t j = list.index[k], o = origin_[j];  // a mirror has its source's ρ and p
      const double r = list.distance[k], q = h - r;
      const double mj_rhoj = all_m_[j] / rho_[o];
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
}

void SphFluid::compute_density(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m) {
  evaluate({&x, &v, &m, nullptr, nullptr}, false);
}

void SphFluid::compute_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                                     const std::vector<double>& m, std::vector<Vec2>& a, const EvaluationHooks& hooks) {
  a.resize(x.size());
  evaluate({&x, &v, &m, &a, &hooks}, true);
}

}  // namespace jellysim::sph
