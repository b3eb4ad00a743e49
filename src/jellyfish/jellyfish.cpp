#include "jellysim/jellyfish/jellyfish.hpp"

#include "jellysim/core/state_archive.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "jellysim/elastic/forces.hpp"
#include "jellysim/jellyfish/segment_sweep.hpp"

namespace jellysim::jellyfish {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void require(bool ok, const std::string& field, const std::string& range) {
  if (!ok) throw std::invalid_argument("field 'jellyfish." + field + "' is out of range " + range);
}

/// Eq. 7.1 (corrected, see docs/physics.md): κ_l = λ A / l_r.
double stiffness(double modulus_pa, double area_m2, double rest_length_m) {
  return elastic::linear_stiffness_from_modulus(modulus_pa, area_m2, rest_length_m);
}

/// Outward normals of a polyline (eq. 7.6 with the sign chosen away from the cavity): the bell
/// runs left tip → apex → right tip, i.e. clockwise seen from inside, so the outward side is the
/// left-hand normal of the tangent.
std::vector<Vec2> outward_normals(const std::vector<Vec2>& p) {
  std::vector<Vec2> n(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 a = p[i == 0 ? 0 : i - 1], b = p[i + 1 == p.size() ? i : i + 1];
    const Vec2 t = b - a;
    n[i] = perp(t) / norm(t);
  }
  return n;
}

}  // namespace

std::vector<Vec2> bell_profile(double diameter_m, double height_m, int segments_per_side) {
  const double r = 0.5 * diameter_m;
  auto at = [&](double phi) { return Vec2{r * std::sin(phi), height_m * std::cos(phi)}; };
  // Arc-length table of the right quarter φ ∈ [0, π/2] (apex to tip); the left side is its exact
  // mirror image, so a symmetric bell starts symmetric to the last bit.
  const int samples = 4096;
  std::vector<double> arc(samples + 1, 0.0);
  for (int k = 1; k <= samples; ++k) {
    const double p0 = 0.5 * std::numbers::pi * (k - 1) / samples, p1 = 0.5 * std::numbers::pi * k / samples;
    arc[k] = arc[k - 1] + norm(at(p1) - at(p0));
  }
  std::vector<Vec2> right;  // apex first
  for (int i = 0; i <= segments_per_side; ++i) {
    const double target = arc.back() * i / segments_per_side;
    const auto it = std::lower_bound(arc.begin(), arc.end(), target);
    const int k = std::clamp(static_cast<int>(it - arc.begin()), 1, samples);
    const double w = std::clamp((target - arc[k - 1]) / std::max(arc[k] - arc[k - 1], 1e-300), 0.0, 1.0);
    right.push_back(at(0.5 * std::numbers::pi * (k - 1 + w) / samples));
  }
  right.front() = {0.0, height_m};
  right.back() = {r, 0.0};
  std::vector<Vec2> points;
  for (int i = segments_per_side; i >= 1; --i) points.push_back({-right[static_cast<std::size_t>(i)].x, right[static_cast<std::size_t>(i)].y});
  points.insert(points.end(), right.begin(), right.end());
  return points;
}

std::vector<int> make_rings(elastic::Body& body, double axis_x, double spacing, const std::vector<int>& partner,
                            const std::vector<std::vector<int>>& hoop_rows, const std::vector<int>& muscles,
                            double membrane_stiffness_n_per_m) {
  const auto& x = body.points.position;
  const double smallest_radius = 0.25 * spacing;  // mean radius of the material within half a spacing of the axis
  auto radius = [&](int p) { return std::abs(x[static_cast<std::size_t>(p)].x - axis_x); };
  std::vector<char> is_muscle(body.linear.size(), 0);
  for (int m : muscles) is_muscle[static_cast<std::size_t>(m)] = 1;
  for (std::size_t k = 0; k < body.linear.size(); ++k) {
    const double r = 0.5 * (radius(body.linear.i[k]) + radius(body.linear.j[k]));
    body.linear.stiffness[k] *= 2.0 * std::numbers::pi * (is_muscle[k] ? 1.0 : std::max(r, smallest_radius));
  }
  for (std::size_t a = 0; a < body.angular.size(); ++a) {
    const double r = (radius(body.angular.i[a]) + radius(body.angular.j[a]) + radius(body.angular.k[a])) / 3.0;
    body.angular.stiffness[a] *= 2.0 * std::numbers::pi * std::max(r, smallest_radius);
  }
  // Hoop springs: a ring of rest radius r₀ and meridional width s has hoop stiffness C s / (2π r₀);
  // its radial pull 2π T = 2π C s (r − r₀)/r₀ is that of a spring of constant π C s / r₀ across the
  // axis, whose length is 2r (rest length 2r₀).
  std::vector<int> hoops;
  for (const std::vector<int>& row : hoop_rows)
    for (std::size_t k = 0; k < row.size(); ++k) {
      const int p = row[k], q = partner[static_cast<std::size_t>(p)];
      const double r0 = radius(p);
      if (q == p || x[static_cast<std::size_t>(p)].x < axis_x || r0 < 1e-12 * spacing) continue;
      double s = 0.0;
      if (k > 0) s += 0.5 * norm(x[static_cast<std::size_t>(p)] - x[static_cast<std::size_t>(row[k - 1])]);
      if (k + 1 < row.size()) s += 0.5 * norm(x[static_cast<std::size_t>(row[k + 1])] - x[static_cast<std::size_t>(p)]);
      body.add_linear_spring(p, q, std::numbers::pi * membrane_stiffness_n_per_m * s / r0, 2.0 * r0);
      hoops.push_back(static_cast<int>(body.linear.size()) - 1);
    }
  return hoops;
}

