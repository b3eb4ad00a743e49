// The bell as an elastic shell: its mesh, material, muscles, pacemaker and tentacles
// (docs/three-d.md, "Part 3").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "jellysim/ode/leapfrog.hpp"
#include "jellysim/shell/shell_bell.hpp"
#include "jellysim/shell/shell_dynamics.hpp"

namespace js = jellysim::shell;

namespace {

constexpr double kPi = std::numbers::pi;

js::Vector jiggled(const js::Vector& x, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  js::Vector y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += amplitude * u(rng);
  return y;
}

js::Vector forces(const js::ShellBody& body, const js::Vector& x) {
  js::Vector f = js::Vector::Zero(x.size());
  js::add_elastic_forces(body, x, f);
  return f;
}

/// x rotated about an axis through the origin by `angle`, then moved by `shift`.
js::Vector rigidly_moved(const js::Vector& x, const Eigen::Matrix3d& R, const js::Vec3& shift) {
  js::Vector y = x;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) y.segment<3>(3 * i) = R * x.segment<3>(3 * i) + shift;
  return y;
}

js::ShellBellSpec coarse_bell() {
  js::ShellBellSpec spec;
  spec.target_edge_m = 0.006;
  return spec;
}

}  // namespace

TEST(ShellBellMesh, VolumeAndAreaConvergeToTheHalfSpheroid) {
  // The slice's half-ellipse (D = 4 cm, H = 2.8 cm) revolved is half a prolate spheroid: volume
  // ⅔πR²H, area πR² (1 + H/(R e) asin e), e² = 1 − R²/H². The inscribed mesh converges at second order.
  const double R = 0.02, H = 0.028, e = std::sqrt(1.0 - R * R / (H * H));
  const double volume = 2.0 / 3.0 * kPi * R * R * H, area = kPi * R * R * (1.0 + H / (R * e) * std::asin(e));
  std::vector<double> dv, da;
  for (double edge : {0.004, 0.002, 0.001}) {
    const js::RevolvedMesh bell = js::bell_mesh(2 * R, H, edge);
    dv.push_back(js::enclosed_volume(bell.mesh.vertices, bell.mesh) / volume - 1.0);
    da.push_back(js::surface_area(bell.mesh) / area - 1.0);
    double min_angle = kPi;
    for (const auto& t : bell.mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        const js::Vec3 a = bell.mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
        const js::Vec3 b = bell.mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])];
        const js::Vec3 c = bell.mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 2) % 3)])];
        min_angle = std::min(min_angle, std::acos((b - a).normalized().dot((c - a).normalized())));
      }
    std::printf("bell mesh, edge %.3f m: %zu vertices, %zu faces, smallest angle %.1f deg, volume error %+.3e, area error %+.3e\n",
                edge, bell.mesh.vertices.size(), bell.mesh.triangles.size(), min_angle * 180 / kPi, dv.back(), da.back());
    EXPECT_GT(min_angle * 180 / kPi, 30.0);  // no slivers, the apex included
  }
  const double volume_order = std::log2(dv[1] / dv[2]), area_order = std::log2(da[1] / da[2]);
  std::printf("orders: volume %.3f, area %.3f\n", volume_order, area_order);
  EXPECT_NEAR(volume_order, 2.0, 0.15);
  EXPECT_NEAR(area_order, 2.0, 0.15);
  EXPECT_LT(std::abs(dv[2]), 2e-3);
  EXPECT_LT(std::abs(da[2]), 2e-3);
}

