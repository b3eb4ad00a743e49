#include "sph/fluid.hpp"

#include <algorithm>
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
      pool_(std::make_unique<WorkerPool>(threads)) {}

void SphFluid::add_mirror(std::size_t source, Vec2 x, Vec2 v, double m) {
  all_x_.push_back(x);
  all_v_.push_back(v);
  all_m_.push_back(m);
  source_.push_back(source);
}

// §5.1.3: every particle within h of a mirroring wall gets a twin reflected across it (position and
// velocity); near a corner of two walls also the twin reflected across both.
void SphFluid::build_mirrors(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m) {
  const std::size_t n = x.size();
  const double h = kernels_.h();
  real_count_ = n;
  all_x_.assign(x.begin(), x.end());
  all_v_.assign(v.begin(), v.end());
  all_m_.assign(m.begin(), m.end());
  source_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t a = 0; a < walls_.size(); ++a) {
      const Wall& wa = walls_[a];
      if (!wa.mirror || wa.distance(x[i]) >= h) continue;
      const Vec2 xa = wa.mirror_position(x[i]), va = wa.mirror_velocity(v[i]);
      add_mirror(i, xa, va, m[i]);
      for (std::size_t b = a + 1; b < walls_.size(); ++b) {
        const Wall& wb = walls_[b];
        if (wb.mirror && wb.distance(x[i]) < h && std::abs(dot(wa.normal, wb.normal)) < 0.999) {
          add_mirror(i, wb.mirror_position(xa), wb.mirror_velocity(va), m[i]);
        }
      }
    }
  }
}

void SphFluid::density_range(std::size_t begin, std::size_t end, int part) {
  const double h2 = kernels_.h2(), poly6 = kernels_.poly6_r2(0.0) / (h2 * h2 * h2);
  NeighbourList& list = lists_[static_cast<std::size_t>(part)];
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
    all_rho_[i] = rho;
  }
}

void SphFluid::compute_density(const std::vector<Vec2>& x, const std::vector<Vec2>& v, const std::vector<double>& m) {
  build_mirrors(x, v, m);
  grid_.build(all_x_, kernels_.h());
  const std::size_t total = all_x_.size();
  all_rho_.resize(total);
  all_p_.resize(total);
  lists_.resize(static_cast<std::size_t>(pool_->threads()));
  first_.resize(real_count_);
  count_.resize(real_count_);
  pool_->run(real_count_, [this](std::size_t b, std::size_t e, int part) { density_range(b, e, part); });
  // A mirror has its source's density by symmetry; equation of state p = κ_p (ρ − ρ0).
  for (std::size_t k = real_count_; k < total; ++k) all_rho_[k] = all_rho_[source_[k - real_count_]];
  for (std::size_t k = 0; k < total; ++k) all_p_[k] = parameters_.gas_constant * (all_rho_[k] - parameters_.rest_density);
  density_.assign(all_rho_.begin(), all_rho_.begin() + static_cast<std::ptrdiff_t>(real_count_));
}

void SphFluid::acceleration_range(std::size_t begin, std::size_t end, int part, std::vector<Vec2>& a) const {
  const double h = kernels_.h();
  const double mu = parameters_.viscosity * parameters_.rest_density;  // μ = ν ρ0
  // a = −(1/ρ_i) Σ ... ∇W: the kernel's −30/(π h⁵) and the minus sign of the force give +30/(π h⁵).
  const double spiky_gradient = -kernels_.spiky_derivative(0.0) / (h * h);
  const double viscosity_laplacian = kernels_.viscosity_laplacian(0.0) / h;
  const NeighbourList& list = lists_[static_cast<std::size_t>(part)];
  for (std::size_t i = begin; i < end; ++i) {
    const Vec2 xi = all_x_[i], vi = all_v_[i];
    const double p_i = all_p_[i];
    Vec2 pressure{}, viscous{};
    const std::uint32_t k0 = first_[i], k1 = first_[i] + count_[i];
    for (std::uint32_t k = k0; k < k1; ++k) {
      const std::size_t j = list.index[k];
      const double r = list.distance[k], q = h - r;
      const double mj_rhoj = all_m_[j] / all_rho_[j];
      // eq. 5.6: ∇W_spiky = −30/(π h⁵) (h − r)² x̂ (constant applied below); r = 0 pairs add nothing.
      const double inv_r = r > 0.0 ? 1.0 / r : 0.0;
      pressure += (xi - all_x_[j]) * (q * q * inv_r * mj_rhoj * 0.5 * (p_i + all_p_[j]));
      // eq. 5.8: ∇²W_visc = 40/(π h⁵) (h − r), with v_j − v_i.
      viscous += (all_v_[j] - vi) * (mj_rhoj * q);
    }
    const double rho_i = all_rho_[i];
    a[i] = pressure * (spiky_gradient / rho_i) + viscous * (mu * viscosity_laplacian / rho_i);
  }
}

void SphFluid::compute_accelerations(const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                                     const std::vector<double>& m, std::vector<Vec2>& a) {
  compute_density(x, v, m);
  a.resize(x.size());
  pool_->run(real_count_, [this, &a](std::size_t b, std::size_t e, int part) { acceleration_range(b, e, part, a); });
}

}  // namespace jellysim::sph
