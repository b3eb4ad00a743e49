#pragma once
// Triangulated surfaces for the elastic shell (issue 40 part 3, docs/three-d.md): vertices (m),
// consistently oriented triangles, the interior edges with their two opposite vertices (the hinges
// of the bending energy), and generators for the bell of revolution, flat plates and cylinders.
//
// Surfaces of revolution are built ring by ring about the y axis (the slice's swimming axis: the
// slice plane is z = 0, azimuth 0 along +x). Every ring holds a multiple of six vertices and two
// neighbouring rings are joined in six identical sectors, so the mesh is exactly six-fold symmetric
// in its connectivity (and to round-off in its coordinates): a symmetric load gives a symmetric
// answer. Rings are about √3/2 of the target edge apart and hold about 2πr / edge vertices, so the
// triangles are close to equilateral everywhere, the apex included (a fan of six).
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "jellysim/math/vec2.hpp"

namespace jellysim::shell {

using Vec3 = Eigen::Vector3d;

struct TriangleMesh {
  std::vector<Vec3> vertices;                 ///< positions (m)
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices, one orientation throughout
};

/// An interior edge v[0] → v[1] shared by the triangles (v[0], v[1], v[2]) and (v[1], v[0], v[3]).
struct Hinge {
  std::array<int, 4> v{};
};

/// Rings of a surface of revolution: ring k's vertices are first[k] … first[k] + count[k] − 1 in
/// order of increasing azimuth; azimuth of vertex i of ring k is 2π (i + offset[k]) / count[k].
struct Rings {
  std::vector<int> first;
  std::vector<int> count;
  std::vector<double> offset;     ///< 0 or ½
  std::vector<double> radius_m;   ///< rest distance from the axis
  int apex = -1;                  ///< the vertex on the axis, or −1
};

struct RevolvedMesh {
  TriangleMesh mesh;
  Rings rings;
};

/// Revolves a meridian (r ≥ 0, y) about the y axis. A first point with r = 0 becomes an apex vertex
/// joined to the next ring by a fan. Each ring gets 6·max(1, round(2πr / (6·edge))) vertices;
/// `equal_counts` gives every ring the largest ring's count instead (a cylinder's lattice).
RevolvedMesh revolve(const std::vector<Vec2>& meridian, double target_edge_m, bool equal_counts = false);

/// The bell's subumbrellar surface: jellyfish::bell_profile(D, H, ·) (the slice's half-ellipse,
/// aperture centre at the origin, apex at (0, H, 0)) revolved, meridian points about √3/2 · edge apart.
RevolvedMesh bell_mesh(double diameter_m, double height_m, double target_edge_m);
/// A flat disc of radius `radius_m` in the plane y = 0 (normal ±y), rings √3/2 · edge apart.
RevolvedMesh disc_mesh(double radius_m, double target_edge_m);
/// An open cylinder of radius R and length L along y (from y = 0), equal rings of the same count.
RevolvedMesh cylinder_mesh(double radius_m, double length_m, double target_edge_m);

/// Interior edges with their opposite vertices, in a fixed order (by the smaller, then the larger
/// vertex index).
std::vector<Hinge> interior_hinges(const TriangleMesh& mesh);
/// Vertices on edges that belong to one triangle only, ascending.
std::vector<int> boundary_vertices(const TriangleMesh& mesh);

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c);
/// Σ triangle areas (m²).
double surface_area(const TriangleMesh& mesh);
/// A third of the area of each triangle at every vertex (m²): the lumped mass's share.
std::vector<double> vertex_areas(const TriangleMesh& mesh);

/// The volume (m³) enclosed by a surface with one boundary loop (the bell and its aperture) closed
/// by a fan from the centroid of the boundary vertices (the aperture plane): by the divergence
/// theorem, |Σ x_a · (x_b × x_c)| / 6 over the surface's and the fan's triangles, the fan oriented
/// against the surface's boundary edges.
double enclosed_volume(const std::vector<Vec3>& positions, const TriangleMesh& mesh);

}  // namespace jellysim::shell
