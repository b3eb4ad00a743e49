#include "jellysim/jellyfish/hoover_miller.hpp"

#include <optional>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace jellysim::jellyfish {

int HooverMillerSpec::cells_x() const { return resolution * 3 / 8; }
int HooverMillerSpec::cells_y() const { return resolution * 5 / 4; }

namespace {

/// One side of the bell, apex first: points on x = a cos θ, y = b sin θ from θ = π/2, each step
/// dθ = ds / |dX/dθ| (about ds of arc), while θ stays below π − asin(cut/b), the margin.
std::vector<Vec2> west_side(const HooverMillerSpec& s) {
  const double a = s.semi_axis_across_m, b = s.semi_axis_up_m, ds = s.marker_spacing_m();
  const double theta_end = std::numbers::pi - std::asin(s.cut_m / b);
  std::vector<Vec2> side;
  for (double theta = 0.5 * std::numbers::pi; theta < theta_end;
       theta += ds / std::hypot(a * std::sin(theta), b * std::cos(theta)))
    side.push_back({a * std::cos(theta), b * std::sin(theta)});
  return side;
}

/// A non-invariant beam through three points, its preferred second difference that of the start
/// shape (the bell is stress-free at t = 0).
elastic::Ib2dNonInvariantBeam beam(const std::vector<Vec2>& x, int l, int m, int r, double k) {
  const Vec2 d = x[static_cast<std::size_t>(l)] - 2.0 * x[static_cast<std::size_t>(m)] + x[static_cast<std::size_t>(r)];
  return {l, m, r, k, d};
}

}  // namespace

HooverMillerBell hoover_miller_bell(const HooverMillerSpec& s) {
  if (s.resolution < 16 || s.resolution > 4096 || s.resolution % 8 != 0)
    throw std::invalid_argument("Hoover-Miller bell: resolution " + std::to_string(s.resolution) +
                                " must be a multiple of 8 in [16, 4096]");
  const double ds = s.marker_spacing_m();
  HooverMillerBell out;
  elastic::Ib2dStructure& st = out.structure;
  auto& x = st.vertices;

  // Bell points: apex, the west side down to the margin, then its mirror image (the east side).
  const std::vector<Vec2> west = west_side(s);
  const int c = static_cast<int>(west.size());
  for (Vec2 p : west) x.push_back(s.centre_m + p);
  for (int k = 1; k < c; ++k) x.push_back(s.centre_m + Vec2{-west[static_cast<std::size_t>(k)].x, west[static_cast<std::size_t>(k)].y});
  const int n = 2 * c - 1;
  out.bell_points = n;

  // Muscle markers: copies of the lowest quarter of each side's points (not tied to the bell:
  // they act on it only through the fluid, as in IB2d).
  const int wing = n / 2, muscles = wing / 4;
  out.muscle_points = muscles;
  for (int k = 1; k <= muscles; ++k) {
    const Vec2 p = x[static_cast<std::size_t>(wing - muscles + k)];  // a copy: push_back may reallocate
    x.push_back(p);
  }
  for (int k = 1; k <= muscles; ++k) {
    const Vec2 p = x[static_cast<std::size_t>(n - muscles + k - 1)];
    x.push_back(p);
  }

  // The flow blocker: a row of targets ds, 5ds, 9ds, … across the domain, 4ds below its top.
  for (double bx = ds; bx <= s.domain_width_m - ds + 1e-12; bx += 4.0 * ds)
    x.push_back({bx, s.domain_height_m - 4.0 * ds});
  out.target_points = static_cast<int>(x.size()) - n - 2 * muscles;

  // Springs along the bell (rest length as built), the apex joined to the east side's first point.
  const double k_bell = s.spring_stiffness / ds;
  auto chain = [&](int i, int j) { st.springs.push_back({i, j, k_bell, norm(x[static_cast<std::size_t>(j)] - x[static_cast<std::size_t>(i)])}); };
  for (int k = 0; k + 1 < c; ++k) chain(k, k + 1);
  for (int k = c; k + 1 < n; ++k) chain(k, k + 1);
  chain(0, c);
  out.first_muscle_spring = static_cast<int>(st.springs.size());
  for (int k = 0; k < muscles; ++k) st.springs.push_back({n + k, n + muscles + k, s.muscle_spring_stiffness(), 0.0});

  // Non-invariant beams along each side and across the apex.
  const double k_beam = s.beam_stiffness / (ds * ds * ds);
  for (int m = 1; m + 1 < c; ++m) st.non_invariant_beams.push_back(beam(x, m - 1, m, m + 1, k_beam));
  for (int m = c + 1; m + 1 < n; ++m) st.non_invariant_beams.push_back(beam(x, m - 1, m, m + 1, k_beam));
  st.non_invariant_beams.push_back(beam(x, c + 1, c, 0, k_beam));
  st.non_invariant_beams.push_back(beam(x, c, 0, 1, k_beam));

  for (int k = n + 2 * muscles; k < static_cast<int>(x.size()); ++k) st.targets.push_back({k, s.target_stiffness});
  return out;
}

std::vector<double> cycle_displacements(const std::vector<double>& t_s, const std::vector<double>& y_m, int cycles,
                                        double tolerance_s) {
  const auto at = [&](double time) {
    for (std::size_t i = 0; i < t_s.size(); ++i)
      if (std::abs(t_s[i] - time) <= tolerance_s) return std::optional<double>(y_m[i]);
    return std::optional<double>();
  };
  std::vector<double> per_cycle;
  for (int k = 1; k <= cycles; ++k) {
    const auto a = at(k - 1.0), b = at(static_cast<double>(k));
    if (a && b) per_cycle.push_back(*b - *a);
  }
  return per_cycle;
}

double later_cycle_displacement(const std::vector<double>& per_cycle) {
  double mean_later = 0.0;
  int later = 0;
  for (std::size_t k = 1; k < per_cycle.size() && k < 3; ++k, ++later) mean_later += per_cycle[k];
  return later > 0 ? mean_later / later : 0.0;
}

}  // namespace jellysim::jellyfish