bool polyline_self_intersects(const std::vector<Vec2>& p) {
  auto crosses = [](const Segment& s, const Segment& t) {
    const Vec2 a = s[0], b = s[1], c = t[0], d = t[1];
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
  };
  std::vector<Segment> segments;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) segments.push_back({p[i], p[i + 1]});
  return any_pair_crosses(segments, crosses, [](std::size_t i, std::size_t j) { return j == i + 1; });
}

MarkerPlan plan_markers(const JellyfishSpec& s) {
  MarkerPlan plan;
  // Segments per side so that neighbouring markers are at most max_spacing apart.
  const std::vector<Vec2> fine = bell_profile(s.diameter_m, s.height_m, 256);
  double half_arc = 0.0;
  for (std::size_t i = 0; i + 1 <= 256; ++i) half_arc += norm(fine[i + 1] - fine[i]);
  plan.segments_per_side = std::max(static_cast<double>(s.min_segments_per_side), std::ceil(half_arc / s.max_spacing_m));
  plan.spacing_m = half_arc / plan.segments_per_side;
  plan.tentacle_points = s.tentacle_length_m > 0 ? std::max(2.0, std::ceil(s.tentacle_length_m / plan.spacing_m)) : 0.0;
  const double rows = s.model == UmbrellaModel::mesh ? 2.0 : 1.0;
  plan.markers = rows * (2.0 * plan.segments_per_side + 1.0) + 2.0 * plan.tentacle_points;
  return plan;
}

void validate(const JellyfishSpec& s) {
  require(s.diameter_m > 0, "diameter", "(0, inf) m");
  require(s.height_m > 0, "height", "(0, inf) m");
  require(s.tentacle_length_m >= 0, "tentacle_length", "[0, inf) m");
  require(s.thickness_m > 0, "thickness", "(0, inf) m");
  require(s.max_spacing_m > 0, "max_spacing", "(0, inf) m");
  require(s.min_segments_per_side >= 2 && s.min_segments_per_side <= 1000, "min_segments_per_side", "[2, 1000]");
  require(s.bell_modulus_pa > 0, "bell_modulus", "(0, inf) Pa");
  require(s.muscle_modulus_pa >= 0, "muscle_modulus", "[0, inf) Pa");
  require(s.bending_factor >= 0, "bending_factor", "[0, inf)");
  require(s.tentacle_bending_factor >= 0, "tentacle_bending_factor", "[0, inf)");
  require(s.tentacle_volume_fraction > 0, "tentacle_volume_fraction", "(0, inf)");
  const ContinuumMaterial& m = s.material;
  require(m.stretching_n_per_m > 0 && std::isfinite(m.stretching_n_per_m), "stretching_stiffness", "(0, inf) N/m");
  require(m.bending_n_m >= 0 && std::isfinite(m.bending_n_m), "bending_rigidity", "[0, inf) N·m");
  require(m.muscle_n_per_m2 >= 0 && std::isfinite(m.muscle_n_per_m2), "muscle_stiffness", "[0, inf) N/m²");
  require(m.tentacle_stretching_n_per_m > 0 && std::isfinite(m.tentacle_stretching_n_per_m),
          "tentacle_stretching_stiffness", "(0, inf) N/m");
  require(m.tentacle_bending_n_m >= 0 && std::isfinite(m.tentacle_bending_n_m), "tentacle_bending_rigidity", "[0, inf) N·m");
  require(m.line_density_kg_per_m2 > 0 && std::isfinite(m.line_density_kg_per_m2), "line_density", "(0, inf) kg/m²");
  require(m.tentacle_line_density_kg_per_m2 > 0 && std::isfinite(m.tentacle_line_density_kg_per_m2),
          "tentacle_line_density", "(0, inf) kg/m²");
  if (s.model == UmbrellaModel::mesh && s.elastic_model == ElasticModel::continuum)
    throw std::invalid_argument("field 'jellyfish.model' = \"mesh\" is the thesis's per-spring lattice (Fig. 7.2 left): "
                                "set jellyfish.elastic_model = \"thesis\" with it");
  require(s.frequency_hz > 0 && s.frequency_hz <= 100, "frequency", "(0, 100] Hz");
  require(s.gamma > 0 && s.gamma <= 1, "gamma", "(0, 1]");
  require(s.profile.contract_fraction > 0 && s.profile.contract_fraction < 1, "contract_fraction", "(0, 1)");
  require(s.profile.pause_fraction >= 0 && s.profile.contract_fraction + s.profile.pause_fraction < 1,
          "pause_fraction", "[0, 1 - contract_fraction)");
  if (s.profile.pause_fraction != 0 && s.closed_loop)
    throw std::invalid_argument("field 'jellyfish.pause_fraction' must be 0 with the closed-loop controller "
                                "(jellyfish.controller = true): the pause belongs to the open-loop contraction");
  require(s.aperture_expansion_exponent >= 1 && s.aperture_expansion_exponent <= 10, "aperture_expansion_exponent",
          "[1, 10]");
  require(s.neural_delay_s >= 0, "neural_delay", "[0, inf) s");
  require(s.profile.trochoid_skew >= 0 && s.profile.trochoid_skew < 1, "trochoid_skew", "[0, 1)");
  if (s.rings && std::abs(std::sin(s.tilt_rad)) > 1e-12)
    throw std::invalid_argument("field 'jellyfish.tilt_deg': a ring jellyfish (axisymmetric tank) swims along the "
                                "axis: the tilt must be 0 or 180 degrees");
}

