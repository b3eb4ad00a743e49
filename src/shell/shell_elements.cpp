#include "shell_elements.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

namespace jellysim::shell::detail {

namespace {

/// The face's 3×2 deformation gradient F = [x1 − x0, x2 − x0] D_m⁻¹.
Eigen::Matrix<double, 3, 2> deformation_gradient(const Eigen::Matrix2d& rest_inverse, const Points<3>& x) {
  Eigen::Matrix<double, 3, 2> ds;
  ds.col(0) = x[1] - x[0];
  ds.col(1) = x[2] - x[0];
  return ds * rest_inverse;
}

/// θ − θ̄ wrapped into (−π, π].
double angle_difference(double theta, double rest) {
  double d = theta - rest;
  while (d > std::numbers::pi) d -= 2.0 * std::numbers::pi;
  while (d <= -std::numbers::pi) d += 2.0 * std::numbers::pi;
  return d;
}

}  // namespace

double membrane(const MembraneElement& e, const Points<3>& x, Points<3>& f) {
  // Compressible neo-Hookean membrane: S = μ(I − C⁻¹) + λ ln J C⁻¹ (second Piola–Kirchhoff, N/m),
  // P = F S, forces on x1, x2 the columns of −A₀ P D_m⁻ᵀ (the constant-strain triangle).
  const Eigen::Matrix<double, 3, 2> F = deformation_gradient(e.rest_inverse, x);
  const Eigen::Matrix2d C = F.transpose() * F;
  const double det = C.determinant();
  const double log_j = 0.5 * std::log(det);
  const Eigen::Matrix2d c_inv = C.inverse();
  const Eigen::Matrix2d S = e.mu_n_per_m * (Eigen::Matrix2d::Identity() - c_inv) + e.lambda_n_per_m * log_j * c_inv;
  const Eigen::Matrix<double, 3, 2> H = -e.rest_area_m2 * (F * S) * e.rest_inverse.transpose();
  f[1] += H.col(0);
  f[2] += H.col(1);
  f[0] -= H.col(0) + H.col(1);
  return e.rest_area_m2 * (0.5 * e.mu_n_per_m * (C.trace() - 2.0) - e.mu_n_per_m * log_j +
                           0.5 * e.lambda_n_per_m * log_j * log_j);
}

double hinge_angle_gradient(const Points<4>& x, Points<4>& g) {
  // Gradient of θ (Bridson, Marino & Fedkiw 2003; Tamstorf & Grinspun 2013): the opposite vertices
  // turn their faces about the edge, ∂θ/∂x₂ = −|e| n_A / |n_A|², ∂θ/∂x₃ = −|e| n_B / |n_B|² (n the
  // unnormalised face normals); the edge's vertices by the lever rule with the feet of the
  // opposite vertices at α = (x_k − x₀)·e / |e|², so that translations and rotations do not bend.
  const Vec3 edge = x[1] - x[0];
  const Vec3 na = edge.cross(x[2] - x[0]);
  const Vec3 nb = (x[0] - x[1]).cross(x[3] - x[1]);
  const double len = edge.norm();
  g[2] = -len / na.squaredNorm() * na;
  g[3] = -len / nb.squaredNorm() * nb;
  const double a2 = (x[2] - x[0]).dot(edge) / (len * len), a3 = (x[3] - x[0]).dot(edge) / (len * len);
  g[0] = -(1.0 - a2) * g[2] - (1.0 - a3) * g[3];
  g[1] = -a2 * g[2] - a3 * g[3];
  return dihedral_angle(x[0], x[1], x[2], x[3]);
}

double hinge(const HingeElement& e, const Points<4>& x, Points<4>& f) {
  Points<4> g;
  const double d = angle_difference(hinge_angle_gradient(x, g), e.rest_angle_rad);
  const double scale = -2.0 * e.stiffness_n_m * d;
  for (std::size_t i = 0; i < 4; ++i) f[i] += scale * g[i];
  return e.stiffness_n_m * d * d;
}

double bending_triangle(const BendingTriangle& e, const Points<6>& x, Points<6>& f) {
  // W = ½ Δθᵀ G Δθ over the face's hinges; hinge i runs along the edge opposite x_i, from x_{i+1}
  // to x_{i+2}, with x_i on this side and x_{3+i} across. A clamped edge's hinge is to the face's
  // mirror image: twice the angle to the (fixed) mirrored rest vertex.
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  std::array<Points<4>, 3> grads;
  std::array<double, 3> factor{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (e.edge[i] == EdgeKind::free) continue;
    const bool clamped = e.edge[i] == EdgeKind::clamped;
    factor[i] = clamped ? 2.0 : 1.0;
    const Points<4> hinge_points{x[(i + 1) % 3], x[(i + 2) % 3], x[i], clamped ? e.mirror[i] : x[3 + i]};
    d(static_cast<Eigen::Index>(i)) =
        angle_difference(factor[i] * hinge_angle_gradient(hinge_points, grads[i]), e.rest_angle_rad[i]);
  }
  const Eigen::Vector3d moment = e.G * d;  // ∂W/∂θ_i
  for (std::size_t i = 0; i < 3; ++i) {
    if (e.edge[i] == EdgeKind::free) continue;
    const double m = factor[i] * moment(static_cast<Eigen::Index>(i));
    f[(i + 1) % 3] -= m * grads[i][0];
    f[(i + 2) % 3] -= m * grads[i][1];
    f[i] -= m * grads[i][2];
    if (e.edge[i] == EdgeKind::hinge) f[3 + i] -= m * grads[i][3];
  }
  return 0.5 * d.dot(moment);
}

double fibre(const FibreElement& e, const Points<3>& x, Points<3>& f) {
  const Vec3 g = e.weights[0] * x[0] + e.weights[1] * x[1] + e.weights[2] * x[2];
  const double stretch = g.norm();
  if (!(stretch > 0)) return 0.5 * e.stiffness_n_per_m * e.rest_area_m2 * e.rest_stretch * e.rest_stretch;
  const double excess = stretch - e.rest_stretch;
  const Vec3 pull = (-e.stiffness_n_per_m * e.rest_area_m2 * excess / stretch) * g;
  for (std::size_t i = 0; i < 3; ++i) f[i] += e.weights[i] * pull;
  return 0.5 * e.stiffness_n_per_m * e.rest_area_m2 * excess * excess;
}

double rod_segment(const RodSegment& e, const Points<2>& x, Points<2>& f) {
  const Vec3 d = x[1] - x[0];
  const double l = d.norm();
  const double k = e.axial_stiffness_n / e.rest_length_m;
  const Vec3 pull = (k * (l - e.rest_length_m) / l) * d;
  f[0] += pull;
  f[1] -= pull;
  return 0.5 * k * (l - e.rest_length_m) * (l - e.rest_length_m);
}

double rod_joint(const RodJoint& e, const Points<4>& x, Points<4>& f) {
  // W = k (1 − t₁·t₂); ∂(t₁·t₂)/∂x_c = (t₁ − (t₁·t₂) t₂) / |e₂|, ∂/∂(point a) = −(t₂ − (t₁·t₂) t₁) / |e₁|.
  const Vec3 a = e.a_weights[0] * x[0] + e.a_weights[1] * x[1];
  const Vec3 e1 = x[2] - a, e2 = x[3] - x[2];
  const double l1 = e1.norm(), l2 = e2.norm();
  const Vec3 t1 = e1 / l1, t2 = e2 / l2;
  const double c = t1.dot(t2);
  const Vec3 dc = (t1 - c * t2) / l2;
  const Vec3 da = -(t2 - c * t1) / l1;
  const double k = e.stiffness_n_m;
  f[3] += k * dc;
  f[2] += k * (-dc - da);
  f[0] += k * e.a_weights[0] * da;
  f[1] += k * e.a_weights[1] * da;
  return k * (1.0 - c);
}

}  // namespace jellysim::shell::detail
