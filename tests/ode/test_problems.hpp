#pragma once
// Small ODE systems with known solutions for the ode tests.
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "jellysim/ode/ode_system.hpp"

namespace jellysim::ode::testing {

inline SparseMatrix sparse_from(Eigen::Index n, const std::vector<Eigen::Triplet<double>>& entries) {
  SparseMatrix m(n, n);
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

/// Undamped spring x'' = -ω² x, y = [x; v].
class HarmonicOscillator final : public OdeSystem {
 public:
  explicit HarmonicOscillator(double omega) : omega_(omega) {}
  Eigen::Index dimension() const override { return 2; }
  Eigen::Index position_size() const override { return 1; }
  bool has_jacobian() const override { return true; }

  Vector exact(double t, const Vector& y0) const {
    const double c = std::cos(omega_ * t), s = std::sin(omega_ * t);
    return Vector{{y0[0] * c + y0[1] / omega_ * s, -y0[0] * omega_ * s + y0[1] * c}};
  }
  double energy(const Vector& y) const { return 0.5 * y[1] * y[1] + 0.5 * omega_ * omega_ * y[0] * y[0]; }

 protected:
  void compute_derivative(double, const Vector& y, Vector& dydt) const override {
    dydt = Vector{{y[1], -omega_ * omega_ * y[0]}};
  }
  void compute_jacobian(double, const Vector&, SparseMatrix& jac) const override {
    jac = sparse_from(2, {{0, 1, 1.0}, {1, 0, -omega_ * omega_}});
  }

 private:
  double omega_;
};

/// Damped spring x'' = -ω² x - 2γ x' (underdamped, γ < ω): a velocity-dependent force.
class DampedOscillator final : public OdeSystem {
 public:
  DampedOscillator(double omega, double gamma) : omega_(omega), gamma_(gamma) {}
  Eigen::Index dimension() const override { return 2; }
  Eigen::Index position_size() const override { return 1; }

  Vector exact(double t, const Vector& y0) const {
    const double wd = std::sqrt(omega_ * omega_ - gamma_ * gamma_);
    const double a = y0[0], b = (y0[1] + gamma_ * y0[0]) / wd;
    const double decay = std::exp(-gamma_ * t), c = std::cos(wd * t), s = std::sin(wd * t);
    const double x = decay * (a * c + b * s);
    const double v = -gamma_ * x + decay * wd * (-a * s + b * c);
    return Vector{{x, v}};
  }

 protected:
  void compute_derivative(double, const Vector& y, Vector& dydt) const override {
    dydt = Vector{{y[1], -omega_ * omega_ * y[0] - 2.0 * gamma_ * y[1]}};
  }

 private:
  double omega_, gamma_;
};

/// Non-autonomous, nonlinear scalar y' = -2 t y², y(0) = 1, with y(t) = 1 / (1 + t²).
class RationalDecay final : public OdeSystem {
 public:
  Eigen::Index dimension() const override { return 1; }
  bool has_jacobian() const override { return true; }
  static double exact(double t) { return 1.0 / (1.0 + t * t); }

 protected:
  void compute_derivative(double t, const Vector& y, Vector& dydt) const override {
    dydt = Vector{{-2.0 * t * y[0] * y[0]}};
  }
  void compute_jacobian(double t, const Vector& y, SparseMatrix& jac) const override {
    jac = sparse_from(1, {{0, 0, -4.0 * t * y[0]}});
  }
};

/// Kepler two-body problem r'' = -r / |r|³ (GM = 1, semi-major axis 1, period 2π), y = [r; v],
/// started at perihelion; after one period it is back at the start.
class Kepler final : public OdeSystem {
 public:
  explicit Kepler(double eccentricity) : e_(eccentricity) {}
  Eigen::Index dimension() const override { return 4; }
  Eigen::Index position_size() const override { return 2; }
  bool has_jacobian() const override { return true; }
  static constexpr double period() { return 2.0 * std::numbers::pi; }
  Vector initial_state() const { return Vector{{1.0 - e_, 0.0, 0.0, std::sqrt((1.0 + e_) / (1.0 - e_))}}; }

 protected:
  void compute_derivative(double, const Vector& y, Vector& dydt) const override {
    const double r3 = std::pow(y.head(2).norm(), 3);
    dydt.resize(4);
    dydt << y[2], y[3], -y[0] / r3, -y[1] / r3;
  }
  void compute_jacobian(double, const Vector& y, SparseMatrix& jac) const override {
    // d(-r/|r|³)/dr = -I/|r|³ + 3 r rᵀ/|r|⁵
    const double r2 = y.head(2).squaredNorm(), r3 = std::pow(r2, 1.5), r5 = r3 * r2;
    std::vector<Eigen::Triplet<double>> entries{{0, 2, 1.0}, {1, 3, 1.0}};
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) entries.emplace_back(2 + i, j, (i == j ? -1.0 / r3 : 0.0) + 3.0 * y[i] * y[j] / r5);
    }
    jac = sparse_from(4, entries);
  }

 private:
  double e_;
};

/// Scalar linear growth or decay y' = λ y.
class ScalarLinear final : public OdeSystem {
 public:
  explicit ScalarLinear(double lambda) : lambda_(lambda) {}
  Eigen::Index dimension() const override { return 1; }
  bool has_jacobian() const override { return true; }

 protected:
  void compute_derivative(double, const Vector& y, Vector& dydt) const override { dydt = lambda_ * y; }
  void compute_jacobian(double, const Vector&, SparseMatrix& jac) const override {
    jac = sparse_from(1, {{0, 0, lambda_}});
  }

 private:
  double lambda_;
};

/// y' = -y until t_bad, NaN afterwards: every step reaching past t_bad fails.
class BreaksDownAt final : public OdeSystem {
 public:
  explicit BreaksDownAt(double t_bad) : t_bad_(t_bad) {}
  Eigen::Index dimension() const override { return 1; }

 protected:
  void compute_derivative(double t, const Vector& y, Vector& dydt) const override {
    dydt = t <= t_bad_ ? Vector(-y) : Vector::Constant(1, std::numeric_limits<double>::quiet_NaN());
  }

 private:
  double t_bad_;
};

}  // namespace jellysim::ode::testing