namespace {

/// The discrete constants of the slice's springs and points under either elastic model
/// (docs/jellyfish.md, "Elastic models"). The thesis branch keeps §7.1's per-spring construction
/// bit for bit; the continuum branch discretises material quantities per metre of depth.
class SpringConstants {
 public:
  explicit SpringConstants(const JellyfishSpec& s) : s_(s) {}

  /// A bell spring of rest length l: κ_l = S / l, or eq. 7.1's λ ϑ² / l.
  double bell_spring(double l) const {
    return continuum() ? s_.material.stretching_n_per_m / l : stiffness(s_.bell_modulus_pa, bell_area(), l);
  }
  /// A bell joint between segments l1 and l2: the discrete curvature is θ over the mean segment l̄,
  /// so E = ½ B (θ/l̄)² l̄ gives κ_θ = B / l̄. Thesis: κ_θ = f κ_l l_r² at the marker spacing.
  double bell_joint(double l1, double l2, double spacing) const {
    if (continuum()) return s_.material.bending_n_m / (0.5 * (l1 + l2));
    return s_.bending_factor * stiffness(s_.bell_modulus_pa, bell_area(), spacing) * spacing * spacing;
  }
  double tentacle_spring(double l) const {
    return continuum() ? s_.material.tentacle_stretching_n_per_m / l
                       : stiffness(s_.bell_modulus_pa, s_.tentacle_volume_fraction * bell_area(), l);
  }
  /// A tentacle joint between segments l1 and l2 (the thesis: at the tentacle spacing).
  double tentacle_joint(double l1, double l2, double tentacle_spacing) const {
    if (continuum()) return s_.material.tentacle_bending_n_m / (0.5 * (l1 + l2));
    return s_.tentacle_bending_factor * tentacle_spring(tentacle_spacing) * tentacle_spacing * tentacle_spacing;
  }
  /// The joint where a tentacle leaves the bell, between the bell's last segment l_bell and the
  /// tentacle's first l_tentacle: its half cells bend in series under the one moment there,
  /// κ_θ = 1 / (½ l_bell / B + ½ l_tentacle / B_t) (B / l̄ when the two are alike).
  double root_joint(double l_bell, double l_tentacle, double tentacle_spacing) const {
    if (!continuum()) return tentacle_joint(l_bell, l_tentacle, tentacle_spacing);
    const double compliance = 0.5 * l_bell / s_.material.bending_n_m + 0.5 * l_tentacle / s_.material.tentacle_bending_n_m;
    return s_.material.bending_n_m > 0 && s_.material.tentacle_bending_n_m > 0 ? 1.0 / compliance : 0.0;
  }
  /// True when the root joint holds the tentacle against the aperture chord (TentacleRoot::axis).
  bool root_on_axis() const {
    return s_.tentacle_root == TentacleRoot::axis || (s_.tentacle_root == TentacleRoot::automatic && continuum());
  }
  /// The root joint against the aperture chord: only the tentacle's first half cell bends between
  /// the chord and the strand, κ_θ = B_t / (½ l_tentacle) (thesis: its tentacle joint).
  double axis_root_joint(double l_tentacle, double tentacle_spacing) const {
    if (!continuum()) return tentacle_joint(l_tentacle, l_tentacle, tentacle_spacing);
    return s_.material.tentacle_bending_n_m / (0.5 * l_tentacle);
  }
  /// A muscle of uncontracted length L standing for a band of bell `band` high, `gap` from its
  /// neighbouring muscles: κ = k_m band / L (its tension per unit strain is k_m band), or §7.1's
  /// λ_m gap² / L.
  double muscle(double band, double gap, double length) const {
    if (continuum()) return s_.material.muscle_n_per_m2 * band / length;
    return s_.muscle_modulus_pa > 0 ? stiffness(s_.muscle_modulus_pa, gap * gap, length) : 0.0;
  }
  /// The mass of a point standing for `arc` metres of bell or tentacle (thesis: one per marker).
  double bell_mass(double arc) const { return continuum() ? s_.material.line_density_kg_per_m2 * arc : s_.point_mass_kg; }
  double tentacle_mass(double arc) const {
    return continuum() ? s_.material.tentacle_line_density_kg_per_m2 * arc : s_.point_mass_kg * s_.tentacle_volume_fraction;
  }
  /// What a tentacle's first half segment adds to the bell tip it hangs from (thesis: nothing).
  double tentacle_root_mass(double arc) const { return continuum() ? tentacle_mass(arc) : 0.0; }
  /// C = κ_l l_r of the bell's springs, the ring jellyfish's hoop membrane stiffness.
  double membrane() const { return continuum() ? s_.material.stretching_n_per_m : s_.bell_modulus_pa * bell_area(); }

