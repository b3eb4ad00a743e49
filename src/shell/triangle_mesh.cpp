#include "jellysim/shell/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "jellysim/jellyfish/jellyfish.hpp"

namespace jellysim::shell {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
const double kRowSpacing = 0.5 * std::sqrt(3.0);  ///< rows of equilateral triangles, per unit edge

/// The apex fan: triangles (apex, ring[i], ring[i + 1]).
void add_fan(TriangleMesh& mesh, int apex, int first, int count) {
  for (int i = 0; i < count; ++i) mesh.triangles.push_back({apex, first + i, first + (i + 1) % count});
}

/// Joins ring A (inner) to ring B (outer) by merging their vertices in order of azimuth: each step
/// advances the ring whose next vertex comes first (ties: A), making (A_{i+1}, A_i, B_j) or
/// (B_j, B_{j+1}, A_i). Azimuths are compared exactly as integers, (2(i+1) + 2o_a) n_b against
/// (2(j+1) + 2o_b) n_a, so the six sectors get the same triangles (the comparison is unchanged by
/// shifting i by n_a/6 and j by n_b/6).
void zip_rings(TriangleMesh& mesh, const Rings& r, std::size_t a, std::size_t b) {
  const long na = r.count[a], nb = r.count[b];
  const long oa = r.offset[a] > 0 ? 1 : 0, ob = r.offset[b] > 0 ? 1 : 0;
  auto A = [&](long i) { return r.first[a] + static_cast<int>(i % na); };
  auto B = [&](long j) { return r.first[b] + static_cast<int>(j % nb); };
  long i = 0, j = 0;
  while (i < na || j < nb) {
    const bool advance_a = j == nb || (i < na && (2 * (i + 1) + oa) * nb <= (2 * (j + 1) + ob) * na);
    if (advance_a) {
      mesh.triangles.push_back({A(i + 1), A(i), B(j)});
      ++i;
    } else {
      mesh.triangles.push_back({B(j), B(j + 1), A(i)});
      ++j;
    }
  }
}

/// Vertices per sector for a ring of radius r.
int sector_count(double r, double edge) { return std::max(1, static_cast<int>(std::lround(kTwoPi * r / (6.0 * edge)))); }

}  // namespace

RevolvedMesh revolve(const std::vector<Vec2>& meridian, double edge, bool equal_counts) {
  if (meridian.size() < 2 || !(edge > 0)) throw std::invalid_argument("revolve: need two meridian points and an edge > 0");
  RevolvedMesh out;
  std::size_t k0 = 0;
  if (meridian.front().x == 0.0) {
    out.rings.apex = 0;
    out.mesh.vertices.push_back({0.0, meridian.front().y, 0.0});
    k0 = 1;
  }
  int largest = 1;
  for (std::size_t k = k0; k < meridian.size(); ++k) largest = std::max(largest, sector_count(meridian[k].x, edge));
  for (std::size_t k = k0; k < meridian.size(); ++k) {
    const int n = 6 * (equal_counts ? largest : sector_count(meridian[k].x, edge));
    const double offset = 0.5 * static_cast<double>((k - k0) % 2);
    out.rings.first.push_back(static_cast<int>(out.mesh.vertices.size()));
    out.rings.count.push_back(n);
    out.rings.offset.push_back(offset);
    out.rings.radius_m.push_back(meridian[k].x);
    for (int i = 0; i < n; ++i) {
      const double phi = kTwoPi * (i + offset) / n;
      out.mesh.vertices.push_back({meridian[k].x * std::cos(phi), meridian[k].y, meridian[k].x * std::sin(phi)});
    }
  }
  if (out.rings.apex >= 0) add_fan(out.mesh, out.rings.apex, out.rings.first[0], out.rings.count[0]);
  for (std::size_t k = 0; k + 1 < out.rings.first.size(); ++k) zip_rings(out.mesh, out.rings, k, k + 1);
  return out;
}

RevolvedMesh bell_mesh(double diameter_m, double height_m, double edge) {
  // The slice's own profile (jellyfish::bell_profile), its right half from the apex to the tip.
  const std::vector<Vec2> fine = jellyfish::bell_profile(diameter_m, height_m, 256);
  double half_arc = 0.0;
  for (std::size_t i = 0; i < 256; ++i) half_arc += norm(fine[i + 1] - fine[i]);
  const int segments = std::max(2, static_cast<int>(std::lround(half_arc / (kRowSpacing * edge))));
  const std::vector<Vec2> profile = jellyfish::bell_profile(diameter_m, height_m, segments);
  const std::vector<Vec2> right(profile.begin() + segments, profile.end());
  return revolve(right, edge);
}

