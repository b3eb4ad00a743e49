#include "jellysim/geometry/surface_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "jellysim/core/errors.hpp"
#include "jellysim/geometry/spline.hpp"

namespace jellysim::geometry {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) { return (static_cast<std::uint64_t>(a) << 32) | b; }

/// The triangles' directed edges a → b, sorted (as a << 32 | b).
std::vector<std::uint64_t> directed_edges(const std::vector<Triangle>& triangles) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles)
    for (int c = 0; c < 3; ++c) edges.push_back(edge_key(t[static_cast<std::size_t>(c)], t[static_cast<std::size_t>((c + 1) % 3)]));
  std::sort(edges.begin(), edges.end());
  return edges;
}

/// The margin: the directed edges a → b whose reverse no triangle has, in the triangles' order.
/// Throws InputError when an edge is used twice in one direction (inconsistent orientation, or an
/// edge of more than two triangles).
std::vector<std::array<std::uint32_t, 2>> margin_edges(const std::vector<Triangle>& triangles) {
  const std::vector<std::uint64_t> edges = directed_edges(triangles);
  if (const auto twice = std::adjacent_find(edges.begin(), edges.end()); twice != edges.end())
    throw InputError("surface: the edge " + std::to_string(*twice >> 32) + " → " + std::to_string(*twice & 0xffffffffu) +
                     " is used twice in one direction (triangles not consistently oriented, or an edge of more than two)");
  std::vector<std::array<std::uint32_t, 2>> margin;
  for (const Triangle& t : triangles)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = t[static_cast<std::size_t>(c)], b = t[static_cast<std::size_t>((c + 1) % 3)];
      if (!std::binary_search(edges.begin(), edges.end(), edge_key(b, a))) margin.push_back({a, b});
    }
  if (margin.empty()) throw InputError("surface: no margin (a closed surface has no cavity opening to draw)");
  return margin;
}

/// The mean of the margin's vertices (each once): the middle of the aperture.
Vec3 margin_centroid(const std::vector<Vec3>& x, const std::vector<std::array<std::uint32_t, 2>>& margin) {
  Vec3 sum;
  for (const auto& e : margin) sum += x[e[0]];  // each margin vertex starts one margin edge
  return sum / static_cast<double>(margin.size());
}

/// Σ over the triangles at each vertex of (b − a) × (c − a): area-weighted normals, not normalised.
void summed_face_normals(const std::vector<Vec3>& x, const std::uint32_t* indices, std::size_t index_count,
                         std::vector<Vec3>& sums) {
  sums.assign(x.size(), Vec3{});
  for (std::size_t k = 0; k < index_count; k += 3) {
    const std::uint32_t a = indices[k], b = indices[k + 1], c = indices[k + 2];
    const Vec3 n = cross(x[b] - x[a], x[c] - x[a]);
    sums[a] += n, sums[b] += n, sums[c] += n;
  }
}

void require_finite(const std::vector<Vec3>& points, const std::string& what) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z))
      throw InputError(what + ": point " + std::to_string(i) + " is not finite");
}

/// Frame k's counts against frame 0's, its points finite.
void check_frame(const SurfaceFrames& f, std::size_t k) {
  const std::string name = "surface frame " + std::to_string(k);
  if (f.surface[k].size() != f.surface[0].size())
    throw InputError(name + " has " + std::to_string(f.surface[k].size()) + " vertices, frame 0 " +
                     std::to_string(f.surface[0].size()));
  require_finite(f.surface[k], name);
  if (f.tentacles[k].size() != f.tentacles[0].size())
    throw InputError(name + " has " + std::to_string(f.tentacles[k].size()) + " tentacle strands, frame 0 " +
                     std::to_string(f.tentacles[0].size()));
  for (std::size_t t = 0; t < f.tentacles[k].size(); ++t) {
    const std::string strand = name + " tentacle " + std::to_string(t);
    if (f.tentacles[k][t].size() != f.tentacles[0][t].size() || f.tentacles[k][t].size() < 2)
      throw InputError(strand + " has " + std::to_string(f.tentacles[k][t].size()) +
                       " nodes (needs ≥ 2 and frame 0's count)");
    require_finite(f.tentacles[k][t], strand);
  }
  if (k > 0 && !(f.time_s[k] > f.time_s[k - 1])) throw InputError("surface frame times must increase (frame " + std::to_string(k) + ")");
}

}  // namespace