 private:
  bool continuum() const { return s_.elastic_model == ElasticModel::continuum; }
  double bell_area() const { return s_.thickness_m * s_.thickness_m; }  ///< A = ϑ² (§7.1)
  const JellyfishSpec& s_;
};

}  // namespace

std::vector<double> arc_per_point(const std::vector<Vec2>& p) {
  std::vector<double> arc(p.size(), 0.0);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double half = 0.5 * norm(p[i + 1] - p[i]);
    arc[i] += half;
    arc[i + 1] += half;
  }
  return arc;
}

Jellyfish::Jellyfish(const JellyfishSpec& spec) : spec_(spec) {
  validate(spec_);
  const MarkerPlan plan = plan_markers(spec_);
  if (!(plan.markers <= kMaxMarkers)) {
    std::ostringstream why;
    why.precision(3);
    why << "the jellyfish would need " << plan.markers << " markers (at most " << kMaxMarkers
        << "): jellyfish.spacing is too small for its size";
    throw std::invalid_argument(why.str());
  }
  std::vector<Vec2> profile = bell_profile(spec_.diameter_m, spec_.height_m, static_cast<int>(plan.segments_per_side));
  for (Vec2& p : profile) p = spec_.aperture_centre_m + rotated(p, spec_.tilt_rad);
  build_umbrella(profile, plan.spacing_m);
  build_muscles(profile, plan.spacing_m);
  build_tentacles(static_cast<int>(plan.tentacle_points));
  if (spec_.rings) make_ring_jellyfish(plan.spacing_m);
  base_stiffness_ = own_body_.linear.stiffness;
  base_joint_stiffness_ = own_body_.angular.stiffness;
  base_rest_angle_ = own_body_.angular.rest_angle;
  // Umbrella joints belong to the left (before the apex) or the right side; tentacle joints to neither.
  const int n = static_cast<int>(profile.size());
  for (std::size_t a = 0; a < own_body_.angular.size(); ++a) {
    const int i = own_body_.angular.i[a], j = own_body_.angular.j[a], k = own_body_.angular.k[a];
    const bool umbrella = i < n && j < n && k < n;
    joint_side_.push_back(!umbrella || j == layout_.apex ? 0 : (j < layout_.apex ? -1 : 1));
  }
  point_count_ = own_body_.points.size();
  actuate(0.0);
}

int Jellyfish::add_spring(int a, int b, double stiffness_n_per_m) {
  const double l = norm(own_body_.points.position[static_cast<std::size_t>(b)] - own_body_.points.position[static_cast<std::size_t>(a)]);
  own_body_.add_linear_spring(a, b, stiffness_n_per_m, l);
  return static_cast<int>(own_body_.linear.size()) - 1;
}

double Jellyfish::distance(int a, int b) const {
  return norm(own_body_.points.position[static_cast<std::size_t>(b)] - own_body_.points.position[static_cast<std::size_t>(a)]);
}

