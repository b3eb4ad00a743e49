#include "jellysim/shell/shell_bell.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace jellysim::shell {

namespace {

void require(bool ok, const std::string& field, const std::string& range) {
  if (!ok) throw std::invalid_argument("shell bell: field '" + field + "' is out of range " + range);
}

constexpr double kPi = std::numbers::pi;

}  // namespace

void validate(const ShellBellSpec& s) {
  jellyfish::validate(s.slice);
  require(s.target_edge_m > 0 && s.target_edge_m >= 1e-3 * s.slice.diameter_m && s.target_edge_m <= 0.5 * s.slice.diameter_m,
          "target_edge", "[diameter/1000, diameter/2] m");
  require(s.poisson_ratio > -1.0 && s.poisson_ratio <= 0.5, "poisson_ratio", "(-1, 0.5]");
  require(s.radial_muscle_n_per_m >= 0 && std::isfinite(s.radial_muscle_n_per_m), "radial_muscle", "[0, inf) N/m");
  require(s.conduction_speed_m_per_s >= 0, "conduction_speed", "[0, inf] m/s (0: the slice's)");
  require(s.tentacle_count >= 0 && s.tentacle_count <= 1000, "tentacle_count", "[0, 1000]");
}

ShellBell::ShellBell(const ShellBellSpec& spec) : spec_(spec) {
  validate(spec_);
  material_ = shell_material_from_continuum(spec_.slice.material, spec_.poisson_ratio);
  surface_ = bell_mesh(spec_.slice.diameter_m, spec_.slice.height_m, spec_.target_edge_m);
  body_ = make_shell_body(surface_.mesh, material_, spec_.bending);
  rest_ = stack(surface_.mesh.vertices);
  // Arc fractions: the meridian's points are evenly spaced in arc, ring j is point j + 1 of K.
  const auto& rings = surface_.rings;
  const double K = static_cast<double>(rings.first.size());
  arc_fraction_.assign(surface_.mesh.vertices.size(), 1.0);
  for (std::size_t j = 0; j < rings.first.size(); ++j)
    for (int i = 0; i < rings.count[j]; ++i) arc_fraction_[static_cast<std::size_t>(rings.first[j] + i)] = 1.0 - (static_cast<double>(j) + 1.0) / K;
  const std::vector<Vec2> fine = jellyfish::bell_profile(spec_.slice.diameter_m, spec_.slice.height_m, 256);
  for (std::size_t i = 0; i < 256; ++i) meridian_arc_ += norm(fine[i + 1] - fine[i]);
  const double tau = spec_.slice.neural_delay_s;
  conduction_speed_ = spec_.conduction_speed_m_per_s > 0 ? spec_.conduction_speed_m_per_s
                      : tau > 0                          ? meridian_arc_ / tau
                                                         : std::numeric_limits<double>::infinity();
  build_muscles();
  build_tentacles();
  actuate(0.0);
}

double ShellBell::margin_delay_s(double azimuth) const {
  if (!spec_.pacemaker) return 0.0;
  double d = std::remainder(azimuth - spec_.pacemaker_azimuth_rad, 2.0 * kPi);  // in [−π, π]
  return 0.5 * spec_.slice.diameter_m * std::abs(d) / conduction_speed_;
}

void ShellBell::add_muscle(std::size_t face, const Vec3& direction, double stiffness, std::vector<std::size_t>& into) {
  const auto& t = surface_.mesh.triangles[face];
  auto at = [&](int v) { return surface_.mesh.vertices[static_cast<std::size_t>(v)]; };
  body_.fibres.push_back(make_fibre(at(t[0]), at(t[1]), at(t[2]), t, direction, stiffness));
  into.push_back(body_.fibres.size() - 1);
  // Fig. 7.5 and §6.2 as the slice has them, by the face's arc fraction s toward the apex.
  double s = 0.0;
  for (int v : t) s += arc_fraction_[static_cast<std::size_t>(v)] / 3.0;
  const Vec3 c = (at(t[0]) + at(t[1]) + at(t[2])) / 3.0;
  jellyfish::ContractionProfile p = spec_.slice.profile;
  p.expansion_exponent = spec_.slice.aperture_expansion_exponent + (1.0 - spec_.slice.aperture_expansion_exponent) * s;
  profile_.push_back(p);
  delay_.push_back(margin_delay_s(std::atan2(c.z(), c.x())) + 0.5 * spec_.slice.neural_delay_s * s);
}

void ShellBell::build_muscles() {
  const auto& mesh = surface_.mesh;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    if (std::find(t.begin(), t.end(), surface_.rings.apex) != t.end()) continue;  // the slice's muscles stop short of the apex
    auto at = [&](int v) { return mesh.vertices[static_cast<std::size_t>(v)]; };
    const Vec3 c = (at(t[0]) + at(t[1]) + at(t[2])) / 3.0;
    const double phi = std::atan2(c.z(), c.x());
    const Vec3 around(-std::sin(phi), 0.0, std::cos(phi));
    add_muscle(f, around, spec_.slice.material.muscle_n_per_m2, coronal_);
    if (spec_.radial_muscle_n_per_m > 0) {
      const Vec3 normal = (at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0]));
      add_muscle(f, around.cross(normal), spec_.radial_muscle_n_per_m, radial_);
    }
  }
}

double ShellBell::activation(std::size_t k, double t) const {
  const double phase = spec_.slice.frequency_hz * (t - delay_[k]) + spec_.slice.phase_cycles;
  return jellyfish::contraction_value(profile_[k], phase);
}

void ShellBell::actuate(double t) {
  for (std::size_t k = 0; k < body_.fibres.size(); ++k)
    body_.fibres[k].rest_stretch = jellyfish::contracted_rest_length(1.0, spec_.slice.gamma, activation(k, t));
}

double ShellBell::cavity_volume(const Vector& x) const {
  return enclosed_volume(unstack(x.head(3 * static_cast<Eigen::Index>(surface_.mesh.vertices.size()))), surface_.mesh);
}

double margin_displacement(const ShellBell& bell, const Vector& x, double azimuth_rad, double half_width_rad) {
  const Rings& r = bell.surface().rings;
  const std::size_t margin = r.first.size() - 1;
  const double turn = 2.0 * std::numbers::pi;
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < r.count[margin]; ++i) {
    const double azimuth = turn * (i + r.offset[margin]) / r.count[margin];
    if (std::abs(std::remainder(azimuth - azimuth_rad, turn)) > half_width_rad + 1e-9) continue;
    sum += axial_radius(x, r.first[margin] + i) - r.radius_m[margin];
    ++count;
  }
  if (count == 0) throw std::invalid_argument("margin_displacement: no margin vertex within the half width");
  return sum / count;
}

}  // namespace jellysim::shell
