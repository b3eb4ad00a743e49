#include "jellysim/jellyfish/ib2d_object.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace jellysim::jellyfish {

std::string_view to_string(ScheduleLaw law) {
  switch (law) {
    case ScheduleLaw::constant: return "constant";
    case ScheduleLaw::abs_cos: return "abs-cos";
    case ScheduleLaw::sine: return "sine";
    case ScheduleLaw::stroke: return "stroke";
  }
  return "unknown";
}

std::optional<ScheduleLaw> schedule_law_from_string(std::string_view name) {
  for (ScheduleLaw l : {ScheduleLaw::constant, ScheduleLaw::abs_cos, ScheduleLaw::sine, ScheduleLaw::stroke})
    if (to_string(l) == name) return l;
  return std::nullopt;
}

double SpringSchedule::value(double t) const {
  switch (law) {
    case ScheduleLaw::constant: return amplitude;
    case ScheduleLaw::abs_cos: return amplitude * std::abs(std::cos(std::numbers::pi * frequency_hz * t));
    case ScheduleLaw::sine: return mean + amplitude * std::sin(2.0 * std::numbers::pi * frequency_hz * t);
    case ScheduleLaw::stroke:
      return contracted_rest_length(amplitude, gamma, contraction_value(profile, frequency_hz * t));
  }
  return amplitude;
}

double SpringSchedule::largest() const {
  return law == ScheduleLaw::sine ? mean + std::abs(amplitude) : std::abs(amplitude);
}

void validate(const Ib2dObjectSpec& spec) {
  const int springs = static_cast<int>(spec.structure.springs.size());
  for (std::size_t k = 0; k < spec.schedules.size(); ++k) {
    const SpringSchedule& s = spec.schedules[k];
    const std::string where = spec.name + ": schedules[" + std::to_string(k) + "]";
    if (s.first < 0 || s.last < s.first || s.last >= springs)
      throw std::invalid_argument(where + ": springs [" + std::to_string(s.first + 1) + ", " +
                                  std::to_string(s.last + 1) + "] must be rows of the .spring file, in [1, " +
                                  std::to_string(springs) + "], first ≤ last");
    // A rest length or stiffness must not go negative (a sine may only swing above zero).
    if (s.law == ScheduleLaw::sine && s.mean - std::abs(s.amplitude) < 0.0)
      throw std::invalid_argument(where + ": a sine schedule needs mean ≥ |amplitude| (the value must stay ≥ 0)");
    if (s.law != ScheduleLaw::sine && s.amplitude < 0.0)
      throw std::invalid_argument(where + ": amplitude must be ≥ 0");
    if (s.law == ScheduleLaw::stroke && !(s.gamma > 0.0 && s.gamma <= 1.0))
      throw std::invalid_argument(where + ": gamma must lie in (0, 1]");
  }
}

Ib2dParts add_ib2d_object(const Ib2dObjectSpec& spec, double ds, elastic::Body& body) {
  const elastic::Ib2dStructure& st = spec.structure;
  Ib2dParts parts;
  parts.first_point = static_cast<int>(body.points.size());
  parts.vertex_count = static_cast<int>(st.vertices.size());
  parts.ds_m = ds;
  // Markers are massless in the coupling (their mass is the fluid's); the nominal mass is unused.
  for (Vec2 v : st.vertices) body.add_point(v + spec.offset_m, 1e-3);
  auto point = [&](int v) { return parts.first_point + v; };
  for (const elastic::Ib2dSpring& s : st.springs) {
    if (s.degree == 1.0) {
      parts.spring.push_back(static_cast<int>(body.linear.size()));
      parts.power_spring.push_back(-1);
      body.add_linear_spring(point(s.master), point(s.slave), s.stiffness * ds, s.rest_length);
    } else {
      parts.spring.push_back(-1);
      parts.power_spring.push_back(static_cast<int>(body.power.size()));
      body.add_power_spring(point(s.master), point(s.slave), s.stiffness * ds, s.rest_length, s.degree);
    }
  }
  for (const elastic::Ib2dSpring& s : st.damped_springs) {
    body.add_linear_spring(point(s.master), point(s.slave), s.stiffness * ds, s.rest_length);
    if (s.damping > 0.0) body.add_dashpot(point(s.master), point(s.slave), s.damping * ds);
  }
  for (const elastic::Ib2dBeam& b : st.beams)
    body.add_torsional_beam(point(b.left), point(b.middle), point(b.right), b.stiffness * ds, b.curvature);
  for (const elastic::Ib2dNonInvariantBeam& b : st.non_invariant_beams)
    body.add_non_invariant_beam(point(b.left), point(b.middle), point(b.right), b.stiffness * ds, b.curvature);
  // Target points: the vertex stays a marker, tied by a zero-length spring to a pinned anchor
  // where it starts, F = k (X_target − X) (IB2d's target law).
  for (const elastic::Ib2dTarget& t : st.targets) {
    const int anchor = body.add_point(body.points.position[static_cast<std::size_t>(point(t.point))], 1e-3,
                                      elastic::PointKind::Pinned);
    parts.tethers.push_back(static_cast<int>(body.linear.size()));
    body.add_linear_spring(point(t.point), anchor, t.stiffness * ds, 0.0);
  }
  return parts;
}

void actuate_schedules(const Ib2dObjectSpec& spec, const Ib2dParts& parts, double t, elastic::Body& body) {
  for (const SpringSchedule& s : spec.schedules) {
    const double v = s.value(t);
    for (int r = s.first; r <= s.last; ++r) {
      const std::size_t row = static_cast<std::size_t>(r);
      if (const int l = parts.spring[row]; l >= 0) {
        (s.stiffness ? body.linear.stiffness : body.linear.rest_length)[static_cast<std::size_t>(l)] =
            s.stiffness ? v * parts.ds_m : v;
      } else {
        const std::size_t p = static_cast<std::size_t>(parts.power_spring[row]);
        (s.stiffness ? body.power.stiffness : body.power.rest_length)[p] = s.stiffness ? v * parts.ds_m : v;
      }
    }
  }
}

void set_strain_references(const Ib2dObjectSpec& spec, const Ib2dParts& parts, std::vector<double>& reference) {
  for (const SpringSchedule& s : spec.schedules) {
    if (s.stiffness) continue;
    for (int r = s.first; r <= s.last; ++r)
      if (const int l = parts.spring[static_cast<std::size_t>(r)]; l >= 0)
        reference[static_cast<std::size_t>(l)] = s.largest();
  }
}

}  // namespace jellysim::jellyfish