void Jellyfish::build_umbrella(const std::vector<Vec2>& profile, double spacing) {
  // The subumbrellar string (§7.1), left tip → apex → right tip.
  const SpringConstants k(spec_);
  const std::vector<double> arc = arc_per_point(profile);
  for (std::size_t i = 0; i < profile.size(); ++i) layout_.umbrella.push_back(own_body_.add_point(profile[i], k.bell_mass(arc[i])));
  layout_.apex = static_cast<int>(profile.size() / 2);
  const auto& u = layout_.umbrella;
  const int n = static_cast<int>(u.size());
  if (spec_.model == UmbrellaModel::angular) {
    for (int i = 0; i + 1 < n; ++i) add_spring(u[i], u[i + 1], k.bell_spring(distance(u[i], u[i + 1])));
    for (int i = 1; i + 1 < n; ++i) {
      const double joint = k.bell_joint(distance(u[i - 1], u[i]), distance(u[i], u[i + 1]), spacing);
      if (joint > 0) own_body_.add_angular_spring(u[i - 1], u[i], u[i + 1], joint, kNaN);
    }
    return;
  }
  // Fig. 7.2 left (thesis model only): a second (exumbrellar) row one spacing outside, quads with
  // crossing diagonals.
  const std::vector<Vec2> normals = outward_normals(profile);
  const double depth = std::max(spec_.thickness_m, spacing);
  for (int i = 0; i < n; ++i)
    layout_.exumbrella.push_back(own_body_.add_point(profile[static_cast<std::size_t>(i)] + depth * normals[static_cast<std::size_t>(i)], spec_.point_mass_kg));
  const auto& e = layout_.exumbrella;
  auto spring = [&](int a, int b) { add_spring(a, b, k.bell_spring(distance(a, b))); };
  for (int i = 0; i < n; ++i) {
    spring(u[i], e[i]);
    if (i + 1 == n) break;
    spring(u[i], u[i + 1]);
    spring(e[i], e[i + 1]);
    spring(u[i], e[i + 1]);
    spring(e[i], u[i + 1]);
  }
}

void Jellyfish::build_muscles(const std::vector<Vec2>& profile, double spacing) {
  // Subumbrellar muscles between opposing points, aperture first (§7.1), up to the point next to
  // the apex. Each stands for a band of bell height: from halfway to the muscle below (the
  // aperture's from the aperture itself) to halfway to the next pair of points above.
  const SpringConstants k(spec_);
  const int n = static_cast<int>(profile.size()), m = layout_.apex;
  const int muscles = std::max(1, m - 1);
  std::vector<Vec2> mids;  // the muscles' midpoints on the axis, then the rest up to the apex
  for (int j = 0; j <= m; ++j) mids.push_back(0.5 * (profile[static_cast<std::size_t>(j)] + profile[static_cast<std::size_t>(n - 1 - j)]));
  for (int j = 0; j < muscles; ++j) {
    const auto at = static_cast<std::size_t>(j);
    // Thesis: A = square of the mean distance to the neighbouring muscle springs.
    double gap = 0.0;
    int count = 0;
    if (j > 0) gap += norm(mids[at] - mids[at - 1]), ++count;
    if (j + 1 < muscles) gap += norm(mids[at + 1] - mids[at]), ++count;
    gap = count > 0 ? gap / count : spacing;
    const double band = 0.5 * ((j > 0 ? norm(mids[at] - mids[at - 1]) : 0.0) + norm(mids[at + 1] - mids[at]));
    const int a = layout_.umbrella[at], b = layout_.umbrella[static_cast<std::size_t>(n - 1 - j)];
    const int spring = add_spring(a, b, k.muscle(band, gap, distance(a, b)));
    layout_.muscle_springs.push_back(spring);
    layout_.muscle_uncontracted_m.push_back(own_body_.linear.rest_length[static_cast<std::size_t>(spring)]);
    // Springs near the aperture re-expand more slowly (Fig. 7.5): exponent from p_aperture to 1.
    ContractionProfile p = spec_.profile;
    const double toward_apex = muscles > 1 ? static_cast<double>(j) / (muscles - 1) : 1.0;
    p.expansion_exponent = spec_.aperture_expansion_exponent + (1.0 - spec_.aperture_expansion_exponent) * toward_apex;
    layout_.muscle_profiles.push_back(p);
    // The impulse starts at the margin and travels toward the apex (§6.2); each spring gets half
    // of the largest delay of its band (§7.1).
    layout_.muscle_delay_s.push_back(0.5 * spec_.neural_delay_s * static_cast<double>(j) / m);
  }
  controllers_.resize(layout_.muscle_springs.size());
}

