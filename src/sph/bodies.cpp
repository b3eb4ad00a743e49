#include "jellysim/sph/bodies.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace jellysim::sph {

CollisionOutline strip_outline(int segments) {
  std::vector<int> loop;
  for (int c = 0; c <= segments; ++c) loop.push_back(segments + 1 + c);
  for (int c = segments; c >= 0; --c) loop.push_back(c);
  CollisionOutline outline;
  outline.add_loop(loop);
  return outline;
}

namespace {

void require(bool ok, const char* field, double value, const char* range) {
  if (ok) return;
  std::ostringstream m;
  m << "larva." << field << " = " << value << " is out of range " << range;
  throw std::invalid_argument(m.str());
}

void validate(const LarvaSpec& s) {
  require(s.length_m > 0.0 && std::isfinite(s.length_m), "length", s.length_m, "(0, inf)");
  require(s.height_m > 0.0 && std::isfinite(s.height_m), "height", s.height_m, "(0, inf)");
  require(s.segments >= 2 && s.segments <= 1000, "segments", s.segments, "[2, 1000]");
  require(s.point_mass_kg > 0.0 && std::isfinite(s.point_mass_kg), "point_mass", s.point_mass_kg, "(0, inf)");
  require(s.stiffness > 0.0 && std::isfinite(s.stiffness), "stiffness", s.stiffness, "(0, inf)");
  require(s.muscle_stiffness >= 0.0 && std::isfinite(s.muscle_stiffness), "muscle_stiffness", s.muscle_stiffness,
          "[0, inf)");
  require(s.contraction >= 0.0 && s.contraction <= 0.9, "contraction", s.contraction, "[0, 0.9]");
  require(s.frequency_hz >= 0.0 && std::isfinite(s.frequency_hz), "frequency", s.frequency_hz, "[0, inf)");
  require(std::isfinite(s.wave_cells), "wave_cells", s.wave_cells, "(-inf, inf)");
}

}  // namespace

Larva make_larva(const LarvaSpec& spec) {
  validate(spec);
  elastic::BarSpec bar;
  bar.length = spec.length_m;
  bar.width = spec.height_m;
  bar.segments = spec.segments;
  bar.point_mass = spec.point_mass_kg;
  bar.stiffness = spec.stiffness;
  bar.gravity = {0.0, 0.0};
  bar.pivot = spec.centre + Vec2{-0.5 * spec.length_m, 0.5 * spec.height_m};
  Larva larva;
  larva.body = elastic::make_bar(bar);
  larva.body.points.kind[0] = elastic::PointKind::Free;  // make_bar pins its first point
  larva.outline = strip_outline(spec.segments);
  const int n = spec.segments;
  std::vector<double> rest;
  std::vector<int> cell;
  std::vector<bool> top;
  for (int c = 0; c + 2 <= n; ++c) {
    for (bool upper : {true, false}) {
      const int a = upper ? c : n + 1 + c;
      larva.muscle_springs.push_back(static_cast<int>(larva.body.linear.size()));
      larva.body.add_linear_spring(a, a + 2, spec.muscle_stiffness);
      rest.push_back(larva.body.linear.rest_length.back());
      cell.push_back(c);
      top.push_back(upper);
    }
  }
  const std::vector<int> springs = larva.muscle_springs;
  larva.muscles = [spec, springs, rest, cell, top](double t, elastic::Body& body) {
    for (std::size_t k = 0; k < springs.size(); ++k) {
      const double phase = 2.0 * std::numbers::pi * (spec.frequency_hz * t - cell[k] * spec.wave_cells);
      const double activation = 0.5 * (1.0 + (top[k] ? 1.0 : -1.0) * std::sin(phase));
      body.linear.rest_length[static_cast<std::size_t>(springs[k])] = rest[k] * (1.0 - spec.contraction * activation);
    }
  };
  return larva;
}

}  // namespace jellysim::sph