RevolvedMesh disc_mesh(double radius_m, double edge) {
  const int rings = std::max(1, static_cast<int>(std::lround(radius_m / (kRowSpacing * edge))));
  std::vector<Vec2> meridian;
  for (int k = 0; k <= rings; ++k) meridian.push_back({radius_m * k / rings, 0.0});
  return revolve(meridian, edge);
}

RevolvedMesh cylinder_mesh(double radius_m, double length_m, double edge) {
  const int rows = std::max(1, static_cast<int>(std::lround(length_m / (kRowSpacing * edge))));
  std::vector<Vec2> meridian;
  for (int k = 0; k <= rows; ++k) meridian.push_back({radius_m, length_m * k / rows});
  return revolve(meridian, edge, true);
}

namespace {

/// Each undirected edge (smaller, larger vertex) with the triangles' opposite vertices, and whether
/// the triangle runs along it from the smaller vertex.
using EdgeMap = std::map<std::pair<int, int>, std::vector<std::pair<int, bool>>>;

EdgeMap edge_map(const TriangleMesh& mesh) {
  EdgeMap edges;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const int a = t[static_cast<std::size_t>(e)], b = t[static_cast<std::size_t>((e + 1) % 3)];
      const int opposite = t[static_cast<std::size_t>((e + 2) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back({opposite, a < b});
    }
  return edges;
}

}  // namespace

std::vector<Hinge> interior_hinges(const TriangleMesh& mesh) {
  std::vector<Hinge> out;
  for (const auto& [edge, sides] : edge_map(mesh)) {
    if (sides.size() != 2) continue;
    if (sides[0].second == sides[1].second) throw std::invalid_argument("interior_hinges: inconsistently oriented triangles");
    // v0 → v1 is the direction the first triangle runs along the edge.
    const auto& first = sides[0].second ? sides[0] : sides[1];
    const auto& second = sides[0].second ? sides[1] : sides[0];
    out.push_back({{edge.first, edge.second, first.first, second.first}});
  }
  return out;
}

std::vector<int> boundary_vertices(const TriangleMesh& mesh) {
  std::vector<int> out;
  for (const auto& [edge, sides] : edge_map(mesh))
    if (sides.size() == 1) {
      out.push_back(edge.first);
      out.push_back(edge.second);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

double surface_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles)
    area += triangle_area(mesh.vertices[static_cast<std::size_t>(t[0])], mesh.vertices[static_cast<std::size_t>(t[1])],
                          mesh.vertices[static_cast<std::size_t>(t[2])]);
  return area;
}

std::vector<double> vertex_areas(const TriangleMesh& mesh) {
  std::vector<double> area(mesh.vertices.size(), 0.0);
  for (const auto& t : mesh.triangles) {
    const double third = triangle_area(mesh.vertices[static_cast<std::size_t>(t[0])], mesh.vertices[static_cast<std::size_t>(t[1])],
                                       mesh.vertices[static_cast<std::size_t>(t[2])]) / 3.0;
    for (int v : t) area[static_cast<std::size_t>(v)] += third;
  }
  return area;
}

double enclosed_volume(const std::vector<Vec3>& x, const TriangleMesh& mesh) {
  auto at = [&](int v) { return x[static_cast<std::size_t>(v)]; };
  double six_volume = 0.0;
  for (const auto& t : mesh.triangles) six_volume += at(t[0]).dot(at(t[1]).cross(at(t[2])));
  const EdgeMap edges = edge_map(mesh);
  Vec3 centre = Vec3::Zero();
  double rim = 0.0;
  for (const auto& [edge, sides] : edges)
    if (sides.size() == 1) centre += at(edge.first) + at(edge.second), rim += 2.0;
  if (rim > 0) centre /= rim;  // every rim vertex of a closed loop counted twice
  // The fan runs along each boundary edge against the triangle that has it: (b, a, centre).
  for (const auto& [edge, sides] : edges) {
    if (sides.size() != 1) continue;
    const int a = sides[0].second ? edge.first : edge.second, b = sides[0].second ? edge.second : edge.first;
    six_volume += at(b).dot(at(a).cross(centre));
  }
  return std::abs(six_volume) / 6.0;
}

}  // namespace jellysim::shell