void Jellyfish::build_tentacles(int tentacle_points) {
  // Two strands hang from the aperture tips, away from the apex; a joint at each tip holds the
  // strand's angle to the aperture chord (the line to the other tip; TentacleRoot::axis) or to the
  // bell's last segment (TentacleRoot::margin, §7.1).
  if (tentacle_points <= 0) return;
  const SpringConstants k(spec_);
  const auto& u = layout_.umbrella;
  const int n = static_cast<int>(u.size());
  const double t_spacing = spec_.tentacle_length_m / tentacle_points;
  const Vec2 down = -initial_axis();
  for (int side = 0; side < 2; ++side) {
    const int tip = side == 0 ? u.front() : u.back();
    const int inner = side == 0 ? u[1] : u[static_cast<std::size_t>(n - 2)];
    const Vec2 root = own_body_.points.position[static_cast<std::size_t>(tip)];
    std::vector<int> strand{tip};
    for (int j = 1; j <= tentacle_points; ++j)
      strand.push_back(own_body_.add_point(root + (j * t_spacing) * down,
                                           k.tentacle_mass(j < tentacle_points ? t_spacing : 0.5 * t_spacing)));
    own_body_.points.mass[static_cast<std::size_t>(tip)] += k.tentacle_root_mass(0.5 * t_spacing);
    for (std::size_t j = 0; j + 1 < strand.size(); ++j)
      add_spring(strand[j], strand[j + 1], k.tentacle_spring(distance(strand[j], strand[j + 1])));
    auto joint = [&](int a, int b, int c, double kappa) {
      if (kappa > 0) own_body_.add_angular_spring(a, b, c, kappa, kNaN);
    };
    const int opposite = side == 0 ? u.back() : u.front();
    if (k.root_on_axis())
      joint(opposite, tip, strand[1], k.axis_root_joint(distance(tip, strand[1]), t_spacing));
    else
      joint(inner, tip, strand[1], k.root_joint(distance(inner, tip), distance(tip, strand[1]), t_spacing));
    for (std::size_t j = 1; j + 1 < strand.size(); ++j)
      joint(strand[j - 1], strand[j], strand[j + 1],
            k.tentacle_joint(distance(strand[j - 1], strand[j]), distance(strand[j], strand[j + 1]), t_spacing));
    layout_.tentacles.push_back(strand);
  }
}

void Jellyfish::make_ring_jellyfish(double spacing) {
  // Mirror images: umbrella k ↔ n − 1 − k (same for the mesh's outer row), left tentacle ↔ right.
  std::vector<int> partner(own_body_.points.size());
  for (std::size_t p = 0; p < partner.size(); ++p) partner[p] = static_cast<int>(p);
  auto pair_rows = [&partner](const std::vector<int>& row) {
    for (std::size_t k = 0; k < row.size(); ++k) partner[static_cast<std::size_t>(row[k])] = row[row.size() - 1 - k];
  };
  pair_rows(layout_.umbrella);
  pair_rows(layout_.exumbrella);
  if (layout_.tentacles.size() == 2)
    for (std::size_t k = 1; k < layout_.tentacles[0].size(); ++k) {
      partner[static_cast<std::size_t>(layout_.tentacles[0][k])] = layout_.tentacles[1][k];
      partner[static_cast<std::size_t>(layout_.tentacles[1][k])] = layout_.tentacles[0][k];
    }
  std::vector<std::vector<int>> rows{layout_.umbrella};
  if (!layout_.exumbrella.empty()) rows.push_back(layout_.exumbrella);
  // C = κ_l l_r of the umbrella springs (eq. 7.1's λ A, or S), per metre of the ring's circumference.
  layout_.hoop_springs = make_rings(own_body_, spec_.aperture_centre_m.x, spacing, partner, rows,
                                    layout_.muscle_springs, SpringConstants(spec_).membrane());
}

