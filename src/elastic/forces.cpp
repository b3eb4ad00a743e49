#include "jellysim/elastic/forces.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace jellysim::elastic {

// ---- Linear spring (eq. 2.5) ----

Vec2 linear_spring_force(Vec2 xi, Vec2 xj, double stiffness, double rest_length) {
  const Vec2 d = xj - xi;
  const double l = norm(d);
  if (l == 0.0) return {};
  return stiffness * (l - rest_length) / l * d;
}

// F_i = k (l - l_r) x̂ = k (d - l_r d/l) with d = x_j - x_i, so
// ∂F_i/∂d = k [(1 - l_r/l)(I - x̂x̂ᵀ) + x̂x̂ᵀ] and ∂F_i/∂x_i = -∂F_i/∂d.
LinearSpringForce linear_spring_force_and_jacobian(Vec2 xi, Vec2 xj, double stiffness, double rest_length) {
  const Vec2 d = xj - xi;
  const double l = norm(d);
  // At zero length the direction is undefined: no force, and the isotropic stiffness -kI (exact
  // when l_r = 0) as the Jacobian.
  if (l == 0.0) return {{}, -stiffness * Mat2::identity()};
  const Vec2 dir = d / l;
  const Mat2 along = Mat2::outer(dir, dir);
  const Mat2 across = Mat2::identity() - along;
  return {stiffness * (l - rest_length) * dir, -stiffness * ((1.0 - rest_length / l) * across + along)};
}

double linear_spring_energy(Vec2 xi, Vec2 xj, double stiffness, double rest_length) {
  const double stretch = norm(xj - xi) - rest_length;
  return 0.5 * stiffness * stretch * stretch;
}

// ---- Angular spring (eqs. 2.6-2.14, derived as F = -∇E with E = ½ κ_θ wrap(θ - θ_r)²) ----

double turning_angle(Vec2 xi, Vec2 xj, Vec2 xk) {
  const Vec2 a = xj - xi;
  const Vec2 b = xk - xj;
  return std::atan2(cross(a, b), dot(a, b));
}

double wrap_angle(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  return a - two_pi * std::ceil((a - std::numbers::pi) / two_pi);
}

namespace {

/// ∂ atan2(s.y, s.x)/∂s = perp(s)/|s|²: the gradient of a segment's polar angle.
Vec2 polar_angle_gradient(Vec2 s) { return perp(s) / norm_squared(s); }

/// ∂/∂s [perp(s)/|s|²] = R/|s|² - 2 perp(s) sᵀ/|s|⁴ (R = rotation by +90°); symmetric.
Mat2 polar_angle_hessian(Vec2 s) {
  const double s2 = norm_squared(s);
  constexpr Mat2 rotation{0.0, -1.0, 1.0, 0.0};
  return (1.0 / s2) * rotation - (2.0 / (s2 * s2)) * Mat2::outer(perp(s), s);
}

/// θ = φ(b) - φ(a) with a = x_j - x_i, b = x_k - x_j and φ the polar angle, so
/// ∇_i θ = ∇φ(a), ∇_k θ = ∇φ(b), ∇_j θ = -(∇_i θ + ∇_k θ).
struct AngleGradient {
  Vec2 a, b;          ///< the two segments
  Vec2 g[3];          ///< ∇_i θ, ∇_j θ, ∇_k θ
  double deviation;   ///< wrap(θ - θ_r)
};

bool degenerate(Vec2 a, Vec2 b) { return norm_squared(a) == 0.0 || norm_squared(b) == 0.0; }

AngleGradient angle_gradient(Vec2 xi, Vec2 xj, Vec2 xk, double rest_angle) {
  AngleGradient ag;
  ag.a = xj - xi;
  ag.b = xk - xj;
  ag.g[0] = polar_angle_gradient(ag.a);
  ag.g[2] = polar_angle_gradient(ag.b);
  ag.g[1] = -(ag.g[0] + ag.g[2]);
  ag.deviation = wrap_angle(std::atan2(cross(ag.a, ag.b), dot(ag.a, ag.b)) - rest_angle);
  return ag;
}

AngularSpringForce forces_from(const AngleGradient& ag, double stiffness) {
  const double scale = -stiffness * ag.deviation;
  AngularSpringForce f;
  f.on_i = scale * ag.g[0];
  f.on_j = scale * ag.g[1];
  f.on_k = scale * ag.g[2];
  return f;
}

}  // namespace

AngularSpringForce angular_spring_force(Vec2 xi, Vec2 xj, Vec2 xk, double stiffness, double rest_angle) {
  if (degenerate(xj - xi, xk - xj)) return {};
  return forces_from(angle_gradient(xi, xj, xk, rest_angle), stiffness);
}

