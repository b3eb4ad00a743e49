#pragma once
// Pure force laws of the spring-mass model (thesis §2.1-2.3) with their energies and analytic
// Jacobians. Every function depends only on its arguments.
#include "jellysim/math/vec2.hpp"

namespace jellysim::elastic {

// ---- Linear spring, Hooke's law (eq. 2.5): F_i = k (l_c - l_r) x̂_ij with x_ij = x_j - x_i, F_j = -F_i.
// (Eq. 2.5 prints k (l_r - l_c) x̂_ij, which pushes a stretched spring apart; the sign here is the
// one the thesis text describes and that F = -∇E gives.) A zero-length spring exerts no force.
struct LinearSpringForce {
  Vec2 on_i;                 ///< force on point i; the force on j is -on_i
  Mat2 d_on_i_d_xi;          ///< ∂F_i/∂x_i; then ∂F_i/∂x_j = -d_on_i_d_xi, ∂F_j/∂x_j = d_on_i_d_xi
};
Vec2 linear_spring_force(Vec2 xi, Vec2 xj, double stiffness, double rest_length);
LinearSpringForce linear_spring_force_and_jacobian(Vec2 xi, Vec2 xj, double stiffness, double rest_length);
/// E = ½ k (l_c - l_r)².
double linear_spring_energy(Vec2 xi, Vec2 xj, double stiffness, double rest_length);

// ---- Angular spring in 2D (eqs. 2.6-2.14), derived as the negative gradient of
// E = ½ k_θ (θ - θ_r)², where θ = atan2(x_ij × x_jk, x_ij · x_jk) is the signed turning angle from
// segment ij to segment jk, θ ∈ (-π, π]. The difference θ - θ_r is wrapped to (-π, π] so that
// angles near ±π do not flip. Forces sum to zero and exert no net torque by construction.
double turning_angle(Vec2 xi, Vec2 xj, Vec2 xk);
/// Wraps an angle difference into (-π, π].
double wrap_angle(double a);
struct AngularSpringForce {
  Vec2 on_i, on_j, on_k;
  /// d_on[a][b] = ∂F_a/∂x_b for a, b ∈ {i=0, j=1, k=2}.
  Mat2 jacobian[3][3];
};
AngularSpringForce angular_spring_force(Vec2 xi, Vec2 xj, Vec2 xk, double stiffness, double rest_angle);
AngularSpringForce angular_spring_force_and_jacobian(Vec2 xi, Vec2 xj, Vec2 xk, double stiffness,
                                                     double rest_angle);
double angular_spring_energy(Vec2 xi, Vec2 xj, Vec2 xk, double stiffness, double rest_angle);

// ---- Drag (eq. 2.17): F = -k_d (v - v_fluid); ∂F/∂v = -k_d I.
constexpr Vec2 drag_force(Vec2 velocity, Vec2 fluid_velocity, double drag_coefficient) {
  return -drag_coefficient * (velocity - fluid_velocity);
}

// ---- Gravity (eq. 2.18): F = m g; potential energy -m g·x.
constexpr Vec2 gravity_force(double mass, Vec2 gravity) { return mass * gravity; }

// ---- Material: spring constant from an elastic modulus (eq. 7.1, corrected).
// The thesis prints λ = κ_l/(l_r A), which is not Hooke's law for a bar; a bar of cross-section A
// and rest length l_r has κ_l = λ A / l_r (see docs/physics.md).
double linear_stiffness_from_modulus(double modulus_pa, double cross_section_area, double rest_length);

}  // namespace jellysim::elastic
