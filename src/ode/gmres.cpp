#include "jellysim/ode/gmres.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace jellysim::ode {

namespace {

/// Givens rotation (c, s) that zeroes b in (a, b).
void givens(double a, double b, double& c, double& s) {
  const double r = std::hypot(a, b);
  if (r == 0.0) {
    c = 1.0;
    s = 0.0;
  } else {
    c = a / r;
    s = b / r;
  }
}

}  // namespace

namespace {

/// Arnoldi step k: w = A v_k orthogonalised against v_0 … v_k (modified Gram–Schmidt) into column k
/// of the Hessenberg matrix h, and v_{k+1} = w / h(k+1, k) when that is not zero.
void arnoldi_column(const LinearOperator& apply, std::vector<Eigen::VectorXd>& basis, Eigen::MatrixXd& h,
                    Eigen::VectorXd& w, int k) {
  apply(basis[static_cast<std::size_t>(k)], w);
  for (int i = 0; i <= k; ++i) {
    h(i, k) = w.dot(basis[static_cast<std::size_t>(i)]);
    w -= h(i, k) * basis[static_cast<std::size_t>(i)];
  }
  h(k + 1, k) = w.norm();
  if (h(k + 1, k) > 0.0) basis[static_cast<std::size_t>(k + 1)] = w / h(k + 1, k);
}

/// Column k of h made upper triangular: the previous Givens rotations applied to it, then a new one
/// that zeroes h(k+1, k), applied to the residual vector g as well (|g[k+1]| is the new residual).
void rotate_column(Eigen::MatrixXd& h, Eigen::VectorXd& cs, Eigen::VectorXd& sn, Eigen::VectorXd& g, int k) {
  for (int i = 0; i < k; ++i) {
    const double t = cs[i] * h(i, k) + sn[i] * h(i + 1, k);
    h(i + 1, k) = -sn[i] * h(i, k) + cs[i] * h(i + 1, k);
    h(i, k) = t;
  }
  givens(h(k, k), h(k + 1, k), cs[k], sn[k]);
  h(k, k) = cs[k] * h(k, k) + sn[k] * h(k + 1, k);
  h(k + 1, k) = 0.0;
  g[k + 1] = -sn[k] * g[k];
  g[k] = cs[k] * g[k];
}

/// The cycle's residual r = b − A x (r = b with x = 0 when `from_zero`).
void cycle_residual(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool from_zero,
                    Eigen::VectorXd& r, Eigen::VectorXd& w) {
  if (from_zero) {
    x.setZero(b.size());
    r = b;
  } else {
    apply(x, w);
    r = b - w;
  }
}

/// The GMRES cycles. `coefficients`, when given: x starts at zero, the first residual is b itself,
/// and a first cycle that converges returns its coefficients without a final residual check.
GmresReport run_gmres(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                      int max_iterations, int restart, Eigen::VectorXd* coefficients) {
  GmresReport report;
  const double b_norm = b.norm();
  if (coefficients) coefficients->resize(0);
  if (b_norm == 0.0) {
    x.setZero(b.size());
    report.converged = true;
    report.coefficients_valid = coefficients != nullptr;  // x = 0 = the empty combination
    return report;
  }
  const Eigen::Index n = b.size();
  const int m = std::max(1, std::min<int>(restart, static_cast<int>(n)));
  std::vector<Eigen::VectorXd> basis(static_cast<std::size_t>(m + 1), Eigen::VectorXd(n));
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(m + 1, m);
  Eigen::VectorXd cs(m), sn(m), g(m + 1), w(n), r(n);
  bool first_cycle = true;
  while (true) {
    cycle_residual(apply, b, x, coefficients && first_cycle, r, w);
    double beta = r.norm();
    report.relative_residual = beta / b_norm;
    if (report.relative_residual <= tolerance) {
      report.converged = true;
      return report;
    }
    if (report.iterations >= max_iterations) return report;
    if (!first_cycle) {
      report.restarted = true;
      if (coefficients) coefficients->resize(0);
    }
    basis[0] = r / beta;
    g.setZero();
    g[0] = beta;
    int k = 0;
    bool converged = false;
    for (; k < m && report.iterations < max_iterations; ++k) {
      arnoldi_column(apply, basis, h, w, k);
      ++report.iterations;
      rotate_column(h, cs, sn, g, k);
      if (std::abs(g[k + 1]) <= tolerance * b_norm || h(k, k) == 0.0) {
        converged = std::abs(g[k + 1]) <= tolerance * b_norm;
        ++k;
        break;
      }
    }
    // Back-substitute the k × k triangular system and update x.
    Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    for (int i = 0; i < k; ++i) x += y[i] * basis[static_cast<std::size_t>(i)];
    if (coefficients && first_cycle && converged) {
      // x = Σ y_i v_i: the caller combines its by-products with these weights.
      *coefficients = y;
      report.relative_residual = std::abs(g[k]) / b_norm;
      report.converged = true;
      report.coefficients_valid = true;
      return report;
    }
    first_cycle = false;
  }
}

}  // namespace

GmresReport gmres(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                  int max_iterations, int restart) {
  return run_gmres(apply, b, x, tolerance, max_iterations, restart, nullptr);
}

GmresReport gmres_from_zero(const LinearOperator& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                            Eigen::VectorXd& coefficients, double tolerance, int max_iterations, int restart) {
  return run_gmres(apply, b, x, tolerance, max_iterations, restart, &coefficients);
}

}  // namespace jellysim::ode
