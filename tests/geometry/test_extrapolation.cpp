// 3D extrapolation (§7.3, Figure 7.6), normals (eq. 7.9) and noise (eqs. 7.10–7.18).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "jellysim/geometry/extrapolation.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {
namespace {

GeometrySettings no_noise() {
  GeometrySettings s;
  s.latitude_samples = 33;
  s.disc_points = 48;
  s.noise.structural_weight = s.noise.compression_weight = s.noise.unstructured_weight = 0.0;
  return s;
}

FrameGeometry build(const jellyfish::SliceFrame& frame, const GeometrySettings& s) {
  return GeometryBuilder(s, resolve_noise_length(s.noise, frame)).build(frame);
}

std::vector<std::uint32_t> part_indices(const Mesh& mesh, const char* name) {
  const MeshPart* p = mesh.part(name);
  if (!p) return {};
  return {mesh.indices.begin() + p->first_index, mesh.indices.begin() + p->first_index + p->index_count};
}

TEST(Extrapolation, WithoutNoiseASymmetricSliceGivesASurfaceOfRevolution) {
  for (double contraction : {0.0, 0.7}) {
    const FrameGeometry g = build(synthetic_bell(0.04, 0.028, contraction, 21, 8), no_noise());
    const UmbrellaLayout& L = g.umbrella;
    EXPECT_EQ(L.rows, 2 + 2 * 16);
    for (int r = 1; r + 1 < L.rows; ++r) {
      const Vec3 first = g.mesh.positions[L.vertex(r, 0)];
      const double radius = std::hypot(first.x, first.z);  // distance from the y axis
      for (int j = 0; j < L.disc_points; ++j) {
        const Vec3 p = g.mesh.positions[L.vertex(r, j)];
        EXPECT_NEAR(std::hypot(p.x, p.z), radius, 1e-15) << "ring " << r << " j " << j;
        EXPECT_NEAR(p.y, first.y, 1e-15);
      }
    }
  }
}

TEST(Extrapolation, UmbrellaIsClosedConsistentlyWoundAndNonDegenerate) {
  GeometrySettings s;  // with every noise on
  s.latitude_samples = 33;
  s.disc_points = 40;
  const FrameGeometry g = build(synthetic_bell(0.04, 0.028, 0.8, 21, 8), s);
  const std::vector<std::uint32_t> idx = part_indices(g.mesh, "umbrella");
  ASSERT_EQ(idx.size() % 3, 0u);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  double volume6 = 0.0;
  const double scale = 0.04;
  for (std::size_t t = 0; t < idx.size(); t += 3) {
    const Vec3 a = g.mesh.positions[idx[t]], b = g.mesh.positions[idx[t + 1]], c = g.mesh.positions[idx[t + 2]];
    EXPECT_GT(norm(cross(b - a, c - a)), 1e-10 * scale * scale) << "degenerate triangle " << t / 3;
    volume6 += dot(a, cross(b, c));
    for (int e = 0; e < 3; ++e) ++directed[{idx[t + e], idx[t + (e + 1) % 3]}];
  }
  // Every directed edge once, and its reverse once: a closed, consistently wound surface.
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  EXPECT_GT(volume6, 0.0);  // counter-clockwise seen from outside encloses positive volume
  EXPECT_EQ(directed.size(), idx.size());
}

TEST(Extrapolation, NormalsPointOutward) {
  for (bool noisy : {false, true}) {
    GeometrySettings s = no_noise();
    if (noisy) s.noise = NoiseSettings{};
    const FrameGeometry g = build(synthetic_bell(0.04, 0.028, 0.5, 21, 8), s);
    const Mesh& m = g.mesh;
    const UmbrellaLayout& L = g.umbrella;
    // Vertex normals agree with the area-weighted normals of the faces around them.
    std::vector<Vec3> face_sum(L.vertex_count());
    const auto idx = part_indices(m, "umbrella");
    for (std::size_t t = 0; t < idx.size(); t += 3) {
      const Vec3 fn = cross(m.positions[idx[t + 1]] - m.positions[idx[t]], m.positions[idx[t + 2]] - m.positions[idx[t]]);
      for (int e = 0; e < 3; ++e) face_sum[idx[t + e]] += fn;
    }
    for (std::uint32_t v = 0; v < L.vertex_count(); ++v) {
      EXPECT_NEAR(norm(m.normals[v]), 1.0, 1e-12);
      EXPECT_GT(dot(m.normals[v], normalized(face_sum[v])), 0.8) << "vertex " << v;
    }
    // The exumbrellar apex faces up (+axis), the subumbrellar apex down into the cavity.
    EXPECT_GT(m.normals[L.vertex(0, 0)].y, 0.99);
    EXPECT_LT(m.normals[L.vertex(L.rows - 1, 0)].y, -0.99);
    if (!noisy) {
      // Exumbrellar rings: normals lean away from the axis; subumbrellar rings: toward it.
      for (int r = 2; r + 2 < L.rows; ++r) {
        const Vec3 p = m.positions[L.vertex(r, 5)], n = m.normals[L.vertex(r, 5)];
        const double radial = p.x * n.x + p.z * n.z;
        if (r <= L.exumbrella_rings) EXPECT_GT(radial, 0.0) << "ring " << r;
        else EXPECT_LT(radial, 0.0) << "ring " << r;
      }
    }
  }
}

TEST(Extrapolation, TentaclesAreTubesAroundPolylines) {
  GeometrySettings s = no_noise();
  s.tentacle_count = 12;
  s.tentacle_samples = 10;
  s.tube_sides = 5;
  const FrameGeometry g = build(synthetic_bell(0.04, 0.028, 0.0, 21, 8), s);
  ASSERT_EQ(g.tentacle_lines.size(), 12u);
  const MeshPart* tubes = g.mesh.part("tentacles");
  ASSERT_NE(tubes, nullptr);
  EXPECT_EQ(tubes->index_count, 12u * 9u * 5u * 6u);
  EXPECT_EQ(g.mesh.vertex_count(), g.umbrella.vertex_count() + 12u * 10u * 5u);
  // Strand 0 is the right slice tentacle, strand 6 the left one (σ = π); roots at the rim.
  const auto slice = synthetic_bell(0.04, 0.028, 0.0, 21, 8);
  EXPECT_NEAR(g.tentacle_lines[0][0].x, slice.tentacles[1][0].x, 1e-15);
  EXPECT_NEAR(g.tentacle_lines[6][0].x, slice.tentacles[0][0].x, 1e-15);
  for (const auto& line : g.tentacle_lines) EXPECT_NEAR(std::hypot(line[0].x, line[0].z), 0.02, 1e-12);
}

TEST(Noise, EachKindMovesTheSurfaceAsDescribed) {
  const jellyfish::SliceFrame expanded = synthetic_bell(0.04, 0.028, 0.0, 21, 8);
  const jellyfish::SliceFrame contracted = synthetic_bell(0.04, 0.028, 0.9, 21, 8);
  const GeometrySettings plain = no_noise();
  auto max_shift = [&](const jellyfish::SliceFrame& f, const GeometrySettings& s, bool exumbrella) {
    const FrameGeometry a = build(f, plain), b = build(f, s);
    double shift = 0.0;
    for (int r = 1; r + 1 < a.umbrella.rows; ++r) {
      if ((r <= a.umbrella.exumbrella_rings) != exumbrella) continue;
      for (int j = 0; j < a.umbrella.disc_points; ++j)
        shift = std::max(shift, norm(a.mesh.positions[a.umbrella.vertex(r, j)] - b.mesh.positions[a.umbrella.vertex(r, j)]));
    }
    return shift;
  };
  const double height = 0.028;
  GeometrySettings structural = plain;
  structural.noise.structural_weight = 0.01875;
  // 64 disc points cannot draw 18 ridges a ring: the ridges' mean offset, 2/π of the amplitude.
  EXPECT_NEAR(max_shift(expanded, structural, true), 2.0 / std::numbers::pi * 0.01875 * height, 1e-9 * height);
  GeometrySettings compression = plain;
  compression.noise.compression_weight = 0.125;
  EXPECT_EQ(max_shift(contracted, compression, false), 0.0);  // exumbrellar side only
  EXPECT_EQ(max_shift(expanded, compression, true), 0.0);     // relaxed muscles: no ridges
  EXPECT_GT(max_shift(contracted, compression, true), 0.125 * height * 0.34 * 0.5);
  GeometrySettings unstructured = plain;
  unstructured.noise.unstructured_weight = 0.45;
  EXPECT_GT(max_shift(expanded, unstructured, true), 1e-4);
  EXPECT_GT(max_shift(expanded, unstructured, false), 1e-4);
}

/// Max − min over the rim ring (the last exumbrellar ring) of how far the structural noise moved it.
double rim_ridge_depth(int disc_points) {
  const jellyfish::SliceFrame expanded = synthetic_bell(0.04, 0.028, 0.0, 21, 8);
  GeometrySettings plain = no_noise();
  plain.disc_points = disc_points;
  GeometrySettings ridges = plain;
  ridges.noise.structural_weight = 0.01875;
  const FrameGeometry a = build(expanded, plain), b = build(expanded, ridges);
  double lo = INFINITY, hi = 0.0;
  for (int j = 0; j < disc_points; ++j) {
    const std::uint32_t v = a.umbrella.vertex(a.umbrella.exumbrella_rings, j);
    const double shift = norm(a.mesh.positions[v] - b.mesh.positions[v]);
    lo = std::min(lo, shift);
    hi = std::max(hi, shift);
  }
  return hi - lo;
}

TEST(Noise, StructuralRidgesAreDrawnOnlyWhereTheRingResolvesThem) {
  const double amplitude = 0.01875 * 0.028;
  // 64 points, 3.6 a ridge: point samples of |sin 9σ| made the rim a saw-tooth (depth = the full
  // amplitude, 0.53 mm); the ring now keeps only what it can draw smoothly: a constant offset.
  EXPECT_LT(rim_ridge_depth(64), 1e-9 * amplitude);
  // 256 points, 14 a ridge: the ridges are drawn (measured 0.865 of the amplitude, the truncated series).
  EXPECT_NEAR(rim_ridge_depth(256), 0.865 * amplitude, 0.005 * amplitude);
  EXPECT_DOUBLE_EQ(resolvable_fraction(8.0, 64), 1.0);
  EXPECT_DOUBLE_EQ(resolvable_fraction(12.0, 64), 0.5);
  EXPECT_DOUBLE_EQ(resolvable_fraction(16.0, 64), 0.0);
  // Fully resolved, the series is |sin| itself (to its truncation).
  EXPECT_NEAR(structural_noise_resolved(1.0, 1.0, 0.7, true, 100000), std::abs(std::sin(0.7)), 1e-3);
  EXPECT_DOUBLE_EQ(structural_noise_resolved(2.0, 9.0, 0.1, false, 1000), 2.0 * std::sin(0.9));
}

TEST(Noise, SeedChangesTheIndividualAndRunsRepeat) {
  const jellyfish::SliceFrame bell = synthetic_bell(0.04, 0.028, 0.3, 21, 8);
  GeometrySettings a;
  a.latitude_samples = 33;
  GeometrySettings b = a;
  b.noise.seed = 2;
  const FrameGeometry ga = build(bell, a), ga2 = build(bell, a), gb = build(bell, b);
  EXPECT_EQ(ga.mesh.positions, ga2.mesh.positions);
  EXPECT_NE(ga.mesh.positions, gb.mesh.positions);
  EXPECT_TRUE(same_topology(ga.mesh, gb.mesh));
}

TEST(Noise, TermsFollowTheEquations) {
  EXPECT_DOUBLE_EQ(structural_noise(2.0, 9.0, 0.1, false), 2.0 * std::sin(0.9));
  EXPECT_DOUBLE_EQ(structural_noise(2.0, 9.0, 0.4, true), 2.0 * std::abs(std::sin(3.6)));
  EXPECT_DOUBLE_EQ(contraction_amount(1.0, 1.0, 0.56), 0.0);
  EXPECT_NEAR(contraction_amount(0.56, 1.0, 0.56), 1.0, 1e-15);
  EXPECT_NEAR(contraction_amount(0.78, 1.0, 0.56), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(compression_noise(1.0, 1.0, 1.0, std::numbers::pi / 2), 0.51);
  EXPECT_DOUBLE_EQ(latitude_distance(3, 0, 10, 10), 0.3);
  EXPECT_DOUBLE_EQ(latitude_distance(8, 0, 10, 10), 0.2);
  EXPECT_DOUBLE_EQ(longitude_distance(60, 64), 4.0 / 64.0);
  const ImprovedNoise reference(0);
  NoiseSettings s;
  EXPECT_DOUBLE_EQ(unstructured_noise(reference, s, 1.0, 0.25, 0.125, 10.0),
                   0.25 * perlin_noise(0.5, 1.0, 3.0));
}

TEST(Animation, SameTopologyThroughAContractionAndBadSettingsRejected) {
  std::vector<jellyfish::SliceFrame> frames;
  for (int k = 0; k < 5; ++k) {
    SyntheticBell spec;
    spec.contraction = 0.2 * k;
    spec.time_s = 0.1 * k;
    spec.aperture_centre_m = {0.0, 0.003 * k};
    frames.push_back(synthetic_bell(spec));
  }
  GeometrySettings s;
  s.latitude_samples = 21;
  const Animation anim = build_animation(frames, s);
  EXPECT_EQ(anim.frames.size(), 5u);
  validate_animation(anim);
  GeometrySettings bad = s;
  bad.disc_points = 3;
  EXPECT_THROW(build_animation(frames, bad), InputError);
  bad = s;
  bad.noise.max_contraction = 1.0;
  EXPECT_THROW(build_animation(frames, bad), InputError);
  frames[2].tentacles.clear();
  EXPECT_THROW(build_animation(frames, s), InputError);  // topology changes
}

TEST(Extrapolation, BuildingIntoAReusedFrameGivesTheSameGeometry) {
  // The interactive path (build into one FrameGeometry frame after frame) must equal a fresh build,
  // also after the frame held another topology (more vertices, another tentacle count).
  GeometrySettings big;
  big.latitude_samples = 41;
  big.disc_points = 36;
  big.tentacle_count = 9;
  GeometrySettings s;
  s.latitude_samples = 21;
  s.disc_points = 16;
  s.tentacle_count = 5;
  const auto slice = [](double contraction, double t) {
    SyntheticBell spec;
    spec.contraction = contraction;
    spec.time_s = t;
    return synthetic_bell(spec);
  };
  FrameGeometry reused;
  GeometryBuilder(big, 0.028).build(slice(0.2, 0.5), reused);
  const GeometryBuilder builder(s, 0.028);
  for (double c : {0.0, 0.6, 1.0}) {
    builder.build(slice(c, 1.0 + c), reused);
    const FrameGeometry fresh = builder.build(slice(c, 1.0 + c));
    EXPECT_EQ(reused.mesh.positions, fresh.mesh.positions);
    EXPECT_EQ(reused.mesh.normals, fresh.mesh.normals);
    EXPECT_EQ(reused.mesh.indices, fresh.mesh.indices);
    EXPECT_TRUE(same_topology(reused.mesh, fresh.mesh));
    EXPECT_EQ(reused.tentacle_lines, fresh.tentacle_lines);
    EXPECT_EQ(reused.umbrella.rows, fresh.umbrella.rows);
    EXPECT_EQ(reused.time_s, fresh.time_s);
  }
}

}  // namespace
}  // namespace jellysim::geometry