// ∂F_p/∂x_q = -κ_θ (∇_p θ ∇_q θᵀ + wrap(θ - θ_r) ∂²θ/∂x_p∂x_q), where with H_a, H_b the polar-angle
// Hessians of a and b: ∂²θ/∂x∂x = [[-H_a, H_a, 0], [H_a, -H_a + H_b, -H_b], [0, -H_b, H_b]].
AngularSpringForce angular_spring_force_and_jacobian(Vec2 xi, Vec2 xj, Vec2 xk, double stiffness,
                                                     double rest_angle) {
  if (degenerate(xj - xi, xk - xj)) return {};
  const AngleGradient ag = angle_gradient(xi, xj, xk, rest_angle);
  AngularSpringForce f = forces_from(ag, stiffness);
  const Mat2 ha = polar_angle_hessian(ag.a);
  const Mat2 hb = polar_angle_hessian(ag.b);
  const Mat2 hessian[3][3] = {{-ha, ha, Mat2{}}, {ha, hb - ha, -hb}, {Mat2{}, -hb, hb}};
  for (int p = 0; p < 3; ++p) {
    for (int q = 0; q < 3; ++q) {
      f.jacobian[p][q] = -stiffness * (Mat2::outer(ag.g[p], ag.g[q]) + ag.deviation * hessian[p][q]);
    }
  }
  return f;
}

double angular_spring_energy(Vec2 xi, Vec2 xj, Vec2 xk, double stiffness, double rest_angle) {
  const double deviation = wrap_angle(turning_angle(xi, xj, xk) - rest_angle);
  return 0.5 * stiffness * deviation * deviation;
}

// ---- IB2d's torsional beam: E = ½ k (c − C)², c = (x_r − x_m) × (x_m − x_l) ----

double beam_cross_product(Vec2 xl, Vec2 xm, Vec2 xr) { return cross(xr - xm, xm - xl); }

namespace {

/// ∇c for c = (x_r − x_m) × (x_m − x_l): ∇_l c = −perp(x_r − x_m), ∇_r c = −perp(x_m − x_l),
/// ∇_m c = perp(x_r − x_l) (they sum to zero).
struct CrossGradient {
  Vec2 g[3];
};

CrossGradient cross_product_gradient(Vec2 xl, Vec2 xm, Vec2 xr) {
  return {{-perp(xr - xm), perp(xr - xl), -perp(xm - xl)}};
}

/// ∂²c/∂x_a∂x_b: c = x_l × x_r + x_r × x_m + x_m × x_l is bilinear, and ∂²(u × w)/∂u∂w = −R with
/// R the rotation by +90°, so the diagonal blocks vanish and the others are ±R.
Mat2 cross_product_hessian(int a, int b) {
  constexpr Mat2 rotation{0.0, -1.0, 1.0, 0.0};
  constexpr double sign[3][3] = {{0.0, 1.0, -1.0}, {-1.0, 0.0, 1.0}, {1.0, -1.0, 0.0}};
  return sign[a][b] * rotation;
}

}  // namespace

// F_a = −k (c − C) ∇_a c;  ∂F_a/∂x_b = −k (∇_a c ∇_b cᵀ + (c − C) ∂²c/∂x_a∂x_b).
ThreePointForce torsional_beam_force_and_jacobian(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, double curvature) {
  const CrossGradient grad = cross_product_gradient(xl, xm, xr);
  const double deviation = beam_cross_product(xl, xm, xr) - curvature;
  ThreePointForce f;
  for (int a = 0; a < 3; ++a) {
    f.on[a] = -stiffness * deviation * grad.g[a];
    for (int b = 0; b < 3; ++b) {
      f.jacobian[a][b] =
          -stiffness * (Mat2::outer(grad.g[a], grad.g[b]) + deviation * cross_product_hessian(a, b));
    }
  }
  return f;
}

double torsional_beam_energy(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, double curvature) {
  const double deviation = beam_cross_product(xl, xm, xr) - curvature;
  return 0.5 * stiffness * deviation * deviation;
}

// ---- IB2d's non-invariant beam: E = ½ k |x_l − 2 x_m + x_r − C|² ----

namespace {

constexpr double second_difference_weight[3] = {1.0, -2.0, 1.0};

/// D = x_l − 2 x_m + x_r − C, m.
Vec2 second_difference_deviation(Vec2 xl, Vec2 xm, Vec2 xr, Vec2 curvature) {
  return xl - 2.0 * xm + xr - curvature;
}

}  // namespace

// F_a = −k w_a D;  ∂F_a/∂x_b = −k w_a w_b I.
ThreePointForce non_invariant_beam_force_and_jacobian(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, Vec2 curvature) {
  const Vec2 deviation = second_difference_deviation(xl, xm, xr, curvature);
  const double* w = second_difference_weight;
  ThreePointForce f;
  for (int a = 0; a < 3; ++a) {
    f.on[a] = -stiffness * w[a] * deviation;
    for (int b = 0; b < 3; ++b) f.jacobian[a][b] = -stiffness * w[a] * w[b] * Mat2::identity();
  }
  return f;
}

