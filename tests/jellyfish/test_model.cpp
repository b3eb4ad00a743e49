// The jellyfish slice model (thesis §7.1): contraction functions, geometry, metrics.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jellysim/elastic/forces.hpp"
#include "jellysim/jellyfish/contraction.hpp"
#include "jellysim/jellyfish/jellyfish.hpp"
#include "jellysim/jellyfish/metrics.hpp"

namespace jellysim::jellyfish {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Hermite, InterpolatesEndPointsAndDerivatives) {
  // Eq. 7.3: Q(0) = x_b, Q(1) = x_e, Q'(0) = v_b, Q'(1) = v_e.
  const double xb = 0.3, xe = -1.2, vb = 2.0, ve = 0.7, h = 1e-6;
  EXPECT_DOUBLE_EQ(hermite(0.0, xb, xe, vb, ve), xb);
  EXPECT_DOUBLE_EQ(hermite(1.0, xb, xe, vb, ve), xe);
  EXPECT_NEAR((hermite(h, xb, xe, vb, ve) - hermite(0.0, xb, xe, vb, ve)) / h, vb, 1e-5);
  EXPECT_NEAR((hermite(1.0, xb, xe, vb, ve) - hermite(1.0 - h, xb, xe, vb, ve)) / h, ve, 1e-5);
}

class ContractionShapes : public ::testing::TestWithParam<ContractionShape> {};

