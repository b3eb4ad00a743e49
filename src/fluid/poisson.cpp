#include "jellysim/fluid/poisson.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "double2.hpp"
#include "jellysim/fluid/direct_poisson.hpp"
#include "jellysim/fluid/fft_poisson.hpp"
#include "jellysim/fluid/multigrid.hpp"
#include "jellysim/fluid/sor.hpp"

namespace jellysim::fluid {
namespace {

// Eq. 4.10 generalised: weight 1/h² for a neighbour, 0 on a Neumann side; a Dirichlet side
// contributes 2/h² to the diagonal (ghost = −p puts p = 0 on the side).
StencilAxis make_axis(int n, double h, PressureBoundary lower_side, PressureBoundary upper_side) {
  StencilAxis a;
  const double w = 1.0 / (h * h);
  a.lower.resize(n);
  a.upper.resize(n);
  a.lower_weight.resize(n);
  a.upper_weight.resize(n);
  a.diagonal.resize(n);
  for (int k = 0; k < n; ++k) {
    double diag = 0.0;
    auto neighbour = [&](int other, bool inside, PressureBoundary side, int& index, double& weight) {
      if (inside || side == PressureBoundary::periodic) {
        index = inside ? other : (other + n) % n;
        weight = w;
        diag += w;
      } else {
        index = k;
        weight = 0.0;
        if (side == PressureBoundary::dirichlet) diag += 2.0 * w;
      }
    };
    neighbour(k - 1, k > 0, lower_side, a.lower[k], a.lower_weight[k]);
    neighbour(k + 1, k < n - 1, upper_side, a.upper[k], a.upper_weight[k]);
    a.diagonal[k] = diag;
  }
  return a;
}

/// The radial axis: cell i at r_i = (i + ½)h between faces r_{i−½} = ih and r_{i+½} = (i + 1)h;
/// neighbour weights r_{i∓½}/(r_i h²). The axis face (r = 0) has no neighbour and no weight; the
/// outer side is Neumann (no flux) or Dirichlet (ghost −p: 2 r_{n}/(r_{n−½} h²) on the diagonal).
StencilAxis make_radial_axis(int n, double h, PressureBoundary outer_side) {
  StencilAxis a = make_axis(n, h, PressureBoundary::neumann, outer_side);
  a.volume.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double r = (k + 0.5) * h, inner = k * h, outer = (k + 1) * h;
    const double w = 1.0 / (r * h * h);
    a.volume[static_cast<std::size_t>(k)] = r;
    a.lower_weight[k] = k > 0 ? inner * w : 0.0;
    a.upper_weight[k] = k < n - 1 ? outer * w : 0.0;
    a.diagonal[k] = a.lower_weight[k] + a.upper_weight[k];
    if (k == n - 1 && outer_side == PressureBoundary::dirichlet) a.diagonal[k] += 2.0 * outer * w;
  }
  return a;
}

void require_opposite_periodic_pairs(const std::array<PressureBoundary, 4>& sides) {
  if ((sides[0] == PressureBoundary::periodic) != (sides[1] == PressureBoundary::periodic) ||
      (sides[2] == PressureBoundary::periodic) != (sides[3] == PressureBoundary::periodic))
    throw std::invalid_argument("PoissonOperator: periodic sides must come in opposite pairs");
}

}  // namespace

std::string_view to_string(Geometry g) { return g == Geometry::planar ? "planar" : "axisymmetric"; }

PoissonOperator::PoissonOperator(int nx, int ny, double dx, double dy,
                                 std::array<PressureBoundary, 4> sides)
    : nx_(nx), ny_(ny), dx_(dx), dy_(dy), sides_(sides),
      x_(make_axis(nx, dx, sides[0], sides[1])),
      y_(make_axis(ny, dy, sides[2], sides[3])) {
  require_opposite_periodic_pairs(sides);
}

