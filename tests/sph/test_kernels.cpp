// The 2D kernels of thesis §5.1.1: normalisation by quadrature, zero value and slope at r = h,
// derivatives against finite differences, and a vanishing gradient sum over a full neighbourhood.
#include "jellysim/sph/initial_conditions.hpp"
#include "jellysim/sph/smoothing_kernels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace jellysim::sph {
namespace {

constexpr double kH = 0.07;

/// ∫∫ W(|x|) dA by the midpoint rule on an n × n Cartesian grid over [−h, h]² (no r = 0 node).
double integrate_2d(const std::function<double(double)>& w, int n) {
  const double dx = 2.0 * kH / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = -kH + (i + 0.5) * dx, y = -kH + (j + 0.5) * dx;
      sum += w(std::hypot(x, y));
    }
  }
  return sum * dx * dx;
}

TEST(SphKernels, Poly6AndSpikyIntegrateToOneOverTheDisc) {
  const Kernels k(kH);
  EXPECT_NEAR(integrate_2d([&](double r) { return k.poly6(r); }, 800), 1.0, 2e-5);
  EXPECT_NEAR(integrate_2d([&](double r) { return k.spiky(r); }, 800), 1.0, 2e-5);
}

TEST(SphKernels, ViscosityKernelIntegratesToOneDespiteItsLogSingularity) {
  const Kernels k(kH);
  EXPECT_NEAR(integrate_2d([&](double r) { return k.viscosity(r); }, 1000), 1.0, 1e-3);
}

TEST(SphKernels, ValueSlopeAndLaplacianVanishAtTheSupportRadius) {
  const Kernels k(kH);
  const double below = kH * (1.0 - 1e-9);
  for (double r : {kH, below}) {
    EXPECT_NEAR(k.poly6(r), 0.0, 1e-12 * k.poly6(0.0));
    EXPECT_NEAR(k.spiky(r), 0.0, 1e-12 * k.spiky(0.0));
    EXPECT_NEAR(k.viscosity(r), 0.0, 1e-6 * k.viscosity(0.5 * kH));
    EXPECT_NEAR(k.poly6_derivative(r), 0.0, 1e-9 * std::abs(k.poly6_derivative(0.5 * kH)));
    EXPECT_NEAR(k.spiky_derivative(r), 0.0, 1e-9 * std::abs(k.spiky_derivative(0.0)));
    EXPECT_NEAR(k.viscosity_derivative(r), 0.0, 1e-6 * std::abs(k.viscosity_derivative(0.5 * kH)));
    EXPECT_NEAR(k.viscosity_laplacian(r), 0.0, 1e-6 * k.viscosity_laplacian(0.0));
  }
  EXPECT_EQ(k.spiky_gradient({kH, 0.0}, kH), (Vec2{0.0, 0.0}));
}

double central_difference(const std::function<double(double)>& f, double r) {
  const double d = 1e-6 * kH;
  return (f(r + d) - f(r - d)) / (2.0 * d);
}

TEST(SphKernels, RadialDerivativesMatchFiniteDifferences) {
  const Kernels k(kH);
  for (int i = 1; i < 20; ++i) {
    const double r = kH * i / 20.0;
    const double tol = 1e-6;
    EXPECT_NEAR(k.poly6_derivative(r), central_difference([&](double s) { return k.poly6(s); }, r),
                tol * std::abs(k.poly6_derivative(0.5 * kH)));
    EXPECT_NEAR(k.spiky_derivative(r), central_difference([&](double s) { return k.spiky(s); }, r),
                tol * std::abs(k.spiky_derivative(0.0)));
    EXPECT_NEAR(k.viscosity_derivative(r), central_difference([&](double s) { return k.viscosity(s); }, r),
                tol * std::abs(k.viscosity_derivative(0.05 * kH)));
  }
}

TEST(SphKernels, SpikyGradientIsTheDerivativeNotTheKernel) {
  // The slip in widely copied 2D code: using W_spiky itself where ∇W belongs.
  const Kernels k(kH);
  const double r = 0.3 * kH;
  const Vec2 g = k.spiky_gradient({r, 0.0}, r);
  EXPECT_NEAR(g.x, -30.0 / (M_PI * std::pow(kH, 5)) * (kH - r) * (kH - r), 1e-9 * std::abs(g.x));
  EXPECT_LT(g.x, 0.0);  // points towards the neighbour: pressure pushes apart with the minus of eq. 5.6
  EXPECT_GT(std::abs(g.x - (-k.spiky(r))), 0.1 * std::abs(g.x));
}

TEST(SphKernels, ViscosityLaplacianIsThe2DPolarLaplacianOfTheKernel) {
  const Kernels k(kH);
  for (int i = 1; i < 20; ++i) {
    const double r = kH * i / 20.0, d = 1e-3 * r;
    const double second = (k.viscosity(r + d) - 2.0 * k.viscosity(r) + k.viscosity(r - d)) / (d * d);
    const double laplacian = second + k.viscosity_derivative(r) / r;  // eq. 5.10
    // The two terms cancel their 1/r² parts: compare relative to the size of W''.
    EXPECT_NEAR(k.viscosity_laplacian(r), laplacian, 1e-5 * (std::abs(second) + k.viscosity_laplacian(0.0)))
        << "r = " << r;
  }
}

TEST(SphKernels, GradientSumVanishesOverAFullNeighbourhood) {
  const Kernels k(kH);
  const std::vector<Vec2> lattice = triangular_lattice({0.0, 0.0}, {1.0, 1.0}, 0.6 * kH);
  // The lattice point nearest the centre has a complete, point-symmetric neighbourhood.
  std::size_t centre = 0;
  for (std::size_t i = 0; i < lattice.size(); ++i) {
    if (norm(lattice[i] - Vec2{0.5, 0.5}) < norm(lattice[centre] - Vec2{0.5, 0.5})) centre = i;
  }
  Vec2 sum{};
  double magnitude = 0.0;
  int neighbours = 0;
  for (const Vec2& x : lattice) {
    const Vec2 d = lattice[centre] - x;
    const Vec2 g = k.spiky_gradient(d, norm(d));
    sum += g;
    magnitude += norm(g);
    neighbours += norm(d) > 0.0 && norm(d) < kH;
  }
  EXPECT_EQ(neighbours, 6);
  EXPECT_LT(norm(sum), 1e-12 * magnitude);
}

}  // namespace
}  // namespace jellysim::sph