TEST_P(ContractionShapes, AreNormalisedPeriodicAndRelaxedAtPhaseZero) {
  ContractionProfile p;
  p.shape = GetParam();
  double lo = 1e9, hi = -1e9;
  for (int k = 0; k <= 2000; ++k) {
    const double s = k / 2000.0;
    const double q = contraction_value(p, s);
    lo = std::min(lo, q);
    hi = std::max(hi, q);
    EXPECT_NEAR(contraction_value(p, s + 3.0), q, 1e-12);
  }
  EXPECT_NEAR(contraction_value(p, 0.0), 1.0, 1e-9);
  EXPECT_NEAR(hi, 1.0, 1e-6);
  EXPECT_NEAR(lo, 0.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(All, ContractionShapes,
                         ::testing::Values(ContractionShape::hermite, ContractionShape::sine, ContractionShape::triangle,
                                           ContractionShape::fourier, ContractionShape::trochoid),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(Contraction, HermiteContractsFastAndApertureSpringsReexpandSlower) {
  ContractionProfile apex, aperture;
  apex.contract_fraction = aperture.contract_fraction = 0.3;
  aperture.expansion_exponent = 2.0;
  EXPECT_NEAR(contraction_value(apex, 0.3), 0.0, 1e-12);  // fully contracted after 30 % of the cycle
  for (double s = 0.35; s < 1.0; s += 0.05) {
    EXPECT_LT(contraction_value(aperture, s), contraction_value(apex, s)) << s;
  }
  EXPECT_NEAR(contracted_rest_length(2.0, 0.56, 0.0), 1.12, 1e-12);  // eq. 7.5
  EXPECT_NEAR(contracted_rest_length(2.0, 0.56, 1.0), 2.0, 1e-12);
}

// Gemmell et al. (2013)'s pause: contraction over the same part of the cycle, expansion compressed
// into the rest of the active part, then relaxed (Q = 1) through the pause; no pause is the old curve.
TEST(Contraction, APauseHoldsTheBellRelaxedAfterReexpanding) {
  ContractionProfile plain, paused;
  paused.pause_fraction = 0.4;
  for (double s = 0.0; s < 0.3; s += 0.01)
    EXPECT_NEAR(contraction_value(paused, s), contraction_value(plain, s), 1e-12) << s;  // the same contraction
  EXPECT_NEAR(contraction_value(paused, 0.3), 0.0, 1e-12);
  EXPECT_NEAR(contraction_value(paused, 0.45), contraction_value(plain, 0.3 + 0.7 * 0.5), 1e-12);  // expansion, halfway
  EXPECT_LT(contraction_value(paused, 0.59), 1.0);
  for (double s = 0.6; s < 1.0; s += 0.02) EXPECT_EQ(contraction_value(paused, s), 1.0) << s;  // the pause
  ContractionProfile sine = paused;
  sine.shape = ContractionShape::sine;
  EXPECT_NEAR(contraction_value(sine, 0.3), 0.0, 1e-12);  // the whole shape within the active 60 %
  EXPECT_EQ(contraction_value(sine, 0.8), 1.0);
}

JellyfishSpec small_spec() {
  JellyfishSpec s;
  s.aperture_centre_m = {0.4, 0.3};
  s.max_spacing_m = 0.004;
  return s;
}

TEST(Jellyfish, GeometryFollowsTheBellShapeAndPeskinsSpacing) {
  const Jellyfish j(small_spec());
  const auto u = j.umbrella_points();
  ASSERT_EQ(u.size() % 2, 1u);
  const std::size_t n = u.size();
  EXPECT_NEAR(u[n / 2].y - 0.3, 0.028, 1e-12);                 // apex at the bell height
  EXPECT_NEAR(norm(u.back() - u.front()), 0.04, 1e-12);        // aperture = diameter
  for (std::size_t k = 0; k + 1 < n; ++k) EXPECT_LE(norm(u[k + 1] - u[k]), 0.004 + 1e-12);
  for (std::size_t k = 0; k < n; ++k) {                         // mirror symmetric about the axis
    EXPECT_NEAR(u[k].x - 0.4, -(u[n - 1 - k].x - 0.4), 1e-12);
    EXPECT_NEAR(u[k].y, u[n - 1 - k].y, 1e-12);
  }
  EXPECT_EQ(j.layout().tentacles.size(), 2u);
  EXPECT_FALSE(polyline_self_intersects(u));
}

TEST(Jellyfish, ContinuumSpringConstantsAreTheMaterialsShare) {
  const JellyfishSpec spec = small_spec();
  const Jellyfish j(spec);
  const auto& lin = j.body().linear;
  const auto& ang = j.body().angular;
  EXPECT_NEAR(lin.stiffness[0], spec.material.stretching_n_per_m / lin.rest_length[0], 1e-12);  // S / l
  const double l1 = lin.rest_length[0], l2 = lin.rest_length[1];
  EXPECT_NEAR(ang.stiffness[0], spec.material.bending_n_m / (0.5 * (l1 + l2)), 1e-15);  // B / l̄
}

/// The joint at the root of tentacle `strand`: the angular spring whose middle point is its margin
/// tip and whose last is the strand's first point beyond the tip.
std::size_t root_joint(const Jellyfish& j, std::size_t strand) {
  const auto& t = j.layout().tentacles[strand];
  const auto& ang = j.body().angular;
  for (std::size_t a = 0; a < ang.size(); ++a)
    if (ang.j[a] == t[0] && ang.k[a] == t[1]) return a;
  ADD_FAILURE() << "no root joint";
  return 0;
}

// Issue 39 item 5 (docs/jellyfish.md, "Tentacles that trail"): the continuum model holds each
// tentacle's root against the aperture chord (the other margin tip), stiffness B_t / (½ l_t) of the
// tentacle's first half cell, so that turning the margin does not turn the tentacle; "margin" and
// the thesis's model hold it against the bell's last segment (§7.1) with the joints as before.
TEST(Jellyfish, TentacleRootsHoldAgainstTheApertureChord) {
  JellyfishSpec spec = small_spec();
  const Jellyfish axis(spec);
  const auto& u = axis.layout().umbrella;
  const auto& ang = axis.body().angular;
  for (std::size_t strand = 0; strand < 2; ++strand) {
    const std::size_t a = root_joint(axis, strand);
    EXPECT_EQ(ang.i[a], strand == 0 ? u.back() : u.front());
    const auto& t = axis.layout().tentacles[strand];
    const double l_t = norm(axis.body().points.position[static_cast<std::size_t>(t[1])] -
                            axis.body().points.position[static_cast<std::size_t>(t[0])]);
    EXPECT_NEAR(ang.stiffness[a], spec.material.tentacle_bending_n_m / (0.5 * l_t), 1e-15);
    EXPECT_NEAR(std::abs(ang.rest_angle[a]), 0.5 * kPi, 1e-9);  // hanging along the axis, across the chord
  }
  spec.tentacle_root = TentacleRoot::margin;
  const Jellyfish margin(spec);
  EXPECT_EQ(margin.body().angular.i[root_joint(margin, 0)], margin.layout().umbrella[1]);
  spec.tentacle_root = TentacleRoot::automatic;
  spec.elastic_model = ElasticModel::thesis;
  const Jellyfish thesis(spec);
  EXPECT_EQ(thesis.body().angular.i[root_joint(thesis, 1)], thesis.layout().umbrella[thesis.layout().umbrella.size() - 2]);
}

TEST(Jellyfish, SpringConstantsComeFromEquationSevenOne) {
  JellyfishSpec spec = small_spec();
  spec.elastic_model = ElasticModel::thesis;
  const Jellyfish j(spec);
  const auto& lin = j.body().linear;
  // First umbrella spring: tangential, A = ϑ².
  EXPECT_NEAR(lin.stiffness[0], spec.bell_modulus_pa * spec.thickness_m * spec.thickness_m / lin.rest_length[0], 1e-9);
  // Muscles join opposing points and are the stiffest springs per unit length here.
  const auto n = static_cast<int>(j.umbrella_points().size());
  for (std::size_t k = 0; k < j.layout().muscle_springs.size(); ++k) {
    const auto s = static_cast<std::size_t>(j.layout().muscle_springs[k]);
    EXPECT_EQ(lin.i[s], static_cast<int>(k));
    EXPECT_EQ(lin.j[s], n - 1 - static_cast<int>(k));
  }
}

TEST(Jellyfish, MusclesShortenToGammaAtFullContraction) {
  JellyfishSpec spec = small_spec();
  spec.neural_delay_s = 0.0;
  Jellyfish j(spec);
  const double t_contracted = spec.profile.contract_fraction / spec.frequency_hz;
  j.actuate(t_contracted);
  for (std::size_t k = 0; k < j.layout().muscle_springs.size(); ++k) {
    const auto s = static_cast<std::size_t>(j.layout().muscle_springs[k]);
    EXPECT_NEAR(j.body().linear.rest_length[s], spec.gamma * j.layout().muscle_uncontracted_m[k], 1e-12);
  }
  j.actuate(1.0 / spec.frequency_hz);
  for (std::size_t k = 0; k < j.layout().muscle_springs.size(); ++k) {
    const auto s = static_cast<std::size_t>(j.layout().muscle_springs[k]);
    EXPECT_NEAR(j.body().linear.rest_length[s], j.layout().muscle_uncontracted_m[k], 1e-12);
  }
}

TEST(Jellyfish, DenseMeshModelNeedsTheThesisElasticModel) {
  JellyfishSpec spec = small_spec();
  spec.model = UmbrellaModel::mesh;
  EXPECT_THROW(validate(spec), std::invalid_argument);
  spec.elastic_model = ElasticModel::thesis;
  EXPECT_NO_THROW(validate(spec));
}

TEST(Jellyfish, DenseMeshModelHasTwoRowsWithCrossingDiagonals) {
  JellyfishSpec spec = small_spec();
  spec.model = UmbrellaModel::mesh;
  spec.elastic_model = ElasticModel::thesis;  // the lattice is the thesis's construction
  spec.tentacle_length_m = 0.0;
  const Jellyfish j(spec);
  const std::size_t n = j.layout().umbrella.size();
  ASSERT_EQ(j.layout().exumbrella.size(), n);
  EXPECT_EQ(j.body().angular.size(), 0u);  // Fig. 7.2 left: linear springs only
  // Per quad: outer edge, inner edge, two diagonals; plus one rung per point; plus the muscles.
  EXPECT_EQ(j.body().linear.size(), 4 * (n - 1) + n + j.layout().muscle_springs.size());
  // The outer row lies outside the cavity: farther from the aperture centre than the inner row.
  const Vec2 c = spec.aperture_centre_m;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 in = j.body().points.position[static_cast<std::size_t>(j.layout().umbrella[k])];
    const Vec2 out = j.body().points.position[static_cast<std::size_t>(j.layout().exumbrella[k])];
    EXPECT_GT(norm(out - c), norm(in - c)) << k;
  }
}

TEST(Contraction, ClosedLoopControllerShortensASpringThatLagsBehind) {
  // Eq. 7.2: during the contraction phase a spring still at full length must shorten its rest length.
  RestLengthController c;
  const double l_ru = 0.03, f = 0.7, gamma = 0.56;
  double rest = l_ru;
  rest = c.update(0.0, l_ru, l_ru, rest, gamma, f, 0.3);
  for (int k = 1; k <= 10; ++k) rest = c.update(0.01 * k, l_ru, l_ru, rest, gamma, f, 0.3);
  EXPECT_LT(rest, l_ru);
  EXPECT_GE(rest, 0.2 * l_ru);
  // In the relaxation phase, a spring stuck at the contracted length lengthens its rest length.
  RestLengthController r;
  double rest2 = gamma * l_ru;
  const double t0 = 0.8 / f;
  rest2 = r.update(t0, gamma * l_ru, l_ru, rest2, gamma, f, 0.3);
  for (int k = 1; k <= 10; ++k) rest2 = r.update(t0 + 0.01 * k, gamma * l_ru, l_ru, rest2, gamma, f, 0.3);
  EXPECT_GT(rest2, gamma * l_ru);
}

TEST(Jellyfish, BadSpecNamesTheField) {
  JellyfishSpec spec = small_spec();
  spec.gamma = 1.5;
  try {
    Jellyfish j(spec);
    FAIL() << "accepted gamma = 1.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("jellyfish.gamma"), std::string::npos) << e.what();
  }
}

TEST(Metrics, ConeVolumeAndApertureAreExact) {
  // Opposing points on a cone of radius r and height h: the frustum sum is exact.
  const double r = 0.02, h = 0.03;
  const int levels = 7;
  std::vector<Vec2> left, right;
  for (int k = 0; k < levels; ++k) {
    const double f = static_cast<double>(k) / levels;
    left.push_back({-r * (1 - f), h * f});
    right.push_back({r * (1 - f), h * f});
  }
  std::vector<Vec2> umbrella = left;
  umbrella.push_back({0.0, h});
  for (int k = levels - 1; k >= 0; --k) umbrella.push_back(right[static_cast<std::size_t>(k)]);
  const BellShape b = measure_bell(umbrella);
  EXPECT_NEAR(b.volume_m3, kPi * r * r * h / 3.0, 1e-15);
  EXPECT_NEAR(b.aperture_area_m2, kPi * r * r, 1e-15);
  EXPECT_NEAR(b.cavity_area_m2, r * h, 1e-15);
  EXPECT_NEAR(b.axis.y, 1.0, 1e-15);
}

TEST(Metrics, HemisphereVolumeConverges) {
  const JellyfishSpec spec = [] {
    JellyfishSpec s;
    s.diameter_m = 0.04;
    s.height_m = 0.02;  // hemisphere
    return s;
  }();
  const auto u = bell_profile(spec.diameter_m, spec.height_m, 200);
  const BellShape b = measure_bell(u);
  EXPECT_NEAR(b.volume_m3 / (2.0 / 3.0 * kPi * 0.02 * 0.02 * 0.02), 1.0, 1e-3);
}

TEST(Metrics, DanielModelReachesTerminalVelocityWhereThrustBalancesDrag) {
  const MetricsSettings s{1000.0, 1e-6};
  const double volume = 1e-5, aperture = 1e-3, thrust = 1e-3;
  std::vector<double> t, v, a, f;
  for (int k = 0; k <= 4000; ++k) {
    t.push_back(k * 0.01);
    v.push_back(volume);
    a.push_back(aperture);
    f.push_back(thrust);
  }
  const auto u = daniel_velocity(t, v, a, f, s);
  const double r = std::sqrt(aperture / kPi);
  const double terminal = u.back();
  const double cd = 24.0 * std::pow(2.0 * r * terminal / s.viscosity_m2_per_s, -0.7);
  EXPECT_NEAR(0.5 * s.density_kg_per_m3 * cd * aperture * terminal * terminal, thrust, 1e-4 * thrust);
  EXPECT_GT(terminal, 0.0);
}

TEST(Metrics, DominantFrequencyOfASampledSine) {
  std::vector<double> y;
  for (int k = 0; k < 300; ++k) y.push_back(std::sin(2 * kPi * 0.7 * k / 30.0) + 0.1);
  EXPECT_NEAR(dominant_frequency(y, 1.0 / 30.0), 0.7, 0.1);
}

}  // namespace
}  // namespace jellysim::jellyfish
