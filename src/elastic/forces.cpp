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
