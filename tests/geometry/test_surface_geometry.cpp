// The simulated 3D bell as rendering geometry (geometry/surface_geometry.hpp): the synthetic bell's
// slice revolved into a triangulated surface, breathing over three frames with two tentacle strands,
// closed into a wall of the set thickness, away from the cavity whichever way the triangles turn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <utility>

#include "jellysim/core/errors.hpp"
#include "jellysim/geometry/surface_geometry.hpp"
#include "jellysim/geometry/synthetic_bell.hpp"
#include "jellysim/geometry/texture_coordinates.hpp"

namespace jellysim::geometry {
namespace {

constexpr int kRingPoints = 24;

/// Three frames of the synthetic bell contracting (0, 0.4, 0.8), 21 slice points (10 rings), two strands.
SurfaceFrames breathing_bell() {
  std::vector<SyntheticBell> specs(3);
  for (std::size_t k = 0; k < specs.size(); ++k) {
    specs[k].contraction = 0.4 * static_cast<double>(k);
    specs[k].time_s = static_cast<double>(k) / 30.0;
  }
  return revolved_synthetic_bell(specs, kRingPoints, 2);
}

SurfaceFrames reversed(SurfaceFrames f) {
  for (auto& t : f.triangles) std::swap(t[1], t[2]);
  return f;
}

/// The signed volume of a closed triangle mesh (the part's triangles), divergence theorem.
double enclosed_volume(const Mesh& mesh, const MeshPart& part) {
  double sum = 0.0;
  for (std::uint32_t k = part.first_index; k < part.first_index + part.index_count; k += 3) {
    const Vec3 a = mesh.positions[mesh.indices[k]], b = mesh.positions[mesh.indices[k + 1]],
               c = mesh.positions[mesh.indices[k + 2]];
    sum += dot(a, cross(b, c));
  }
  return sum / 6.0;
}

double area(const std::vector<Vec3>& x, const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  double sum = 0.0;
  for (const auto& t : triangles) sum += 0.5 * norm(cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]));
  return sum;
}

TEST(SurfaceGeometry, TheWallIsClosedFacesOutwardAndIsAsThickAsSet) {
  const SurfaceFrames given = breathing_bell();
  const SurfaceFrames flipped = reversed(given);
  const GeometrySettings settings;
  const SurfaceGeometryBuilder a(given, settings), b(flipped, settings);
  EXPECT_EQ(a.orientation(), 1);
  EXPECT_EQ(b.orientation(), -1);
  const std::size_t N = given.surface.front().size();
  for (std::size_t k = 0; k < given.surface.size(); ++k) {
    const FrameGeometry g = a.build(k);
    EXPECT_EQ(g.mesh.positions, b.build(k).mesh.positions);  // the wall does not depend on the triangles' turn
    const MeshPart& wall = *g.mesh.part("umbrella");
    // Closed and consistently wound: every directed edge once, its reverse once.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::uint32_t i = wall.first_index; i < wall.first_index + wall.index_count; i += 3)
      for (int c = 0; c < 3; ++c) ++edges[{g.mesh.indices[i + c], g.mesh.indices[i + (c + 1) % 3]}];
    for (const auto& [e, count] : edges) {
      ASSERT_EQ(count, 1);
      ASSERT_EQ(edges.count({e.second, e.first}), 1u);
    }
    EXPECT_EQ(umbrella_vertex_count(g), 2 * N);
    double thickness_error = 0.0;
    for (std::size_t i = 0; i < N; ++i)
      thickness_error = std::max(thickness_error, std::abs(norm(g.mesh.positions[i + N] - g.mesh.positions[i]) - given.thickness_m));
    EXPECT_LT(thickness_error, 1e-17);
    // Wound outward: the wall encloses area × ϑ, more by about ϑ times the mean curvature (offset
    // outward: 1.0576, 1.0648, 1.0757 measured as the bell contracts and its curvature grows).
    const double ratio = enclosed_volume(g.mesh, wall) / (area(given.surface[k], given.triangles) * given.thickness_m);
    std::printf("frame %zu: largest thickness error %.3g m, wall volume / (area × thickness) %.6f\n", k,
                thickness_error, ratio);
    EXPECT_GT(ratio, 1.05);
    EXPECT_LT(ratio, 1.08) << k;
    // Ring 5 (halfway down): the exumbrella's normals point away from the axis, the subumbrella's toward it.
    for (std::size_t i = 1 + 4 * kRingPoints; i < 1 + 5 * kRingPoints; ++i) {
      const Vec3 p = g.mesh.positions[i];
      const Vec3 radial = normalized(Vec3{p.x, 0.0, p.z});
      EXPECT_GT(dot(g.mesh.normals[i + N], radial), 0.5);
      EXPECT_LT(dot(g.mesh.normals[i], radial), -0.5);
    }
  }
}

