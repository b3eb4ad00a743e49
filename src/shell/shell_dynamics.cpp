#include "jellysim/shell/shell_dynamics.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>

namespace jellysim::shell {

ShellSystem::ShellSystem(ShellBody& body, ShellLoads loads, std::function<void(double)> before_force)
    : body_(body), loads_(std::move(loads)), before_force_(std::move(before_force)) {
  const auto n = static_cast<std::size_t>(position_size());
  if (!loads_.external_force.size()) loads_.external_force = Vector::Zero(position_size());
  if (loads_.fixed.empty()) loads_.fixed.assign(n, 0);
  if (static_cast<std::size_t>(loads_.external_force.size()) != n || loads_.fixed.size() != n)
    throw std::invalid_argument("ShellSystem: loads sized for another body");
}

Vector ShellSystem::initial_state(const Vector& x) const {
  Vector y = Vector::Zero(dimension());
  y.head(position_size()) = x;
  return y;
}

void ShellSystem::compute_derivative(double t, const ode::Vector& y, ode::Vector& dydt) const {
  const Eigen::Index n = position_size();
  if (before_force_) before_force_(t);
  Vector f = loads_.external_force;
  add_elastic_forces(body_, y.head(n), f);
  dydt.resize(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool held = loads_.fixed[static_cast<std::size_t>(i)] != 0;
    const double m = body_.mass_kg[static_cast<std::size_t>(i / 3)];
    const double v = y(n + i);
    dydt(i) = held ? 0.0 : v;
    dydt(n + i) = held ? 0.0 : f(i) / m - loads_.damping_per_s * v;
  }
}

void ShellSystem::compute_jacobian(double t, const ode::Vector& y, ode::SparseMatrix& jac) const {
  // d(dx/dt)/dv = I, d(dv/dt)/dx = −M⁻¹ K, d(dv/dt)/dv = −c I; nothing moves a held component.
  const Eigen::Index n = position_size();
  if (before_force_) before_force_(t);
  const SparseMatrix k = stiffness_matrix(body_, y.head(n));
  auto held = [&](Eigen::Index i) { return loads_.fixed[static_cast<std::size_t>(i)] != 0; };
  std::vector<Eigen::Triplet<double>> t_list;
  t_list.reserve(static_cast<std::size_t>(k.nonZeros() + 2 * n));
  for (Eigen::Index i = 0; i < n; ++i)
    if (!held(i)) {
      t_list.emplace_back(i, n + i, 1.0);
      if (loads_.damping_per_s != 0.0) t_list.emplace_back(n + i, n + i, -loads_.damping_per_s);
    }
  for (Eigen::Index col = 0; col < k.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(k, col); it; ++it)
      if (!held(it.row()))
        t_list.emplace_back(n + it.row(), it.col(), -it.value() / body_.mass_kg[static_cast<std::size_t>(it.row() / 3)]);
  jac.resize(2 * n, 2 * n);
  jac.setFromTriplets(t_list.begin(), t_list.end());
}

double kinetic_energy(const ShellBody& body, const Vector& v) {
  double e = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) e += 0.5 * body.mass_kg[static_cast<std::size_t>(i / 3)] * v(i) * v(i);
  return e;
}

namespace {

/// The stiffness restricted to the free components (index map `free_index`, −1 for fixed ones).
SparseMatrix free_block(const SparseMatrix& k, const std::vector<Eigen::Index>& free_index, Eigen::Index free_count) {
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index col = 0; col < k.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(k, col); it; ++it) {
      const Eigen::Index r = free_index[static_cast<std::size_t>(it.row())], c = free_index[static_cast<std::size_t>(it.col())];
      if (r >= 0 && c >= 0) t.emplace_back(r, c, it.value());
    }
  SparseMatrix out(free_count, free_count);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace

StaticSolution solve_static(const ShellBody& body, const ShellLoads& loads, const Vector& x0, double tolerance_n,
                            int max_iterations) {
  const Eigen::Index n = x0.size();
  std::vector<Eigen::Index> free_index(static_cast<std::size_t>(n), -1);
  Eigen::Index free_count = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (loads.fixed.empty() || !loads.fixed[static_cast<std::size_t>(i)]) free_index[static_cast<std::size_t>(i)] = free_count++;
  StaticSolution s{x0, 0, 0.0};
  for (;; ++s.iterations) {
    Vector f = loads.external_force.size() ? loads.external_force : Vector::Zero(n);
    add_elastic_forces(body, s.x, f);
    Vector r(free_count);
    for (Eigen::Index i = 0; i < n; ++i)
      if (free_index[static_cast<std::size_t>(i)] >= 0) r(free_index[static_cast<std::size_t>(i)]) = f(i);
    const double previous = s.iterations > 0 ? s.residual_n : INFINITY;
    s.residual_n = r.cwiseAbs().maxCoeff();
    // Done at the tolerance, or where round-off stalls Newton's quadratic convergence.
    if (s.residual_n <= tolerance_n || s.residual_n > 0.5 * previous || s.iterations >= max_iterations) return s;
    Eigen::SimplicialLDLT<SparseMatrix> solver(free_block(stiffness_matrix(body, s.x), free_index, free_count));
    if (solver.info() != Eigen::Success) throw std::runtime_error("solve_static: the stiffness could not be factorised");
    const Vector dx = solver.solve(r);
    for (Eigen::Index i = 0; i < n; ++i)
      if (free_index[static_cast<std::size_t>(i)] >= 0) s.x(i) += dx(free_index[static_cast<std::size_t>(i)]);
  }
}

}  // namespace jellysim::shell