PoissonOperator::PoissonOperator(int nx, int ny, double dx, double dy, std::array<PressureBoundary, 4> sides,
                                 StencilAxis x, StencilAxis y)
    : nx_(nx), ny_(ny), dx_(dx), dy_(dy), sides_(sides), x_(std::move(x)), y_(std::move(y)) {
  require_opposite_periodic_pairs(sides);
}

PoissonOperator PoissonOperator::axisymmetric(int nr, int nz, double dr, double dz,
                                              std::array<PressureBoundary, 4> sides) {
  if (sides[0] != PressureBoundary::neumann)
    throw std::invalid_argument("axisymmetric PoissonOperator: the west side is the axis and must be Neumann");
  if (sides[1] == PressureBoundary::periodic)
    throw std::invalid_argument("axisymmetric PoissonOperator: the radial axis cannot be periodic");
  return PoissonOperator(nr, nz, dr, dz, sides, make_radial_axis(nr, dr, sides[1]), make_axis(nz, dz, sides[2], sides[3]));
}

PoissonOperator PoissonOperator::transposed() const {
  // West/east of the transposed problem are this one's south/north, and the other way round.
  return PoissonOperator(ny_, nx_, dy_, dx_, {sides_[2], sides_[3], sides_[0], sides_[1]}, y_, x_);
}

void PoissonOperator::remove_weighted_mean(std::span<double> values) const {
  if (uniform()) {
    remove_mean(values);
    return;
  }
  double weighted = 0.0, total = 0.0;
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const double w = (x_.volume.empty() ? 1.0 : x_.volume[static_cast<std::size_t>(i)]) *
                       (y_.volume.empty() ? 1.0 : y_.volume[static_cast<std::size_t>(j)]);
      weighted += w * values[static_cast<std::size_t>(j) * nx_ + i];
      total += w;
    }
  const double mean = weighted / total;
  for (double& v : values) v -= mean;
}

bool PoissonOperator::singular() const {
  return std::none_of(sides_.begin(), sides_.end(),
                      [](PressureBoundary s) { return s == PressureBoundary::dirichlet; });
}

bool PoissonOperator::same_problem(const PoissonOperator& o) const {
  return nx_ == o.nx_ && ny_ == o.ny_ && dx_ == o.dx_ && dy_ == o.dy_ && sides_ == o.sides_ &&
         x_.volume.empty() == o.x_.volume.empty() && y_.volume.empty() == o.y_.volume.empty();
}

double PoissonOperator::neighbour_sum(std::span<const double> p, int i, int j) const {
  const std::size_t row = static_cast<std::size_t>(j) * nx_;
  return x_.lower_weight[i] * p[row + x_.lower[i]] + x_.upper_weight[i] * p[row + x_.upper[i]] +
         y_.lower_weight[j] * p[static_cast<std::size_t>(y_.lower[j]) * nx_ + i] +
         y_.upper_weight[j] * p[static_cast<std::size_t>(y_.upper[j]) * nx_ + i];
}

template <class Visit>
void PoissonOperator::for_each_laplacian(std::span<const double> p, Visit&& visit) const {
  // Interior cells use the plain five-point stencil; the boundary ring uses the eq. 4.10 tables.
  const double cx = 1.0 / (dx_ * dx_);
  const double cy = 1.0 / (dy_ * dy_);
  const double centre = 2.0 * cx + 2.0 * cy;
  for (int j = 0; j < ny_; ++j) {
    const std::size_t row = static_cast<std::size_t>(j) * nx_;
    const bool interior_row = j > 0 && j < ny_ - 1 && nx_ >= 3 && uniform();
    if (!interior_row) {
      for (int i = 0; i < nx_; ++i) visit(row + i, neighbour_sum(p, i, j) - diagonal(i, j) * p[row + i]);
      continue;
    }
    visit(row, neighbour_sum(p, 0, j) - diagonal(0, j) * p[row]);
    const double* q = p.data() + row;
    for (int i = 1; i < nx_ - 1; ++i)
      visit(row + i, cx * (q[i - 1] + q[i + 1]) + cy * (q[i - nx_] + q[i + nx_]) - centre * q[i]);
    visit(row + nx_ - 1, neighbour_sum(p, nx_ - 1, j) - diagonal(nx_ - 1, j) * p[row + nx_ - 1]);
  }
}