TEST(SurfaceGeometry, TentaclesAreTubesFromTheMarginAndTheTopologyStays) {
  const SurfaceFrames f = breathing_bell();
  GeometrySettings settings;
  settings.tentacle_samples = 12;
  const SurfaceGeometryBuilder builder(f, settings);
  const FrameGeometry first = builder.build(0);
  FrameGeometry g;
  for (std::size_t k = 0; k < f.surface.size(); ++k) {
    builder.build(k, g);
    EXPECT_TRUE(same_topology(first.mesh, g.mesh));
    EXPECT_EQ(g.time_s, f.time_s[k]);
    ASSERT_EQ(g.tentacle_lines.size(), 2u);
    for (std::size_t t = 0; t < 2; ++t) {
      ASSERT_EQ(g.tentacle_lines[t].size(), 12u);
      EXPECT_EQ(g.tentacle_lines[t].front(), f.tentacles[k][t].front());  // the root, on the margin
      EXPECT_EQ(g.tentacle_lines[t].back(), f.tentacles[k][t].back());
    }
  }
  const MeshPart* tubes = first.mesh.part("tentacles");
  ASSERT_NE(tubes, nullptr);
  EXPECT_EQ(vertex_range(first.mesh, *tubes).count, 2u * 12u * static_cast<std::uint32_t>(settings.tube_sides));
  // Texture coordinates: the apex at v = 0, the margin at v = 1, u = j / ring points around.
  const std::vector<TexCoord> uv = texture_coordinates(first);
  ASSERT_EQ(uv.size(), first.mesh.vertex_count());
  const std::size_t N = f.surface.front().size(), margin = N - kRingPoints;
  EXPECT_EQ(uv[0][1], 0.0f);
  for (std::size_t j = 0; j < kRingPoints; ++j) {
    EXPECT_NEAR(uv[margin + j][1], 1.0f, 1e-6f);
    EXPECT_NEAR(uv[margin + j][0], static_cast<double>(j) / kRingPoints, 1e-6) << j;
    EXPECT_EQ(uv[margin + j], uv[N + margin + j]);  // both surfaces share them
  }
}

TEST(SurfaceGeometry, BadFramesAreInputErrorsNamingTheFault) {
  const GeometrySettings settings;
  const auto message = [&](const SurfaceFrames& f) {
    try {
      SurfaceGeometryBuilder builder(f, settings);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  SurfaceFrames f = breathing_bell();
  std::swap(f.triangles[5][1], f.triangles[5][2]);
  EXPECT_NE(message(f).find("used twice in one direction"), std::string::npos) << message(f);
  f = breathing_bell();
  f.surface[1].pop_back();
  EXPECT_NE(message(f).find("surface frame 1 has"), std::string::npos) << message(f);
  f = breathing_bell();
  f.tentacles[2][1].resize(1);
  EXPECT_NE(message(f).find("surface frame 2 tentacle 1"), std::string::npos) << message(f);
  f = breathing_bell();
  f.time_s[2] = f.time_s[1];
  EXPECT_NE(message(f).find("times must increase"), std::string::npos) << message(f);
  f = breathing_bell();
  f.thickness_m = 0.0;
  EXPECT_NE(message(f).find("thickness"), std::string::npos) << message(f);
}

}  // namespace
}  // namespace jellysim::geometry
