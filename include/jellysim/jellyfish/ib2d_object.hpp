#pragma once
// An IB2d structure in the tank (scene objects of type "ib2d"): its vertices become markers, its
// springs, beams and targets our force laws (elastic/forces.hpp), its time-dependent springs (IB2d's
// update_Springs.m) a schedule given as data. IB2d's laws give force densities per unit length;
// a marker's force is that times the marker spacing ds (IB2d spreads f·ds), so every stiffness is
// multiplied by ds here. Knows nothing of files.
#include <string>
#include <vector>

#include "jellysim/elastic/body.hpp"
#include "jellysim/elastic/ib2d_structure.hpp"
#include "jellysim/jellyfish/contraction.hpp"

namespace jellysim::jellyfish {

/// How a scheduled spring column changes with time t (a small fixed menu).
enum class ScheduleLaw {
  constant,  ///< value = amplitude
  abs_cos,   ///< value = amplitude |cos(π f t)| (IB2d's jellyfish: full contraction at t = ½f, 3/2f, …)
  sine,      ///< value = mean + amplitude sin(2π f t)
  stroke,    ///< value = amplitude (γ + (1 − γ) Q(f t)): the thesis's contraction (eq. 7.5, our Hermite stroke)
};
std::string_view to_string(ScheduleLaw law);
std::optional<ScheduleLaw> schedule_law_from_string(std::string_view name);

/// A column of a run of springs of the .spring file, set from a law of t before every force evaluation.
struct SpringSchedule {
  int first = 0, last = 0;  ///< springs first … last (0-based rows of the .spring file), inclusive
  bool stiffness = false;   ///< false: the rest length (m); true: the stiffness (IB2d units)
  ScheduleLaw law = ScheduleLaw::abs_cos;
  double frequency_hz = 1.0;
  double amplitude = 1.0;
  double mean = 0.0;        ///< sine only
  double gamma = 0.5;       ///< stroke only: contracted fraction
  ContractionProfile profile{};  ///< stroke only
  /// The column's value at time t.
  double value(double t) const;
  /// The largest value the law takes (the rest length structural checks measure strain against).
  double largest() const;
};

struct Ib2dObjectSpec {
  std::string name;   ///< for messages ("objects[0] (ib2d)")
  elastic::Ib2dStructure structure;
  Vec2 offset_m{};    ///< added to every vertex
  std::vector<SpringSchedule> schedules;
  std::vector<std::string> files;  ///< the IB2d files it was read from (none for a generated model)
};

/// Checks indices of the schedules against the structure; throws std::invalid_argument naming them.
void validate(const Ib2dObjectSpec& spec);

/// Where an IB2d structure's parts live in the coupled body.
struct Ib2dParts {
  int first_point = 0;           ///< vertex v is body point first_point + v
  int vertex_count = 0;
  std::vector<int> spring;       ///< per .spring row: its index in body.linear, or −1 (a power spring)
  std::vector<int> power_spring; ///< per .spring row: its index in body.power, or −1
  std::vector<int> tethers;      ///< per target: the zero-length spring in body.linear tying it to its anchor
  double ds_m = 0.0;             ///< marker spacing the stiffnesses were scaled by
};

/// Adds the structure's markers, springs, beams and targets (each a pinned anchor where the vertex
/// starts and a zero-length spring of stiffness k·ds) to `body`.
Ib2dParts add_ib2d_object(const Ib2dObjectSpec& spec, double ds_m, elastic::Body& body);

/// Sets the scheduled springs for time t.
void actuate_schedules(const Ib2dObjectSpec& spec, const Ib2dParts& parts, double t, elastic::Body& body);

/// The strain reference of the scheduled springs (their largest rest length), the others' own.
void set_strain_references(const Ib2dObjectSpec& spec, const Ib2dParts& parts, std::vector<double>& reference);

}  // namespace jellysim::jellyfish