void PoissonOperator::apply(std::span<const double> p, std::span<double> out) const {
  for_each_laplacian(p, [&](std::size_t k, double lap) { out[k] = lap; });
}

void PoissonOperator::residual(std::span<const double> p, std::span<const double> b, std::span<double> r) const {
  for_each_laplacian(p, [&](std::size_t k, double lap) { r[k] = b[k] - lap; });
}

void PoissonOperator::residual_row(std::span<const double> p, std::span<const double> b, int j, double* out) const {
  const std::size_t row = static_cast<std::size_t>(j) * nx_;
  const double* br = b.data() + row;
  auto edge = [&](int i) { out[i] = br[i] - (neighbour_sum(p, i, j) - diagonal(i, j) * p[row + i]); };
  if (!(j > 0 && j < ny_ - 1 && nx_ >= 3 && uniform())) {
    for (int i = 0; i < nx_; ++i) edge(i);
    return;
  }
  const double cx = 1.0 / (dx_ * dx_);
  const double cy = 1.0 / (dy_ * dy_);
  const double centre = 2.0 * cx + 2.0 * cy;
  const double* q = p.data() + row;
  edge(0);
  for (int i = 1; i < nx_ - 1; ++i)
    out[i] = br[i] - (cx * (q[i - 1] + q[i + 1]) + cy * (q[i - nx_] + q[i + nx_]) - centre * q[i]);
  edge(nx_ - 1);
}

double PoissonOperator::residual_max(std::span<const double> p, std::span<const double> b) const {
  // Same stencil as for_each_laplacian, with four running maxima on the interior rows so that the
  // loop is not bound by the latency of one max (the result is the same number).
  const double cx = 1.0 / (dx_ * dx_);
  const double cy = 1.0 / (dy_ * dy_);
  const double centre = 2.0 * cx + 2.0 * cy;
  double m[4] = {0.0, 0.0, 0.0, 0.0};
  simd::Double2 m2a{0.0, 0.0}, m2b{0.0, 0.0};
  auto edge = [&](int i, int j) {
    const std::size_t k = static_cast<std::size_t>(j) * nx_ + i;
    m[0] = std::max(m[0], std::abs(b[k] - (neighbour_sum(p, i, j) - diagonal(i, j) * p[k])));
  };
  for (int j = 0; j < ny_; ++j) {
    const bool interior_row = j > 0 && j < ny_ - 1 && nx_ >= 3 && uniform();
    if (!interior_row) {
      for (int i = 0; i < nx_; ++i) edge(i, j);
      continue;
    }
    edge(0, j);
    const std::size_t row = static_cast<std::size_t>(j) * nx_;
    const double* q = p.data() + row;
    const double* br = b.data() + row;
    auto pair = [&](int k) {
      using namespace simd;
      const Double2 lap = cx * (load2(q + k - 1) + load2(q + k + 1)) + cy * (load2(q + k - nx_) + load2(q + k + nx_)) -
                          centre * load2(q + k);
      return abs2(load2(br + k) - lap);
    };
    int i = 1;
    for (; i + 4 <= nx_ - 1; i += 4) {
      m2a = simd::max2(m2a, pair(i));
      m2b = simd::max2(m2b, pair(i + 2));
    }
    for (; i < nx_ - 1; ++i)
      m[0] = std::max(m[0], std::abs(br[i] - (cx * (q[i - 1] + q[i + 1]) + cy * (q[i - nx_] + q[i + nx_]) - centre * q[i])));
    edge(nx_ - 1, j);
  }
  const simd::Double2 m2 = simd::max2(m2a, m2b);
  return std::max(m[0], std::max(m2[0], m2[1]));
}