double non_invariant_beam_energy(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, Vec2 curvature) {
  return 0.5 * stiffness * norm_squared(second_difference_deviation(xl, xm, xr, curvature));
}

// ---- IB2d's power-law spring: E = ½ k |l − l_r|^(α+1) ----

double power_spring_tension(double stretch, double stiffness, double degree) {
  const double magnitude = 0.5 * (degree + 1.0) * stiffness * std::pow(std::abs(stretch), degree);
  return stretch < 0.0 ? -magnitude : magnitude;
}

namespace {

/// T' = dT/dl = ½ (α+1) α k |e|^(α−1), N/m (k at α = 1, also at e = 0).
double power_spring_tension_slope(double stretch, double stiffness, double degree) {
  return 0.5 * (degree + 1.0) * degree * stiffness * std::pow(std::abs(stretch), degree - 1.0);
}

}  // namespace

Vec2 power_spring_force(Vec2 xi, Vec2 xj, double stiffness, double rest_length, double degree) {
  const Vec2 d = xj - xi;
  const double l = norm(d);
  if (l == 0.0) return {};
  return power_spring_tension(l - rest_length, stiffness, degree) / l * d;
}

// F_i = T(l) d̂ with d = x_j − x_i: ∂F_i/∂d = T' d̂d̂ᵀ + (T/l)(I − d̂d̂ᵀ), ∂F_i/∂x_i = −∂F_i/∂d.
LinearSpringForce power_spring_force_and_jacobian(Vec2 xi, Vec2 xj, double stiffness, double rest_length,
                                                  double degree) {
  const Vec2 d = xj - xi;
  const double l = norm(d);
  const double stretch = l - rest_length;
  const double slope = power_spring_tension_slope(stretch, stiffness, degree);
  if (l == 0.0) return {{}, -slope * Mat2::identity()};
  const double tension = power_spring_tension(stretch, stiffness, degree);
  const Vec2 dir = d / l;
  const Mat2 along = Mat2::outer(dir, dir);
  const Mat2 across = Mat2::identity() - along;
  return {tension * dir, -(slope * along + (tension / l) * across)};
}

double power_spring_energy(Vec2 xi, Vec2 xj, double stiffness, double rest_length, double degree) {
  const double stretch = std::abs(norm(xj - xi) - rest_length);
  return 0.5 * stiffness * std::pow(stretch, degree + 1.0);
}

// ---- Dashpot along a spring: F_i = b ((v_j − v_i)·d̂) d̂ ----

Vec2 dashpot_force(Vec2 xi, Vec2 xj, Vec2 vi, Vec2 vj, double coefficient) {
  const Vec2 d = xj - xi;
  const double l2 = norm_squared(d);
  if (l2 == 0.0) return {};
  return coefficient * dot(vj - vi, d) / l2 * d;
}

// With w = v_j − v_i, P = I − d̂d̂ᵀ: ∂F_i/∂v_i = −b d̂d̂ᵀ and
// ∂[(d̂·w) d̂]/∂d = [(d̂·w) P + d̂ (P w)ᵀ] / l, so ∂F_i/∂x_i = −(b/l) [(d̂·w) P + d̂ (P w)ᵀ].
DashpotForce dashpot_force_and_jacobian(Vec2 xi, Vec2 xj, Vec2 vi, Vec2 vj, double coefficient) {
  const Vec2 d = xj - xi;
  const double l = norm(d);
  if (l == 0.0) return {};
  const Vec2 dir = d / l;
  const Vec2 w = vj - vi;
  const double closing = dot(dir, w);
  const Mat2 along = Mat2::outer(dir, dir);
  const Mat2 across = Mat2::identity() - along;
  DashpotForce f;
  f.on_i = coefficient * closing * dir;
  f.d_on_i_d_vi = -coefficient * along;
  f.d_on_i_d_xi = -(coefficient / l) * (closing * across + Mat2::outer(dir, across * w));
  return f;
}

// ---- Material (eq. 7.1, corrected to Hooke's law for a bar: κ_l = λ A / l_r) ----

double linear_stiffness_from_modulus(double modulus_pa, double cross_section_area, double rest_length) {
  const auto require_positive = [](double value, const char* name) {
    if (!(value > 0.0 && std::isfinite(value))) {
      throw std::invalid_argument(std::string(name) + " = " + std::to_string(value) +
                                  " must be positive and finite");
    }
  };
  require_positive(modulus_pa, "elastic modulus");
  require_positive(cross_section_area, "cross-section area");
  require_positive(rest_length, "rest length");
  return modulus_pa * cross_section_area / rest_length;
}

}  // namespace jellysim::elastic