void Jellyfish::move_into(elastic::Body& shared) {
  if (body_ != &own_body_) throw std::logic_error("a jellyfish can be moved into a shared body only once");
  const auto point_offset = static_cast<int>(shared.points.size());
  first_point_ = shared.points.size();
  first_linear_ = shared.linear.size();
  first_angular_ = shared.angular.size();
  const elastic::Body& part = own_body_;
  // The coupled body ignores masses (the markers are massless, §4.3.2); a zero mass (weightless
  // tentacles) becomes a token one that the body accepts.
  for (std::size_t p = 0; p < part.points.size(); ++p)
    shared.add_point(part.points.position[p], part.points.mass[p] > 0 ? part.points.mass[p] : 1e-6);
  for (std::size_t s = 0; s < part.linear.size(); ++s)
    shared.add_linear_spring(part.linear.i[s] + point_offset, part.linear.j[s] + point_offset,
                             part.linear.stiffness[s], part.linear.rest_length[s]);
  for (std::size_t s = 0; s < part.angular.size(); ++s)
    shared.add_angular_spring(part.angular.i[s] + point_offset, part.angular.j[s] + point_offset,
                              part.angular.k[s] + point_offset, part.angular.stiffness[s], part.angular.rest_angle[s]);
  auto shift = [](std::vector<int>& indices, std::size_t by) {
    for (int& i : indices) i += static_cast<int>(by);
  };
  shift(layout_.umbrella, first_point_);
  shift(layout_.exumbrella, first_point_);
  for (std::vector<int>& strand : layout_.tentacles) shift(strand, first_point_);
  shift(layout_.muscle_springs, first_linear_);
  shift(layout_.hoop_springs, first_linear_);
  body_ = &shared;
  own_body_ = elastic::Body{};
}

Vec2 Jellyfish::heading() const {
  const auto& x = body_->points.position;
  const Vec2 aperture = 0.5 * (x[static_cast<std::size_t>(layout_.umbrella.front())] +
                               x[static_cast<std::size_t>(layout_.umbrella.back())]);
  const Vec2 axis = x[static_cast<std::size_t>(layout_.umbrella[static_cast<std::size_t>(layout_.apex)])] - aperture;
  return norm(axis) > 0 ? axis / norm(axis) : initial_axis();
}

void Jellyfish::archive(core::StateArchive& a) {
  a.value("frequency", spec_.frequency_hz);
  a.value("phase", spec_.phase_cycles);
  a.value("gamma", spec_.gamma);
  a.value("steering", spec_.steering);
  a.value("steer_target", spec_.steer_target_m);
  a.vector("controllers", controllers_);
  a.value("steer_bias", steer_bias_);
  a.value("steer_updated_phase", steer_updated_phase_);
  a.value("steer_last_heading", steer_last_heading_);
  a.value("steer_has_heading", steer_has_heading_);
}

void Jellyfish::set_frequency(double hz, double t) {
  if (!(hz > 0 && hz <= 100)) throw std::invalid_argument("frequency must be in (0, 100] Hz");
  // Keep f·t + phase continuous at time t.
  spec_.phase_cycles += (spec_.frequency_hz - hz) * t;
  spec_.frequency_hz = hz;
}

void Jellyfish::set_gamma(double gamma) {
  if (!(gamma > 0 && gamma <= 1)) throw std::invalid_argument("gamma must be in (0, 1]");
  spec_.gamma = gamma;
}

void Jellyfish::set_stiffness_scale(double scale) {
  if (!(scale > 0 && std::isfinite(scale))) throw std::invalid_argument("stiffness scale must be > 0");
  auto& linear = body_->linear.stiffness;
  for (std::size_t s = 0; s < base_stiffness_.size(); ++s) linear[first_linear_ + s] = scale * base_stiffness_[s];
  for (int m : layout_.muscle_springs) linear[static_cast<std::size_t>(m)] = base_stiffness_[static_cast<std::size_t>(m) - first_linear_];
  for (std::size_t a = 0; a < base_joint_stiffness_.size(); ++a)
    body_->angular.stiffness[first_angular_ + a] = scale * base_joint_stiffness_[a];
}

void Jellyfish::set_steer_target(std::optional<Vec2> target_m) {
  spec_.steering = target_m.has_value();
  if (target_m) spec_.steer_target_m = *target_m;
  steer_updated_phase_ = -1e300;  // choose a new bias at the next actuation
  steer_has_heading_ = false;
  if (!target_m) {
    steer_bias_ = 0.0;
    std::copy(base_rest_angle_.begin(), base_rest_angle_.end(),
              body_->angular.rest_angle.begin() + static_cast<std::ptrdiff_t>(first_angular_));
  }
}

