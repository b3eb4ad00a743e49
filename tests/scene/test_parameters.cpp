// The scene layer's parameter tables: the generated files are current, every default is allowed,
// every bound is enforced with a message naming the field and the range, the physics structs'
// defaults are the built-in scene, and the viewer's live parameters are table entries.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "scene_test_util.hpp"
#include "jellysim/core/errors.hpp"
#include "jellysim/scene/experiment_scenes.hpp"
#include "jellysim/scene/jellyfish_scene.hpp"
#include "jellysim/scene/live_parameters.hpp"
#include "jellysim/scene/objects.hpp"
#include "jellysim/scene/particle_scenes.hpp"
#include "jellysim/scene/reference.hpp"
#include "jellysim/scene/render_settings.hpp"
#include "jellysim/scene/study_scenes.hpp"

namespace {

using namespace jellysim;
using jellysim::testing::error_of;
using jellysim::testing::read_source_file;
using scene::Parameter;
using scene::ParameterTable;
using scene::Type;

const std::vector<const ParameterTable*>& tables() {
  static const std::vector<const ParameterTable*> all{&scene::jellyfish_scene(), &scene::render_parameters(),
                                                      &scene::viewer_controls(), &scene::driven_cavity_scene(),
                                                      &scene::oval_membrane_scene(), &scene::taylor_green_scene(),
                                                      &scene::solver_cost_scene(), &scene::integrator_order_scene(),
                                                      &scene::stages_scene()};
  return all;
}

/// Reads `key` of `config` by its type through the table (throws what the readers throw).
void read_by_type(const scene::Reader& r, const Parameter& p) {
  switch (p.type) {
    case Type::number: r.number(p.key); break;
    case Type::integer: r.integer(p.key); break;
    case Type::vec2: r.vec2(p.key); break;
    default: r.validate_all();
  }
}

TEST(SceneParameters, ReferencePageIsCurrent) {
  EXPECT_EQ(read_source_file("docs/parameters.md"), scene::parameters_reference())
      << "docs/parameters.md is stale: build/release/jellysim scenes --reference > docs/parameters.md";
}

TEST(SceneParameters, DefinitionFilesAreTheirTables) {
  for (const auto& [path, name] : {std::pair{"scenes/jellyfish.toml", "jellyfish"},
                                   {"experiments/driven-cavity.toml", "driven-cavity"},
                                   {"experiments/oval-membrane.toml", "oval-membrane"},
                                   {"experiments/taylor-green.toml", "taylor-green"},
                                   {"experiments/solver-cost.toml", "solver-cost"},
                                   {"experiments/integrator-order.toml", "integrator-order"}}) {
    const ParameterTable* table = scene::table_for_definition(path);
    ASSERT_NE(table, nullptr) << path;
    EXPECT_EQ(read_source_file(path), table->scene_toml())
        << path << " is stale: build/release/jellysim scenes " << name << " > " << path;
  }
  EXPECT_EQ(scene::table_for_definition("experiments/kinematics.toml"), nullptr);
}

TEST(SceneParameters, EveryDefaultIsAllowedAndReadable) {
  for (const ParameterTable* t : tables()) {
    const config::Config defaults = t->defaults();
    EXPECT_NO_THROW(scene::Reader(defaults, *t).validate_all()) << t->name();
    for (const Parameter& p : t->parameters()) {
      EXPECT_TRUE(defaults.has(p.key)) << p.key;
      EXPECT_FALSE(p.description.empty()) << p.key;
      if (p.slider.defined()) {
        EXPECT_TRUE(p.range.contains(p.slider.min) && p.range.contains(p.slider.max)) << p.key;
      }
    }
  }
  EXPECT_NO_THROW(scene::read_swim_settings(scene::jellyfish_scene().defaults()));
  EXPECT_NO_THROW(scene::read_render_settings(scene::render_parameters().defaults()));
}

// Every finite bound of every number and integer parameter is enforced, and the message names the
// field and the allowed range.
TEST(SceneParameters, EveryBoundIsEnforcedWithTheFieldAndRangeNamed) {
  int checked = 0;
  for (const ParameterTable* t : tables()) {
    for (const Parameter& p : t->parameters()) {
      if (p.type != Type::number && p.type != Type::integer) continue;
      auto step = [&](double bound) { return p.type == Type::integer ? 1.0 : std::max(1e-9, 1e-6 * std::abs(bound)); };
      std::vector<double> outside;
      if (std::isfinite(p.range.min)) outside.push_back(p.range.min_open ? p.range.min : p.range.min - step(p.range.min));
      if (std::isfinite(p.range.max)) outside.push_back(p.range.max_open ? p.range.max : p.range.max + step(p.range.max));
      for (double v : outside) {
        config::Config c = t->defaults();
        std::ostringstream value;
        value.precision(17);
        if (p.type == Type::integer) value << static_cast<long long>(v);
        else value << v;
        if (p.type == Type::number && value.str().find_first_of(".e") == std::string::npos) value << ".0";
        c.set(p.key + "=" + value.str());
        const std::string message = error_of([&] { read_by_type(scene::Reader(c, *t), p); });
        EXPECT_NE(message.find(p.key), std::string::npos) << p.key << " = " << v << ": " << message;
        EXPECT_NE(message.find(p.range.describe()), std::string::npos) << p.key << ": " << message;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 60);
}

TEST(SceneParameters, ArraysNeedTheirLengthAndChoicesTheirValues) {
  const ParameterTable& t = scene::jellyfish_scene();
  for (const char* bad : {"tank.cells=[96]", "tank.cells=[96, 128, 4]", "tank.cells=[3, 128]",
                          "tank.boundaries=[\"free-slip\"]", "tank.boundaries=[\"wall\", \"free-slip\", "
                          "\"free-slip\", \"free-slip\"]", "tank.solver=\"lbm\""}) {
    config::Config c = t.defaults();
    c.set(bad);
    const std::string key = std::string(bad).substr(0, std::string(bad).find('='));
    const std::string message = error_of([&] { scene::read_swim_settings(c); });
    EXPECT_NE(message.find(key), std::string::npos) << bad << ": " << message;
  }
}

TEST(SceneParameters, TheSceneFileCommentsGiveUnitAndRange) {
  const std::string toml = scene::jellyfish_scene().scene_toml();
  EXPECT_NE(toml.find("frequency = 0.7                # Hz, (0, 5]: contractions per second"), std::string::npos) << toml;
  EXPECT_NE(toml.find("solver = \"semi-lagrangian\"     # eulerian | semi-lagrangian:"), std::string::npos);
}

// The physics structs' defaults are the built-in scene (they disagreed once: TankSpec defaulted to
// the semi-Lagrangian solver and multigrid while the scene said Eulerian and FFT).
TEST(SceneParameters, SpecDefaultsAreTheBuiltInScene) {
  const jellyfish::SwimSettings scene = scene::read_swim_settings(scene::jellyfish_scene().defaults());
  const jellyfish::SwimSettings structs;
  const coupling::TankSpec& a = scene.tank;
  const coupling::TankSpec& b = structs.tank;
  EXPECT_EQ(a.width_m, b.width_m);
  EXPECT_EQ(a.height_m, b.height_m);
  EXPECT_EQ(a.cells_x, b.cells_x);
  EXPECT_EQ(a.cells_y, b.cells_y);
  EXPECT_EQ(a.solver, b.solver);
  EXPECT_EQ(a.pressure_solver, b.pressure_solver);
  EXPECT_EQ(a.pressure_tolerance, b.pressure_tolerance);
  EXPECT_EQ(a.viscosity_m2_per_s, b.viscosity_m2_per_s);
  EXPECT_EQ(a.density_kg_per_m3, b.density_kg_per_m3);
  EXPECT_EQ(a.boundaries.west.type, b.boundaries.west.type);
  EXPECT_EQ(a.boundaries.north.type, b.boundaries.north.type);
  EXPECT_EQ(a.tracers_per_side, b.tracers_per_side);
  EXPECT_EQ(a.symmetry, b.symmetry);
  EXPECT_EQ(a.half_tank, b.half_tank);
  EXPECT_DOUBLE_EQ(scene.duration_s, structs.duration_s);
  EXPECT_DOUBLE_EQ(scene.frame_interval_s, structs.frame_interval_s);

  ASSERT_EQ(scene.school.size(), 1u);
  const jellyfish::JellyfishSpec& j = scene.jellyfish();
  const jellyfish::JellyfishSpec k;
  EXPECT_EQ(j.aperture_centre_m.x, k.aperture_centre_m.x);
  EXPECT_EQ(j.aperture_centre_m.y, k.aperture_centre_m.y);
  EXPECT_EQ(j.tilt_rad, k.tilt_rad);
  EXPECT_EQ(j.diameter_m, k.diameter_m);
  EXPECT_EQ(j.height_m, k.height_m);
  EXPECT_EQ(j.tentacle_length_m, k.tentacle_length_m);
  EXPECT_EQ(j.thickness_m, k.thickness_m);
  EXPECT_DOUBLE_EQ(j.max_spacing_m, k.max_spacing_m);
  EXPECT_EQ(j.min_segments_per_side, k.min_segments_per_side);
  EXPECT_EQ(j.model, k.model);
  EXPECT_EQ(j.elastic_model, k.elastic_model);
  EXPECT_EQ(j.material.stretching_n_per_m, k.material.stretching_n_per_m);
  EXPECT_EQ(j.material.bending_n_m, k.material.bending_n_m);
  EXPECT_EQ(j.material.muscle_n_per_m2, k.material.muscle_n_per_m2);
  EXPECT_EQ(j.material.tentacle_stretching_n_per_m, k.material.tentacle_stretching_n_per_m);
  EXPECT_EQ(j.material.tentacle_bending_n_m, k.material.tentacle_bending_n_m);
  EXPECT_EQ(j.material.line_density_kg_per_m2, k.material.line_density_kg_per_m2);
  EXPECT_EQ(j.material.tentacle_line_density_kg_per_m2, k.material.tentacle_line_density_kg_per_m2);
  EXPECT_EQ(j.bell_modulus_pa, k.bell_modulus_pa);
  EXPECT_EQ(j.muscle_modulus_pa, k.muscle_modulus_pa);
  EXPECT_EQ(j.bending_factor, k.bending_factor);
  EXPECT_EQ(j.tentacle_volume_fraction, k.tentacle_volume_fraction);
  EXPECT_EQ(j.tentacle_bending_factor, k.tentacle_bending_factor);
  EXPECT_EQ(j.frequency_hz, k.frequency_hz);
  EXPECT_EQ(j.gamma, k.gamma);
  EXPECT_EQ(j.profile.shape, k.profile.shape);
  EXPECT_EQ(j.profile.contract_fraction, k.profile.contract_fraction);
  EXPECT_EQ(j.profile.trochoid_skew, k.profile.trochoid_skew);
  EXPECT_EQ(j.aperture_expansion_exponent, k.aperture_expansion_exponent);
  EXPECT_EQ(j.neural_delay_s, k.neural_delay_s);
  EXPECT_EQ(j.closed_loop, k.closed_loop);
  EXPECT_EQ(j.controller_alpha, k.controller_alpha);
  EXPECT_EQ(j.phase_cycles, k.phase_cycles);
  EXPECT_EQ(j.steering, k.steering);
  EXPECT_EQ(j.steer_target_m.x, k.steer_target_m.x);
  EXPECT_EQ(j.steer_target_m.y, k.steer_target_m.y);
  EXPECT_EQ(j.steer_gain, k.steer_gain);
  EXPECT_DOUBLE_EQ(j.steer_max_bend_rad, k.steer_max_bend_rad);
  EXPECT_EQ(j.steer_damping_cycles, k.steer_damping_cycles);
  EXPECT_EQ(j.noise_seed, k.noise_seed);

  const coupling::CouplingSettings& c = scene.coupling;
  const coupling::CouplingSettings d;
  EXPECT_EQ(c.scheme, d.scheme);
  EXPECT_EQ(c.kernel, d.kernel);
  EXPECT_EQ(c.safety_factor, d.safety_factor);
  EXPECT_DOUBLE_EQ(c.max_time_step_s, d.max_time_step_s);
  EXPECT_EQ(c.min_time_step_s, d.min_time_step_s);
  EXPECT_EQ(c.krylov_tolerance, d.krylov_tolerance);
  EXPECT_EQ(c.krylov_max_iterations, d.krylov_max_iterations);
  EXPECT_EQ(c.preconditioner, d.preconditioner);
  EXPECT_EQ(c.mobility_rebuild_cells, d.mobility_rebuild_cells);
  EXPECT_EQ(scene.limits.max_speed_m_per_s, structs.limits.max_speed_m_per_s);
  EXPECT_EQ(scene.limits.max_strain, structs.limits.max_strain);
  EXPECT_DOUBLE_EQ(scene.limits.max_bend_rad, structs.limits.max_bend_rad);
}

TEST(SceneParameters, LiveParametersAreTableEntriesWithSliders) {
  EXPECT_EQ(scene::live_parameter("frequency").parameter->key, "jellyfish.frequency");
  EXPECT_EQ(scene::live_parameter("viscosity").parameter->key, "tank.viscosity");
  EXPECT_EQ(scene::live_parameter("noise.unstructured").parameter->key, "render.noise.unstructured_weight");
  for (const scene::LiveParameter& l : scene::live_parameters()) {
    EXPECT_TRUE(l.parameter->slider.defined()) << l.name;
    EXPECT_EQ(scene::check_live_value(l, l.parameter->slider.min), "") << l.name;
    EXPECT_EQ(scene::check_live_value(l, l.parameter->slider.max), "") << l.name;
  }
  // The viewer and a scene file allow the same frequencies.
  EXPECT_EQ(scene::check_live_value(scene::live_parameter("frequency"), 5.0), "");
  EXPECT_EQ(scene::check_live_value(scene::live_parameter("frequency"), 5.5), "frequency must be in (0, 5], got 5.5");
  config::Config c = scene::jellyfish_scene().defaults();
  c.set("jellyfish.frequency=5.5");
  EXPECT_NE(error_of([&] { scene::read_swim_settings(c); }).find("(0, 5]"), std::string::npos);
  EXPECT_THROW(scene::live_parameter("colour"), InputError);
}

// The [[objects]] tables' documented defaults are what the readers leave when a field is absent
// (the specs' own defaults): an object giving every default reads the same as one giving none.
std::string with_every_default(const std::string& type, std::string toml) {
  for (const Parameter& p : scene::object_parameters(type).parameters())
    if (!p.value.empty() && p.key != "type" && p.type != Type::tables) toml += p.key + " = " + p.value + "\n";
  return toml;
}

TEST(SceneParameters, ObjectTablesDefaultsAreTheReadersDefaults) {
  const std::pair<std::string, std::string> obstacles[] = {
      {"circle", "type = \"circle\"\ncentre = [0.5, 0.5]\nradius = 0.1\n"},
      {"box", "type = \"box\"\ncentre = [0.5, 0.5]\nsize = [0.1, 0.2]\n"}};
  for (const auto& [type, minimal] : obstacles) {
    const jellyfish::ObstacleSpec a = scene::read_obstacle(config::Config::parse(minimal, type), type, type);
    const jellyfish::ObstacleSpec b =
        scene::read_obstacle(config::Config::parse(with_every_default(type, minimal), type), type, type);
    EXPECT_EQ(a.tether_stiffness_n_per_m2, b.tether_stiffness_n_per_m2) << type;
    EXPECT_EQ(a.angle_rad, b.angle_rad) << type;
    EXPECT_EQ(a.motion.velocity_m_per_s.x, b.motion.velocity_m_per_s.x) << type;
    EXPECT_EQ(a.motion.amplitude_m.y, b.motion.amplitude_m.y) << type;
    EXPECT_EQ(a.motion.frequency_hz, b.motion.frequency_hz) << type;
  }
  const std::string ib2d = "type = \"ib2d\"\nmodel = \"hoover-miller\"\nresolution = 64\n";
  const std::string schedule = "[[schedules]]\nsprings = \"muscles\"\n";
  const coupling::TankSpec tank{};
  const jellyfish::Ib2dObjectSpec a = scene::read_ib2d_object(config::Config::parse(ib2d + schedule, "a"), "a", tank);
  const jellyfish::Ib2dObjectSpec b = scene::read_ib2d_object(
      config::Config::parse(with_every_default("ib2d", ib2d) + with_every_default("schedules", schedule), "b"), "b", tank);
  ASSERT_EQ(a.schedules.size(), 1u);
  ASSERT_EQ(b.schedules.size(), 1u);
  EXPECT_EQ(a.offset_m.x, b.offset_m.x);
  const jellyfish::SpringSchedule& sa = a.schedules[0];
  const jellyfish::SpringSchedule& sb = b.schedules[0];
  EXPECT_EQ(sa.stiffness, sb.stiffness);
  EXPECT_EQ(sa.law, sb.law);
  EXPECT_EQ(sa.frequency_hz, sb.frequency_hz);
  EXPECT_EQ(sa.amplitude, sb.amplitude);
  EXPECT_EQ(sa.mean, sb.mean);
  EXPECT_EQ(sa.gamma, sb.gamma);
}

void expect_object_rejected(const std::string& message, const std::string& key, const std::string& allowed) {
  EXPECT_NE(message.find("'" + key + "'"), std::string::npos) << message;
  EXPECT_NE(message.find(allowed), std::string::npos) << message;
}

// An object's fields are its table's: one that is not is refused, naming the allowed ones, and a
// value out of its range names the field and the range.
TEST(SceneParameters, ObjectFieldsFollowTheirTables) {
  const std::string circle = "type = \"circle\"\ncentre = [0.5, 0.5]\n";
  expect_object_rejected(error_of([&] {
                    scene::read_obstacle(config::Config::parse(circle + "radius = 0.1\nsize = [1.0, 1.0]\n", "c"), "circle",
                                         "objects[0] (circle)");
                  }),
                  "size", "allowed: type, centre, radius, tether_stiffness");
  expect_object_rejected(error_of([&] {
                    scene::read_obstacle(config::Config::parse(circle + "radius = -0.1\n", "c"), "circle", "c");
                  }),
                  "radius", "(0, inf)");
  for (const std::string& type : scene::object_types())
    EXPECT_NE(scene::parameters_reference().find("### [[objects]] type = \"" + type + "\""), std::string::npos) << type;
  EXPECT_NE(scene::parameters_reference().find("### [[objects.schedules]]"), std::string::npos);
}

}  // namespace