TEST(ShellBell, MaterialIsTheSlicesContinuumMaterial) {
  // h = √(12B/S), E = S(1 − ν²)/h, ρh = line density: the meridional strip is the slice.
  const js::ShellBell bell(coarse_bell());
  const auto& c = bell.spec().slice.material;
  const js::ShellMaterial& m = bell.material();
  std::printf("bell shell: h = %.4f mm, E = %.2f Pa, rho = %.2f kg/m3, D = %.3e N m\n", m.thickness_m * 1e3,
              m.youngs_modulus_pa, m.density_kg_per_m3, m.bending_n_m());
  EXPECT_NEAR(m.stretching_n_per_m(), c.stretching_n_per_m, 1e-12 * c.stretching_n_per_m);
  EXPECT_NEAR(m.bending_n_m(), c.bending_n_m, 1e-12 * c.bending_n_m);
  EXPECT_NEAR(m.mass_per_area_kg_per_m2(), c.line_density_kg_per_m2, 1e-12);
  EXPECT_NEAR(m.thickness_m, 0.013412, 1e-6);
  // Masses: the surface's area times ρh plus the tentacles' curtain.
  double mass = 0.0;
  for (double k : bell.body().mass_kg) mass += k;
  const double curtain = c.tentacle_line_density_kg_per_m2 * kPi * bell.spec().slice.diameter_m * bell.spec().slice.tentacle_length_m;
  EXPECT_NEAR(mass, m.mass_per_area_kg_per_m2() * js::surface_area(bell.surface().mesh) + curtain, 1e-12);
}

TEST(ShellBell, ForcesAreTheEnergysGradientWithMusclesAndTentacles) {
  js::ShellBell bell(coarse_bell());
  bell.actuate(0.2);  // muscles partly contracted
  const js::Vector x = jiggled(bell.rest_positions(), 3e-4, 5);
  const js::Vector f = forces(bell.body(), x);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    js::Vector p = x, m = x;
    p(i) += 1e-8;
    m(i) -= 1e-8;
    worst = std::max(worst, std::abs(f(i) + (js::elastic_energy(bell.body(), p) - js::elastic_energy(bell.body(), m)) / 2e-8));
  }
  std::printf("bell: max |f + dW/dx| / max |f| = %.2e\n", worst / f.cwiseAbs().maxCoeff());
  EXPECT_LT(worst / f.cwiseAbs().maxCoeff(), 1e-6);
}

TEST(ShellBell, RigidMotionsGiveNoForceAndRotateTheForces) {
  js::ShellBell bell(coarse_bell());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, js::Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  const js::Vec3 shift(0.3, -0.1, 0.05);
  // At rest with relaxed muscles (at t = 0 the fibres with a delay are still finishing the previous
  // stroke, as the slice's): no force, wherever the bell is put.
  for (auto& fibre : bell.body().fibres) fibre.rest_stretch = 1.0;
  const js::Vector rest_moved = forces(bell.body(), rigidly_moved(bell.rest_positions(), R, shift));
  // Deformed and contracting: the forces turn with the body.
  bell.actuate(0.25);
  const js::Vector x = jiggled(bell.rest_positions(), 3e-4, 9);
  const js::Vector f = forces(bell.body(), x), g = forces(bell.body(), rigidly_moved(x, R, shift));
  const double scale = f.cwiseAbs().maxCoeff();
  const double turned = (g - rigidly_moved(f, R, js::Vec3::Zero())).cwiseAbs().maxCoeff() / scale;
  std::printf("rigid motion: rest force %.2e N (deformed scale %.2e N), rotated forces mismatch %.2e\n",
              rest_moved.cwiseAbs().maxCoeff(), scale, turned);
  EXPECT_LT(rest_moved.cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT(turned, 1e-11);
}

TEST(ShellBell, StiffnessMatrixIsTheForcesDerivative) {
  js::ShellBell bell(coarse_bell());
  bell.actuate(0.25);
  const js::Vector x = jiggled(bell.rest_positions(), 3e-4, 13);
  const js::SparseMatrix K = js::stiffness_matrix(bell.body(), x);
  const js::Vector v = jiggled(js::Vector::Zero(x.size()), 1.0, 17);
  const js::Vector kv = K * v, jvp = js::stiffness_times(bell.body(), x, v);
  const double asym = (js::SparseMatrix(K.transpose()) - K).cwiseAbs().sum() / K.cwiseAbs().sum();
  std::printf("stiffness: |K v - (f(x-ev) - f(x+ev))/2e| / |K v| = %.2e, asymmetry %.1e, %ld nonzeros for %ld unknowns\n",
              (kv - jvp).norm() / kv.norm(), asym, static_cast<long>(K.nonZeros()), static_cast<long>(x.size()));
  EXPECT_LT((kv - jvp).norm() / kv.norm(), 1e-6);
  EXPECT_EQ(asym, 0.0);
}
