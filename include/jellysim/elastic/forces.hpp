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

// ---- IB2d's structural laws (github.com/nickabattista/IB2d; see ib2d_structure.hpp). Each is
// written here as the negative gradient of its energy, so forces of the position-dependent laws
// sum to zero. Points are l, m (middle), r for the beams; jacobian[a][b] = ∂F_a/∂x_b with
// a, b ∈ {l=0, m=1, r=2}.
struct ThreePointForce {
  Vec2 on[3];          ///< forces on l, m, r
  Mat2 jacobian[3][3]; ///< ∂F_a/∂x_b
};

// ---- Torsional beam (IB2d ".beam"): c = (x_r − x_m) × (x_m − x_l) with a × b = a.x b.y − a.y b.x,
// E = ½ k (c − C)², F = −∇E. With e = k (c − C): F_l = e perp(x_r − x_m), F_r = e perp(x_m − x_l),
// F_m = −e perp(x_r − x_l) (perp = rotation by +90°).
// IB2d's own code applies the end-point forces with the opposite sign, so its three forces do not
// sum to zero (a net force 2e (Y_r − Y_l, −(X_r − X_l))); ours is the energy gradient.
/// c = (x_r − x_m) × (x_m − x_l), m² (twice the signed area of the triangle l, r, m).
double beam_cross_product(Vec2 xl, Vec2 xm, Vec2 xr);
ThreePointForce torsional_beam_force_and_jacobian(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, double curvature);
double torsional_beam_energy(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, double curvature);

// ---- Non-invariant beam (IB2d ".nonInv_beam"): D = x_l − 2 x_m + x_r − C, E = ½ k |D|².
// F_l = F_r = −k D, F_m = 2 k D; ∂F_a/∂x_b = −k w_a w_b I with w = (1, −2, 1), a constant.
// Not invariant under rotation: C is a fixed vector in the lab frame.
ThreePointForce non_invariant_beam_force_and_jacobian(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, Vec2 curvature);
double non_invariant_beam_energy(Vec2 xl, Vec2 xm, Vec2 xr, double stiffness, Vec2 curvature);

// ---- Power-law spring (IB2d ".spring" with degree α ≥ 1): d = x_j − x_i, l = |d|, e = l − l_r,
// E = ½ k |e|^(α+1), tension T = dE/dl = ½ (α+1) k sign(e) |e|^α (α = 1: Hooke's law k e), and
// F_i = T d̂ (toward j when stretched, as for the linear spring), F_j = −F_i. With
// T' = dT/dl = ½ (α+1) α k |e|^(α−1): ∂F_i/∂x_i = −[T' d̂d̂ᵀ + (T/l)(I − d̂d̂ᵀ)].
// (IB2d raises (l − l_r) itself to α, which is not real for a compressed spring and non-integer α;
// sign(e)|e|^α makes a compressed spring push.) α < 1 has an infinite T' at e = 0 and is not
// supported. A zero-length spring exerts no force; its Jacobian is then the isotropic −T' I
// (−k I for α = 1, as the linear spring's).
/// Tension T = ½ (α+1) k sign(e) |e|^α of a spring stretched by e, N.
double power_spring_tension(double stretch, double stiffness, double degree);
Vec2 power_spring_force(Vec2 xi, Vec2 xj, double stiffness, double rest_length, double degree);
/// Same layout as the linear spring's: on_i and ∂F_i/∂x_i.
LinearSpringForce power_spring_force_and_jacobian(Vec2 xi, Vec2 xj, double stiffness, double rest_length,
                                                  double degree);
double power_spring_energy(Vec2 xi, Vec2 xj, double stiffness, double rest_length, double degree);

// ---- Dashpot along a spring (for IB2d ".d_spring"): F_i = b ((v_j − v_i)·d̂) d̂, F_j = −F_i, with
// d = x_j − x_i. It damps the relative velocity along the spring only, so it is Galilean
// invariant and exerts no net force. IB2d's damped spring instead damps the master point's own
// velocity, adding −b·V_master to the master (and, in the version we read, +b·V_master to the
// slave): that depends on the frame. Velocity-dependent: integrators treat it explicitly;
// ∂F_i/∂v_i = −b d̂d̂ᵀ (∂F_i/∂v_j = −∂F_i/∂v_i). With w = v_j − v_i and P = I − d̂d̂ᵀ,
// ∂F_i/∂x_i = −(b/l) [(d̂·w) P + d̂ (P w)ᵀ] for implicit uses (ElasticSystem). Zero length: no force.
struct DashpotForce {
  Vec2 on_i;          ///< force on point i; the force on j is -on_i
  Mat2 d_on_i_d_vi;   ///< ∂F_i/∂v_i; ∂F_i/∂v_j = −d_on_i_d_vi, ∂F_j/∂v_j = d_on_i_d_vi
  Mat2 d_on_i_d_xi;   ///< ∂F_i/∂x_i; same pattern over x_i, x_j
};
Vec2 dashpot_force(Vec2 xi, Vec2 xj, Vec2 vi, Vec2 vj, double coefficient);
DashpotForce dashpot_force_and_jacobian(Vec2 xi, Vec2 xj, Vec2 vi, Vec2 vj, double coefficient);

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