void Jellyfish::steer(double t) {
  // The bias is chosen once per cycle, at its start, from the heading error toward the target:
  // to turn counter-clockwise (target to the left of the heading) the right side strokes harder.
  const double cycle = std::floor(spec_.frequency_hz * t + spec_.phase_cycles);
  if (cycle != steer_updated_phase_) {
    steer_updated_phase_ = cycle;
    const Vec2 h = heading();
    const auto& x = body_->points.position;
    const Vec2 aperture = 0.5 * (x[static_cast<std::size_t>(layout_.umbrella.front())] +
                                 x[static_cast<std::size_t>(layout_.umbrella.back())]);
    const Vec2 to_target = spec_.steer_target_m - aperture;
    const double error = norm(to_target) > 0 ? std::atan2(cross(h, to_target), dot(h, to_target)) : 0.0;
    // Proportional–derivative on the heading: the turn rate over the last cycle predicts where the
    // heading goes next (the wake keeps the bell turning for about a cycle after the bias changes).
    const double turned = steer_has_heading_ ? std::atan2(cross(steer_last_heading_, h), dot(steer_last_heading_, h)) : 0.0;
    steer_last_heading_ = h;
    steer_has_heading_ = true;
    const double command = spec_.steer_gain * (error - spec_.steer_damping_cycles * turned);
    steer_bias_ = std::clamp(-command, -spec_.steer_max_bend_rad, spec_.steer_max_bend_rad);
  }
  // Mean contraction of the muscles now, 0 relaxed … 1 fully contracted.
  double contraction = 0.0;
  for (std::size_t k = 0; k < layout_.muscle_springs.size(); ++k) contraction += 1.0 - muscle_activation(k, t);
  contraction /= std::max<std::size_t>(1, layout_.muscle_springs.size());
  // The umbrella turns clockwise from the left tip to the right one (negative turning angles):
  // bending a side inward makes its joints' rest angles more negative.
  // The bias is the whole side's extra bend, shared evenly by its joints.
  const double joints_per_side = std::max(1.0, static_cast<double>(layout_.apex) - 1.0);
  const double per_joint = std::abs(steer_bias_) * contraction / joints_per_side;
  for (std::size_t a = 0; a < base_rest_angle_.size(); ++a) {
    const int side = joint_side_[a];
    const bool active = (side < 0 && steer_bias_ > 0) || (side > 0 && steer_bias_ < 0);
    body_->angular.rest_angle[first_angular_ + a] = base_rest_angle_[a] - (active ? per_joint : 0.0);
  }
}

double Jellyfish::muscle_activation(std::size_t k, double t) const {
  const double phase = spec_.frequency_hz * (t - layout_.muscle_delay_s[k]) + spec_.phase_cycles;
  return contraction_value(layout_.muscle_profiles[k], phase);
}

void Jellyfish::actuate(double t) {
  for (std::size_t k = 0; k < layout_.muscle_springs.size(); ++k) {
    const auto spring = static_cast<std::size_t>(layout_.muscle_springs[k]);
    const double l_ru = layout_.muscle_uncontracted_m[k];
    if (spec_.closed_loop) {
      const auto& x = body_->points.position;
      const double length = norm(x[static_cast<std::size_t>(body_->linear.j[spring])] - x[static_cast<std::size_t>(body_->linear.i[spring])]);
      body_->linear.rest_length[spring] =
          controllers_[k].update(t - layout_.muscle_delay_s[k] + spec_.phase_cycles / spec_.frequency_hz, length, l_ru,
                                 body_->linear.rest_length[spring], spec_.gamma, spec_.frequency_hz,
                                 spec_.profile.contract_fraction);
    } else {
      body_->linear.rest_length[spring] = contracted_rest_length(l_ru, spec_.gamma, muscle_activation(k, t));
    }
  }
  if (spec_.steering || steer_bias_ != 0.0) steer(t);
}

std::vector<Vec2> Jellyfish::umbrella_points() const {
  std::vector<Vec2> p;
  for (int i : layout_.umbrella) p.push_back(body_->points.position[static_cast<std::size_t>(i)]);
  return p;
}

SliceFrame Jellyfish::slice_frame(double t) const {
  SliceFrame f;
  f.time_s = t;
  f.umbrella = umbrella_points();
  for (const auto& strand : layout_.tentacles) {
    std::vector<Vec2> line;
    for (int i : strand) line.push_back(body_->points.position[static_cast<std::size_t>(i)]);
    f.tentacles.push_back(std::move(line));
  }
  const int n = static_cast<int>(f.umbrella.size());
  for (std::size_t k = 0; k < layout_.muscle_springs.size(); ++k) {
    const int a = static_cast<int>(k), b = n - 1 - static_cast<int>(k);
    const double length = norm(f.umbrella[static_cast<std::size_t>(b)] - f.umbrella[static_cast<std::size_t>(a)]);
    const auto spring = static_cast<std::size_t>(layout_.muscle_springs[k]);
    const double tension = body_->linear.stiffness[spring] * (length - body_->linear.rest_length[spring]);
    f.muscles.push_back({a, b, length, layout_.muscle_uncontracted_m[k], tension});
  }
  f.thickness_m = spec_.thickness_m;
  const Vec2 aperture = 0.5 * (f.umbrella.front() + f.umbrella.back());
  const Vec2 axis = f.umbrella[static_cast<std::size_t>(layout_.apex)] - aperture;
  f.axis = norm(axis) > 0 ? axis / norm(axis) : initial_axis();
  return f;
}

}  // namespace jellysim::jellyfish
