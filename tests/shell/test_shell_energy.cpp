// The shell's elements: forces are the energy's gradient, rigid motions are free, the membrane passes
// the patch test, the stiffness matrix is the forces' derivative (docs/three-d.md, "Part 3").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "jellysim/shell/shell_body.hpp"
#include "jellysim/shell/triangle_mesh.hpp"

namespace js = jellysim::shell;

namespace {

/// A disc with every vertex moved by up to `amplitude` (m) in every direction, deterministic.
js::Vector jiggled(const js::Vector& x, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  js::Vector y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += amplitude * u(rng);
  return y;
}

/// Largest |f + ∂W/∂x| over the components, central differences of the energy, relative to max |f|.
double gradient_mismatch(const js::ShellBody& body, const js::Vector& x) {
  js::Vector f = js::Vector::Zero(x.size());
  js::add_elastic_forces(body, x, f);
  double worst = 0.0;
  const double h = 1e-7;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    js::Vector p = x, m = x;
    p(i) += h;
    m(i) -= h;
    const double grad = (js::elastic_energy(body, p) - js::elastic_energy(body, m)) / (2.0 * h);
    worst = std::max(worst, std::abs(f(i) + grad));
  }
  return worst / f.cwiseAbs().maxCoeff();
}

}  // namespace

TEST(ShellEnergy, ForcesAreTheEnergysGradient) {
  const js::RevolvedMesh disc = js::disc_mesh(0.01, 0.004);
  js::ShellMaterial m;
  m.thickness_m = 2e-3;
  const js::ShellBody body = js::make_shell_body(disc.mesh, m);
  const js::Vector x = jiggled(js::stack(disc.mesh.vertices), 5e-4, 7);
  const double mismatch = gradient_mismatch(body, x);
  std::printf("membrane + hinges: max |f + dW/dx| / max |f| = %.2e\n", mismatch);
  EXPECT_LT(mismatch, 1e-6);
}

TEST(ShellEnergy, HingeForcesAreTheBendingEnergysGradient) {
  const js::RevolvedMesh disc = js::disc_mesh(0.01, 0.004);
  for (auto model : {js::BendingModel::hinge, js::BendingModel::triangle}) {
  js::ShellBody body = js::make_shell_body(disc.mesh, js::ShellMaterial{}, model);
  body.membranes.clear();
  const js::Vector x = jiggled(js::stack(disc.mesh.vertices), 5e-4, 11);
  const double mismatch = gradient_mismatch(body, x);
  std::printf("hinges alone: max |f + dW/dx| / max |f| = %.2e\n", mismatch);
  EXPECT_LT(mismatch, 1e-6);
  }
}

TEST(ShellEnergy, DebugBendingEnergyOfQuadratics) {
  for (auto model : {js::BendingModel::hinge, js::BendingModel::triangle})
  for (double edge : {0.01, 0.005, 0.0025}) {
    const js::RevolvedMesh disc = js::disc_mesh(0.1, edge);
    js::ShellBody body = js::make_shell_body(disc.mesh, js::ShellMaterial{}, model);
    body.membranes.clear();
    const double D = js::ShellMaterial{}.bending_n_m(), kappa = 0.1;
    double min_angle = 180;
    for (const auto& t : disc.mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        const js::Vec3 a = disc.mesh.vertices[t[k]], b = disc.mesh.vertices[t[(k + 1) % 3]], c = disc.mesh.vertices[t[(k + 2) % 3]];
        min_angle = std::min(min_angle, std::acos((b - a).normalized().dot((c - a).normalized())) * 180 / M_PI);
      }
    for (int mode = 0; mode < 2; ++mode) {
      js::Vector x = js::stack(disc.mesh.vertices);
      for (std::size_t v = 0; v < disc.mesh.vertices.size(); ++v) {
        const double X = disc.mesh.vertices[v].x(), Z = disc.mesh.vertices[v].z();
        x(3 * v + 1) = mode == 0 ? 0.5 * kappa * X * X : 0.25 * kappa * (X * X + Z * Z);
      }
      const double area = js::surface_area(disc.mesh);
      const double exact = mode == 0 ? 0.5 * D * kappa * kappa * area : 0.5 * D * (kappa * kappa - 2 * (1 - 0.3) * 0.25 * kappa * kappa) * area;
      std::printf("edge %.4f min angle %.1f mode %d: W / exact = %.4f\n", edge, min_angle, mode, js::elastic_energy(body, x) / exact);
    }
  }
}
