// Stokes drag on a sphere of markers in 3D (issue 40, part 2): a simple cubic array of spheres
// (one periodic cell, computed as its quarter between mirror planes) against Zick & Homsy's (1982)
// drag coefficient.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "jellysim/ib3d/immersed_boundary_3d.hpp"

namespace jellysim::ib3d {
namespace {

using fluid3d::Boundaries3d;
using fluid3d::Grid3d;

/// Adds U − mean(v) to every v sample: the cell's mean (superficial) velocity held at U, i.e. the
/// uniform driving acceleration that keeps it there. A uniform shift is divergence-free and keeps
/// every boundary condition here (v is tangential to the mirror planes, y is periodic).
void hold_mean_flow(fluid3d::FluidSolver3d& fluid, double u) {
  const Grid3d& g = fluid.state().grid;
  fluid3d::Field3d& v = fluid.mutable_state().velocity.c[1];
  double sum = 0.0;
  for (int k = 0; k < g.n(2); ++k)
    for (int j = 0; j < g.n(1); ++j)
      for (int i = 0; i < g.n(0); ++i) sum += v[g.index(i, j, k)];
  const double shift = u - sum / static_cast<double>(g.cell_count());
  for (double& s : v) s += shift;
}

struct DragRun {
  double drag_n = 0.0, radius_m = 0.0;
  std::size_t markers = 0;
};

constexpr double kVolumeFraction = 0.064, kZickHomsyK = 2.810;  // Zick & Homsy (1982), Table 2, simple cubic
constexpr double kCell = 0.048, kSpeed = 1e-3, kViscosity = 1e-3, kDensity = 1000.0;

/// One periodic cell (side L = n h = 48 mm) of a simple cubic array of spheres of volume fraction
/// c = 4πa³/(3L³) = 0.064 (a = 0.248 L), as its quarter: x and z between two mirror planes (through
/// the sphere's centre and half-way to the next sphere), periodic along y, the flow along y with the
/// cell's mean velocity held at U = 1 mm/s. The sphere's surface markers (half a cell apart, the
/// quarter's) are tethered to their anchors (0.5 N/m each: the sphere sits 1e-3 cells downstream);
/// the drag is the tethers' pull, four times the quarter's. ν = 1e-3 m²/s: Re = Ua/ν = 0.012.
/// Run for 0.4 s, seven viscous times L²/(4π²ν) = 0.058 s: the drag changes by less than 2e-4 from
/// 0.4 to 0.5 s (measured); later it creeps up by 0.09 % per second (n = 24), as the markers follow
/// the flow that leaks through the sphere's surface and the tethers stretch with them.
DragRun periodic_array_drag(int n, Scheme3d scheme, double duration_s = 0.4) {
  const double h = kCell / n, a = kCell * std::cbrt(3.0 * kVolumeFraction / (4.0 * std::numbers::pi));
  fluid3d::FluidSettings3d fs;
  fs.viscosity_m2_per_s = kViscosity;
  fs.density_kg_per_m3 = kDensity;
  fs.boundaries = Boundaries3d::duct(1);
  fs.boundaries.axis[0].symmetry = fs.boundaries.axis[2].symmetry = {true, true};
  fs.safety_factor = 0.9;
  auto fluid = fluid3d::make_fluid_solver_3d(Grid3d({n / 2, n, n / 2}, {kCell / 2, kCell, kCell / 2}), fs);
  hold_mean_flow(*fluid, kSpeed);
  Markers3d markers(sphere_surface_markers({0.0, kCell / 2, 0.0}, a, h / 2, true));
  const double k = 0.5;
  Tethers3d tethers(markers.position, std::vector<double>(markers.size(), k));
  CouplingSettings3d cs;
  cs.scheme = scheme;
  ImmersedBoundary3d ib(*fluid, markers, tethers, cs);
  const double dt = fluid->stable_time_step();
  while (ib.time_s() < duration_s - 1e-12) {
    ib.step(dt);
    hold_mean_flow(*fluid, kSpeed);
  }
  DragRun r{0.0, a, markers.size()};
  for (std::size_t m = 0; m < markers.size(); ++m) r.drag_n += 4.0 * k * (markers.position[m][1] - tethers.anchors()[m][1]);
  return r;
}

/// F = 6πμaKU (Zick & Homsy 1982: U the superficial velocity, the cell's mean).
double exact_drag(double radius_m) { return 6.0 * std::numbers::pi * kViscosity * kDensity * radius_m * kZickHomsyK * kSpeed; }

/// The value at h = 0 of F0 + A h + B h² through three resolutions (n = L/h).
double extrapolate_quadratic(const std::array<int, 3>& n, const std::array<double, 3>& f) {
  double sum = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    double l = 1.0;
    for (std::size_t j = 0; j < 3; ++j)
      if (j != i) l *= (0.0 - 1.0 / n[j]) / (1.0 / n[i] - 1.0 / n[j]);
    sum += f[i] * l;
  }
  return sum;
}

std::array<double, 3> drag_ratios(const std::array<int, 3>& n) {
  std::array<double, 3> ratio{};
  for (std::size_t i = 0; i < 3; ++i) {
    const DragRun r = periodic_array_drag(n[i], Scheme3d::explicit_euler);
    ratio[i] = r.drag_n / exact_drag(r.radius_m);
    std::printf("n = %d (%.2f cells per radius, %zu markers in the quarter): drag / exact %.5f\n", n[i],
                r.radius_m * n[i] / kCell, r.markers, ratio[i]);
  }
  return ratio;
}

// Stokes drag on a sphere in a simple cubic array, c = 0.064: K = 2.810 (Zick & Homsy 1982, Table 2;
// the series of Sangani & Acrivos 1982 gives 2.8101). The error of the immersed boundary is that of
// a sphere larger by about half a cell, which a periodic array amplifies (d ln F / d ln a ≈ 3 here)
// and makes markedly nonlinear: measured F/F_exact − 1 = 0.463, 0.252, 0.204 at 3.97, 5.96, 6.95
// cells per radius (n = 16, 24, 28; 0.171 at 7.94, n = 32), so (F − F_exact)·n falls from 7.4 to
// 5.5: not yet first order. The two finest alone, extrapolated at first order, are 8.4 % low;
// F0 + A h + B h² through the three is 3.0 % high (measured 1.0301). We ask the latter within 5 %,
// and the error to fall with the cell.
TEST(SphereDrag3d, PeriodicArrayOfSpheresMatchesZickAndHomsy) {
  const std::array<int, 3> n{16, 24, 28};
  const auto ratio = drag_ratios(n);
  const double extrapolated = extrapolate_quadratic(n, ratio);
  const double first_order = (n[2] * ratio[2] - n[1] * ratio[1]) / (n[2] - n[1]);
  std::printf("extrapolated drag / exact: %.4f (F0 + A h + B h^2), %.4f (first order from the two finest)\n",
              extrapolated, first_order);
  EXPECT_GT(ratio[0], ratio[1]);
  EXPECT_GT(ratio[1], ratio[2]);
  EXPECT_GT(ratio[2], 1.0);
  EXPECT_NEAR(extrapolated, 1.0, 0.05);
}

// The same on finer grids (Release only: the name holds "Slow"): 5.96, 7.94 and 9.93 cells per radius, F/F_exact 1.2520,
// 1.1710, 1.1288; extrapolated 1.0075 (measured), asked within 2 %.
TEST(SlowSphereDrag3d, PeriodicArrayOfSpheresOnFinerGrids) {
  const std::array<int, 3> n{24, 32, 40};
  const auto ratio = drag_ratios(n);
  const double extrapolated = extrapolate_quadratic(n, ratio);
  std::printf("extrapolated drag / exact: %.4f\n", extrapolated);
  EXPECT_GT(ratio[1], ratio[2]);
  EXPECT_NEAR(extrapolated, 1.0, 0.02);
}

}  // namespace
}  // namespace jellysim::ib3d