PoissonOperator PoissonOperator::coarsened() const {
  if (nx_ % 2 != 0 || ny_ % 2 != 0)
    throw std::logic_error("PoissonOperator::coarsened needs even cell counts");
  if (!uniform()) throw std::logic_error("PoissonOperator::coarsened: planar operators only");
  return PoissonOperator(nx_ / 2, ny_ / 2, 2.0 * dx_, 2.0 * dy_, sides_);
}

void remove_mean(std::span<double> values) {
  if (values.empty()) return;
  // Four partial sums in a fixed order (deterministic, not latency-bound).
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  const std::size_t n = values.size();
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4)
    for (std::size_t l = 0; l < 4; ++l) s[l] += values[k + l];
  for (; k < n; ++k) s[0] += values[k];
  const double mean = ((s[0] + s[1]) + (s[2] + s[3])) / static_cast<double>(n);
  for (double& v : values) v -= mean;
}

double max_abs(std::span<const double> values) {
  double m[4] = {0.0, 0.0, 0.0, 0.0};
  const std::size_t n = values.size();
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4)
    for (std::size_t l = 0; l < 4; ++l) {
      const double a = std::abs(values[k + l]);
      m[l] = m[l] > a ? m[l] : a;
    }
  for (; k < n; ++k) m[0] = std::max(m[0], std::abs(values[k]));
  return std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
}

const std::vector<std::string>& pressure_solver_names() {
  static const std::vector<std::string> names{"sor", "multigrid", "direct", "fft"};
  return names;
}

std::unique_ptr<PressureSolver> make_pressure_solver(std::string_view name,
                                                     const PressureSolverSettings& settings) {
  if (name == "sor") return std::make_unique<SorSolver>(settings);
  if (name == "multigrid") return std::make_unique<MultigridSolver>(settings);
  if (name == "direct") return std::make_unique<DirectPoissonSolver>();
  if (name == "fft") return std::make_unique<FftPoissonSolver>();
  throw std::invalid_argument("unknown pressure solver '" + std::string(name) +
                              "' (expected sor, multigrid, direct or fft)");
}

int conjugate_gradient_poisson(const PoissonOperator& op, std::span<const double> b,
                               std::span<double> p, double relative_tolerance, int max_iterations) {
  // Solves A p = c with A = −∇² (SPD, or semi-definite with the constants as null space) and
  // c = −b. Residual r = c − A p = −(b − ∇²p).
  const std::size_t n = p.size();
  std::vector<double> r(n), d(n), q(n);
  op.residual(p, b, r);
  for (double& x : r) x = -x;
  if (op.singular()) remove_mean(r);
  const double b_norm = std::max(max_abs(b), 1e-300);
  d = r;
  double rr = std::inner_product(r.begin(), r.end(), r.begin(), 0.0);
  int it = 0;
  for (; it < max_iterations && max_abs(r) > relative_tolerance * b_norm; ++it) {
    op.apply(d, q);
    for (double& x : q) x = -x;  // q = A d
    const double dq = std::inner_product(d.begin(), d.end(), q.begin(), 0.0);
    if (!(dq > 0.0)) break;
    const double alpha = rr / dq;
    for (std::size_t k = 0; k < n; ++k) {
      p[k] += alpha * d[k];
      r[k] -= alpha * q[k];
    }
    if (op.singular()) remove_mean(r);
    const double rr_new = std::inner_product(r.begin(), r.end(), r.begin(), 0.0);
    const double beta = rr_new / rr;
    rr = rr_new;
    for (std::size_t k = 0; k < n; ++k) d[k] = r[k] + beta * d[k];
  }
  if (op.singular()) remove_mean(p);
  return it;
}

}  // namespace jellysim::fluid