void validate_surface_frames(const SurfaceFrames& f) {
  if (f.surface.empty()) throw InputError("no surface frames to render");
  if (f.time_s.size() != f.surface.size() || f.tentacles.size() != f.surface.size())
    throw InputError("surface frames: " + std::to_string(f.surface.size()) + " surfaces, " +
                     std::to_string(f.time_s.size()) + " times and " + std::to_string(f.tentacles.size()) +
                     " tentacle sets (one each per frame)");
  if (!(f.thickness_m > 0.0) || !std::isfinite(f.thickness_m))
    throw InputError("surface thickness = " + std::to_string(f.thickness_m) + " is out of range (0, inf)");
  if (f.triangles.empty()) throw InputError("surface: no triangles");
  for (std::size_t t = 0; t < f.triangles.size(); ++t) {
    const Triangle& tri = f.triangles[t];
    if (std::max({tri[0], tri[1], tri[2]}) >= f.surface[0].size())
      throw InputError("surface triangle " + std::to_string(t) + " has a vertex index out of range");
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw InputError("surface triangle " + std::to_string(t) + " repeats a vertex");
  }
  for (std::size_t k = 0; k < f.surface.size(); ++k) check_frame(f, k);
  margin_edges(f.triangles);
}

double signed_cavity_volume(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles) {
  // With the aperture's middle c as the origin the closing fan's terms vanish (one corner is c), so
  // the divergence theorem's Σ x_a · (x_b × x_c) / 6 runs over the surface's triangles only.
  const Vec3 c = margin_centroid(x, margin_edges(triangles));
  double sum = 0.0;
  for (const Triangle& t : triangles) sum += dot(x[t[0]] - c, cross(x[t[1]] - c, x[t[2]] - c));
  return sum / 6.0;
}

std::array<Vec3, 2> surface_path_bounds(const SurfaceFrames& f) {
  Vec3 lo = f.surface.front().front(), hi = lo;
  const auto take = [&](Vec3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  };
  for (std::size_t k = 0; k < f.surface.size(); ++k) {
    for (Vec3 p : f.surface[k]) take(p);
    for (const auto& strand : f.tentacles[k])
      for (Vec3 p : strand) take(p);
  }
  return {lo, hi};
}

namespace {

/// +1 when the triangles' normals point out of the cavity (positive signed volume), −1 when into
/// it; a surface enclosing no volume has no inside to tell (InputError).
int cavity_orientation(const SurfaceFrames& f) {
  const double volume = signed_cavity_volume(f.surface.front(), f.triangles);
  const std::array<Vec3, 2> box = surface_path_bounds(f);
  const double extent = norm(box[1] - box[0]);
  if (!(std::abs(volume) > 1e-9 * extent * extent * extent))
    throw InputError("surface: it encloses no cavity with its aperture, so its outside is undefined");
  return volume > 0.0 ? 1 : -1;
}

/// The closed wall (N surface vertices): the subumbrella [0, N) facing the cavity, the exumbrella
/// [N, 2N) facing away from it, and the rim band: for each margin edge p → q of the subumbrella as
/// wound in the wall, the quad q, p, p + N, q + N as two triangles, so every edge of the wall is in
/// two triangles, once each way (counter-clockwise seen from outside the mesoglea).
std::vector<std::uint32_t> wall_indices(const std::vector<Triangle>& triangles, std::uint32_t N, int orientation) {
  std::vector<Triangle> sub = triangles;
  if (orientation > 0)
    for (Triangle& t : sub) std::swap(t[1], t[2]);  // the given normals point away from the cavity
  std::vector<std::uint32_t> idx;
  idx.reserve(2 * 3 * sub.size());
  for (const Triangle& t : sub) idx.insert(idx.end(), {t[0], t[1], t[2]});
  for (const Triangle& t : sub) idx.insert(idx.end(), {t[0] + N, t[2] + N, t[1] + N});
  for (const auto& [p, q] : margin_edges(sub)) idx.insert(idx.end(), {q, p, p + N, q, p + N, q + N});
  return idx;
}

/// The bell's axis at frame 0: its vector area Σ (b − a) × (c − a) / 2 turned away from the cavity
/// (from the aperture toward the apex for a dome), unit.
Vec3 bell_axis(const SurfaceFrames& f, int orientation) {
  Vec3 area;
  const std::vector<Vec3>& x = f.surface.front();
  for (const Triangle& t : f.triangles) area += cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]);
  return normalized(static_cast<double>(orientation) * area);
}

