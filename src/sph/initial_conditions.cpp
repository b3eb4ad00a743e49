#include "jellysim/sph/initial_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace jellysim::sph {

std::vector<Vec2> triangular_lattice(Vec2 lo, Vec2 hi, double spacing_m) {
  if (!(spacing_m > 0.0)) throw std::invalid_argument("triangular_lattice: spacing must be positive");
  std::vector<Vec2> out;
  const double a = spacing_m, row_height = a * std::sqrt(3.0) / 2.0, eps = 1e-9 * a;
  // Half a spacing from the walls, so that a wall particle's mirrored twin (§5.1.3) sits one
  // spacing away, like the neighbour it replaces.
  for (int row = 0;; ++row) {
    const double y = lo.y + 0.5 * a + row * row_height;
    if (y > hi.y - 0.5 * a + eps) break;
    const double shift = (row % 2 == 0) ? 0.5 : 1.0;
    for (int c = 0;; ++c) {
      const double x = lo.x + (c + shift) * a;
      if (x > hi.x - 0.5 * a + eps) break;
      out.push_back({x, y});
    }
  }
  return out;
}

namespace {

std::vector<Vec2> lattice_outside(Vec2 lo, Vec2 hi, double spacing, const std::function<bool(Vec2)>& excluded) {
  std::vector<Vec2> all = triangular_lattice(lo, hi, spacing), kept;
  for (Vec2 p : all) {
    if (!excluded || !excluded(p)) kept.push_back(p);
  }
  return kept;
}

}  // namespace

std::vector<Vec2> triangular_lattice_with_count(Vec2 lo, Vec2 hi, std::size_t count,
                                                const std::function<bool(Vec2)>& excluded) {
  if (count < 1) throw std::invalid_argument("triangular_lattice_with_count: count must be >= 1");
  const double area = (hi.x - lo.x) * (hi.y - lo.y);
  if (!(area > 0.0)) throw std::invalid_argument("triangular_lattice_with_count: empty box");
  // Spacing of a lattice with `count` points per box area: area per point = (√3/2) a².
  double coarse = 2.0 * std::sqrt(area / (static_cast<double>(count) * std::sqrt(3.0) / 2.0));
  double fine = coarse / 64.0;
  if (lattice_outside(lo, hi, fine, excluded).size() < count) {
    throw std::invalid_argument("triangular_lattice_with_count: the region outside the excluded area is too small");
  }
  for (int it = 0; it < 60; ++it) {  // invariant: fine gives >= count points
    const double mid = 0.5 * (fine + coarse);
    (lattice_outside(lo, hi, mid, excluded).size() >= count ? fine : coarse) = mid;
  }
  std::vector<Vec2> points = lattice_outside(lo, hi, fine, excluded);
  points.resize(count);
  return points;
}

void thermalise(std::vector<Vec2>& x, std::vector<Vec2>& v, double noise_m, double velocity_per_noise,
                std::uint64_t seed) {
  v.resize(x.size());
  std::mt19937_64 rng(seed);  // raw bits mapped by hand: identical streams on every platform
  const auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double radius = noise_m * std::sqrt(uniform()), angle = 2.0 * std::numbers::pi * uniform();
    const Vec2 eps{radius * std::cos(angle), radius * std::sin(angle)};
    x[i] += eps;
    v[i] = eps * (-velocity_per_noise);
  }
}

double relax(std::vector<Vec2>& x, const std::vector<double>& m, const SphParameters& parameters,
             const std::vector<Wall>& walls, int iterations) {
  SphParameters p = parameters;
  p.viscosity = 0.0;  // at rest: viscosity plays no part
  SphFluid fluid(p, walls);
  const std::vector<Vec2> v(x.size());
  std::vector<Vec2> a;
  const double tau = 0.2 * p.smoothing_radius_m / std::sqrt(std::max(p.gas_constant, 1e-300));
  double largest = 0.0;
  for (int it = 0; it <= iterations; ++it) {
    fluid.compute_accelerations(x, v, m, a);
    largest = 0.0;
    for (const Vec2& ai : a) largest = std::max(largest, norm(ai));
    if (it == iterations) break;
    for (std::size_t i = 0; i < x.size(); ++i) {
      x[i] += a[i] * (0.5 * tau * tau);
      Vec2 ignored{};
      reflect_from_walls(walls, x[i], ignored);
    }
  }
  return largest;
}

namespace {

double mean_density(SphFluid& fluid, const std::vector<Vec2>& x, const std::vector<Vec2>& v,
                    const std::vector<double>& m) {
  fluid.compute_density(x, v, m);
  double sum = 0.0;
  for (double rho : fluid.density()) sum += rho;
  return sum / static_cast<double>(x.size());
}

}  // namespace

MassSearch find_particle_mass(const std::vector<Vec2>& x, double area_m2, const SphParameters& parameters,
                              const std::vector<Wall>& walls, double relative_tolerance) {
  if (x.empty() || !(parameters.rest_density > 0.0) || !(area_m2 > 0.0) || !(relative_tolerance > 0.0)) {
    throw std::invalid_argument("find_particle_mass needs particles, ρ0 > 0, area > 0 and tolerance > 0");
  }
  SphFluid fluid(parameters, walls);
  const std::vector<Vec2> v(x.size());
  std::vector<double> m(x.size());
  MassSearch r;
  r.initial_guess_kg = parameters.rest_density * area_m2 / static_cast<double>(x.size());  // eq. 5.21
  const double target = parameters.rest_density, tol = relative_tolerance * target;
  auto density_at = [&](double mass) {
    m.assign(x.size(), mass);
    return mean_density(fluid, x, v, m);
  };
  double lo = r.initial_guess_kg, hi = r.initial_guess_kg;
  while (density_at(lo) > target) lo *= 0.5;  // bracket: ρ(lo) <= ρ0 <= ρ(hi)
  while (density_at(hi) < target) hi *= 2.0;
  for (r.iterations = 0; r.iterations < 200; ++r.iterations) {
    r.mass_kg = 0.5 * (lo + hi);
    r.mean_density = density_at(r.mass_kg);
    if (std::abs(r.mean_density - target) <= tol) break;
    (r.mean_density < target ? lo : hi) = r.mass_kg;
  }
  return r;
}

}  // namespace jellysim::sph