/// Texture coordinates fixed by frame 0, the two surfaces sharing them (a two-sided decal, as the
/// slice's): u the azimuth about the axis through the aperture's middle over 2π (0 toward +x, rising
/// toward −z as the slice's σ_j; ½ on the axis), v = 1 − height / the highest vertex's height along
/// the axis (0 at the apex, 1 at the aperture's plane, clamped to [0, 1]).
std::vector<std::array<float, 2>> wall_texture_coordinates(const SurfaceFrames& f, int orientation) {
  const std::vector<Vec3>& x = f.surface.front();
  const Vec3 axis = bell_axis(f, orientation);
  const Vec3 c = margin_centroid(x, margin_edges(f.triangles));
  Vec3 e1 = Vec3{1.0, 0.0, 0.0} - axis.x * axis;
  if (norm(e1) < 1e-6) e1 = Vec3{0.0, 0.0, 1.0} - axis.z * axis;
  e1 = normalized(e1);
  const Vec3 e2 = cross(axis, e1);
  double top = 0.0;
  for (const Vec3& p : x) top = std::max(top, dot(p - c, axis));
  const std::array<Vec3, 2> box = surface_path_bounds(f);
  const double size = norm(box[1] - box[0]);
  std::vector<std::array<float, 2>> uv(2 * x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec3 r = x[i] - c;
    const double a = dot(r, e1), b = dot(r, e2);
    double u = std::hypot(a, b) > 1e-9 * size ? std::atan2(b, a) / (2.0 * std::numbers::pi) : 0.5;
    if (u < 0.0) u += 1.0;
    if (static_cast<float>(u) >= 1.0f) u = 0.0;  // just below 0 wrapped: the seam's u = 0
    const double v = top > 0.0 ? std::clamp(1.0 - dot(r, axis) / top, 0.0, 1.0) : 0.0;
    uv[i] = uv[i + x.size()] = {static_cast<float>(u), static_cast<float>(v)};
  }
  return uv;
}

/// A polyline resampled as the slice's tentacles are (rendering_model.hpp): `samples` points at
/// uniform parameters of the interpolant through the nodes. The cubic acts on each coordinate alone,
/// so the 3D curve is the (x, y) and (z, 0) curves resampled together.
std::vector<Vec3> resample_strand(const std::vector<Vec3>& nodes, int samples, Interpolant interpolant) {
  std::vector<Vec2> xy, z0;
  for (const Vec3& p : nodes) xy.push_back({p.x, p.y}), z0.push_back({p.z, 0.0});
  const std::vector<Vec2> a = resample_open_curve(xy, samples, interpolant), b = resample_open_curve(z0, samples, interpolant);
  std::vector<Vec3> line(a.size());
  for (std::size_t m = 0; m < a.size(); ++m) line[m] = {a[m].x, a[m].y, b[m].x};
  return line;
}

}  // namespace

SurfaceGeometryBuilder::SurfaceGeometryBuilder(const SurfaceFrames& frames, const GeometrySettings& settings)
    : frames_(frames), settings_(settings) {
  validate_geometry_settings(settings_);
  validate_surface_frames(frames_);
  orientation_ = cavity_orientation(frames_);
  wall_indices_ = wall_indices(frames_.triangles, static_cast<std::uint32_t>(frames_.surface.front().size()), orientation_);
  wall_uv_ = wall_texture_coordinates(frames_, orientation_);
}

void SurfaceGeometryBuilder::build(std::size_t frame, FrameGeometry& out) const {
  if (frame >= frame_count()) throw InputError("surface frame " + std::to_string(frame) + " does not exist");
  const std::vector<Vec3>& sub = frames_.surface[frame];
  const std::size_t N = sub.size();
  Mesh& mesh = out.mesh;
  // The exumbrella: each vertex moved by ϑ along the subumbrella's smooth normal, away from the cavity.
  summed_face_normals(sub, wall_indices_.data(), 3 * frames_.triangles.size(), mesh.normals);  // face the cavity
  mesh.positions.resize(2 * N);
  for (std::size_t i = 0; i < N; ++i) {
    mesh.positions[i] = sub[i];
    mesh.positions[i + N] = sub[i] - frames_.thickness_m * normalized(mesh.normals[i]);
  }
  mesh.indices = wall_indices_;
  summed_face_normals(mesh.positions, mesh.indices.data(), mesh.indices.size(), mesh.normals);  // lighting
  for (Vec3& n : mesh.normals) n = normalized(n);
  mesh.parts.assign(1, MeshPart{"umbrella", 0, static_cast<std::uint32_t>(mesh.indices.size())});
  out.time_s = frames_.time_s[frame];
  out.umbrella = {};
  out.umbrella_uv = wall_uv_;
  const auto& strands = frames_.tentacles[frame];
  out.tentacle_lines.resize(strands.size());
  for (std::size_t t = 0; t < strands.size(); ++t)
    out.tentacle_lines[t] = resample_strand(strands[t], settings_.tentacle_samples, settings_.interpolant);
  if (!out.tentacle_lines.empty()) append_tentacle_tubes(out.tentacle_lines, settings_, mesh);
}

FrameGeometry SurfaceGeometryBuilder::build(std::size_t frame) const {
  FrameGeometry out;
  build(frame, out);
  return out;
}

FrameGeometry surface_frame_geometry(const SurfaceFrames& frames, std::size_t frame, const GeometrySettings& settings) {
  return SurfaceGeometryBuilder(frames, settings).build(frame);
}

}  // namespace jellysim::geometry
