#include "jellysim/geometry/extrapolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "jellysim/core/errors.hpp"

namespace jellysim::geometry {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

void require_int(int value, int min, int max, const char* field) {
  if (value < min || value > max)
    throw InputError(std::string(field) + " = " + std::to_string(value) + " is out of range [" + std::to_string(min) +
                     ", " + std::to_string(max) + "]");
}

void require_number(double value, bool ok, const char* field, const char* range) {
  if (!ok || !std::isfinite(value))
    throw InputError(std::string(field) + " = " + std::to_string(value) + " is out of range " + range);
}

/// One disc of Figure 7.6: centre, in-plane unit direction ê toward the right point, radius.
struct Disc {
  Vec2 centre;
  Vec2 e{1.0, 0.0};
  double radius = 0.0;
  /// Unit direction of angle σ on the disc, cos σ ê − sin σ ẑ, from cos σ and sin σ.
  Vec3 direction(double cos_sigma, double sin_sigma) const { return {cos_sigma * e.x, cos_sigma * e.y, -sin_sigma}; }
  Vec3 point(double cos_sigma, double sin_sigma) const { return lift(centre) + radius * direction(cos_sigma, sin_sigma); }
};

/// cos σ_j and sin σ_j of σ_j = 2πj/count (eq. 7.12), j = 0 … count − 1.
struct AngleTable {
  std::vector<double> cos, sin;
  explicit AngleTable(int count) : cos(static_cast<std::size_t>(count)), sin(static_cast<std::size_t>(count)) {
    for (int j = 0; j < count; ++j) {
      const double sigma = kTwoPi * j / count;
      cos[static_cast<std::size_t>(j)] = std::cos(sigma);
      sin[static_cast<std::size_t>(j)] = std::sin(sigma);
    }
  }
};

Disc disc_of(Vec2 left, Vec2 right, Vec2 axis) {
  const Vec2 d = right - left;
  const double length = norm(d);
  // A degenerate pair (both points equal) gets the direction perpendicular to the axis.
  const Vec2 e = length > 0.0 ? d / length : Vec2{axis.y, -axis.x};
  return {0.5 * (left + right), e, 0.5 * length};
}

/// Per umbrella row: its disc (rings only), surface side and umbrella parameter.
struct Row {
  Disc disc;
  bool exumbrella = false;
  double u = 0.0;  ///< parameter on the simulated umbrella (for the muscle contraction)
};

std::vector<Row> umbrella_rows(const RenderingSlice& slice) {
  const int m = static_cast<int>(slice.subumbrella.size());
  const int h = (m - 1) / 2;
  std::vector<Row> rows;
  rows.reserve(static_cast<std::size_t>(2 * h + 2));
  auto add = [&](const std::vector<Vec2>& surface, int k, bool ex) {
    rows.push_back({disc_of(surface[static_cast<std::size_t>(k)], surface[static_cast<std::size_t>(m - 1 - k)], slice.axis),
                    ex, slice.umbrella_parameter[static_cast<std::size_t>(k)]});
  };
  add(slice.exumbrella, h, true);                          // row 0: exumbrellar apex (pole)
  for (int k = h - 1; k >= 0; --k) add(slice.exumbrella, k, true);  // apex → rim
  for (int k = 0; k <= h - 1; ++k) add(slice.subumbrella, k, false);  // rim → apex
  add(slice.subumbrella, h, false);                        // last row: subumbrellar apex (pole)
  return rows;
}

Vec3 face_normal(Vec3 a, Vec3 b, Vec3 c) { return cross(b - a, c - a); }

/// Replaces `idx` by the umbrella's triangles (its capacity is kept).
void umbrella_indices(const UmbrellaLayout& L, std::vector<std::uint32_t>& idx) {
  const int J = L.disc_points;
  idx.resize(static_cast<std::size_t>(6 * J * (L.rows - 3) + 6 * J));
  std::uint32_t* out = idx.data();
  for (int j = 0; j < J; ++j) {  // fan around the exumbrellar apex
    const int jn = (j + 1) % J;
    *out++ = L.vertex(0, 0);
    *out++ = L.vertex(1, j);
    *out++ = L.vertex(1, jn);
  }
  for (int r = 1; r + 2 < L.rows; ++r) {  // quads between rings r and r + 1, split into two triangles
    for (int j = 0; j < J; ++j) {
      const int jn = (j + 1) % J;
      const std::uint32_t a = L.vertex(r, j), b = L.vertex(r + 1, j), c = L.vertex(r + 1, jn), d = L.vertex(r, jn);
      out[0] = a, out[1] = b, out[2] = c, out[3] = a, out[4] = c, out[5] = d;
      out += 6;
    }
  }
  const int last = L.rows - 1;
  for (int j = 0; j < J; ++j) {  // fan around the subumbrellar apex
    const int jn = (j + 1) % J;
    *out++ = L.vertex(last - 1, j);
    *out++ = L.vertex(last, 0);
    *out++ = L.vertex(last - 1, jn);
  }
}

/// Unit tangent of a polyline at point m (central difference, one-sided at the ends).
Vec3 polyline_tangent(const std::vector<Vec3>& line, std::size_t m) {
  const std::size_t a = m == 0 ? 0 : m - 1, b = std::min(m + 1, line.size() - 1);
  return normalized(line[b] - line[a]);
}

/// A unit vector orthogonal to t.
Vec3 any_orthogonal(Vec3 t) {
  const Vec3 c = cross(t, Vec3{0.0, 0.0, 1.0});
  return norm(c) > 1e-6 ? normalized(c) : normalized(cross(t, Vec3{1.0, 0.0, 0.0}));
}

/// A tube around `line` (parallel-transported frames) written into mesh vertices from `first`
/// and indices from `first_index` (both already sized); `sides` angles in `angles`.
void write_tube(const std::vector<Vec3>& line, const AngleTable& angles, double radius_m, Mesh& mesh,
                std::size_t first, std::size_t first_index) {
  const std::size_t count = line.size(), S = angles.cos.size();
  Vec3* position = mesh.positions.data() + first;
  Vec3* normal_out = mesh.normals.data() + first;
  Vec3 normal = any_orthogonal(polyline_tangent(line, 0));
  for (std::size_t m = 0; m < count; ++m) {
    const Vec3 t = polyline_tangent(line, m);
    const Vec3 projected = normal - dot(normal, t) * t;
    normal = norm(projected) > 1e-12 ? normalized(projected) : any_orthogonal(t);
    const Vec3 binormal = cross(t, normal);
    const double r = radius_m * (1.0 - 0.7 * static_cast<double>(m) / static_cast<double>(count - 1));
    for (std::size_t s = 0; s < S; ++s) {  // φ_s = 2πs/sides
      const Vec3 dir = angles.cos[s] * normal + angles.sin[s] * binormal;
      *position++ = line[m] + r * dir;
      *normal_out++ = dir;
    }
  }
  std::uint32_t* out = mesh.indices.data() + first_index;
  const auto base = static_cast<std::uint32_t>(first), n = static_cast<std::uint32_t>(S);
  for (std::uint32_t m = 0; m + 1 < count; ++m) {
    for (std::uint32_t s = 0; s < n; ++s) {
      const std::uint32_t sn = (s + 1) % n;
      const std::uint32_t a = base + m * n + s, b = base + (m + 1) * n + s;
      const std::uint32_t c = base + (m + 1) * n + sn, d = base + m * n + sn;
      out[0] = a, out[1] = c, out[2] = b, out[3] = a, out[4] = d, out[5] = c;
      out += 6;
    }
  }
}

}  // namespace

void validate_geometry_settings(const GeometrySettings& s) {
  if (s.latitude_samples % 2 == 0)
    throw InputError("latitude_samples = " + std::to_string(s.latitude_samples) + " must be odd");
  require_int(s.latitude_samples, 5, 100001, "latitude_samples");
  require_int(s.disc_points, 8, 100000, "disc_points");
  require_int(s.tentacle_samples, 2, 100000, "tentacle_samples");
  require_int(s.tentacle_count, 1, 10000, "tentacle_count");
  require_int(s.tube_sides, 3, 64, "tube_sides");
  require_number(s.tentacle_radius_m, s.tentacle_radius_m > 0.0, "tentacle_radius", "(0, inf)");
  const NoiseSettings& n = s.noise;
  require_number(n.structural_weight, n.structural_weight >= 0.0, "structural_weight", "[0, inf)");
  require_number(n.compression_weight, n.compression_weight >= 0.0, "compression_weight", "[0, inf)");
  require_number(n.unstructured_weight, n.unstructured_weight >= 0.0, "unstructured_weight", "[0, inf)");
  require_number(n.structural_frequency, true, "structural_frequency", "(-inf, inf)");
  require_number(n.compression_frequency, true, "compression_frequency", "(-inf, inf)");
  require_number(n.max_contraction, n.max_contraction > 0.0 && n.max_contraction < 1.0, "max_contraction", "(0, 1)");
  require_number(n.latitude_frequency, true, "latitude_frequency", "(-inf, inf)");
  require_number(n.longitude_frequency, true, "longitude_frequency", "(-inf, inf)");
  require_number(n.time_frequency_hz, true, "time_frequency", "(-inf, inf)");
  require_number(n.length_scale_m, n.length_scale_m >= 0.0, "length_scale", "[0, inf)");
}

std::uint32_t UmbrellaLayout::vertex(int row, int j) const {
  if (row == 0) return 0;
  if (row == rows - 1) return vertex_count() - 1;
  return static_cast<std::uint32_t>(1 + (row - 1) * disc_points + j);
}

void umbrella_normals(const UmbrellaLayout& L, const std::vector<Vec3>& x, std::vector<Vec3>& normals) {
  const int J = L.disc_points;
  normals.resize(x.size());
  const auto row = [&](int r) { return x.data() + L.vertex(r, 0); };
  for (int r = 1; r + 1 < L.rows; ++r) {
    // Rows r − 1 and r + 1 (a pole: one vertex for every j, stride 0).
    const Vec3 *below = row(r - 1), *above = row(r + 1), *ring = row(r);
    const std::size_t below_step = r - 1 == 0 ? 0 : 1, above_step = r + 1 == L.rows - 1 ? 0 : 1;
    Vec3* out = normals.data() + L.vertex(r, 0);
    for (int j = 0; j < J; ++j) {
      const auto k = static_cast<std::size_t>(j);
      const Vec3 along = above[above_step * k] - below[below_step * k];
      const Vec3 around = ring[j + 1 == J ? 0 : k + 1] - ring[j == 0 ? static_cast<std::size_t>(J - 1) : k - 1];
      out[k] = normalized(cross(along, around));  // eq. 7.9
    }
  }
  Vec3 top, bottom;
  for (int j = 0; j < J; ++j) {
    const int jn = (j + 1) % J;
    top += face_normal(x[L.vertex(0, 0)], x[L.vertex(1, j)], x[L.vertex(1, jn)]);
    bottom += face_normal(x[L.vertex(L.rows - 2, j)], x[L.vertex(L.rows - 1, 0)], x[L.vertex(L.rows - 2, jn)]);
  }
  normals[L.vertex(0, 0)] = normalized(top);
  normals[L.vertex(L.rows - 1, 0)] = normalized(bottom);
}

GeometryBuilder::GeometryBuilder(const GeometrySettings& settings, double length_scale_m)
    : settings_(settings), length_scale_m_(length_scale_m), noise_(settings.noise.seed) {
  validate_geometry_settings(settings_);
  if (!(length_scale_m > 0.0) || !std::isfinite(length_scale_m))
    throw InputError("noise length scale = " + std::to_string(length_scale_m) + " must be in (0, inf)");
}

double resolve_noise_length(const NoiseSettings& noise, const jellyfish::SliceFrame& first_frame) {
  if (noise.length_scale_m > 0.0) return noise.length_scale_m;
  validate_slice(first_frame);
  return bell_height(first_frame);
}

FrameGeometry GeometryBuilder::build(const jellyfish::SliceFrame& frame) const {
  FrameGeometry out;
  build(frame, out);
  return out;
}

namespace {

/// The unperturbed discs (Figure 7.6): ring r of the umbrella grid on row r's disc, at the angles σ_j.
void place_discs(const std::vector<Row>& rows, const UmbrellaLayout& L, std::vector<Vec3>& x) {
  const int J = L.disc_points;
  const AngleTable disc_angles(J);  // σ_j, eq. 7.12
  x.resize(L.vertex_count());
  x[L.vertex(0, 0)] = lift(rows.front().disc.centre);
  x[L.vertex(L.rows - 1, 0)] = lift(rows.back().disc.centre);
  for (int r = 1; r + 1 < L.rows; ++r) {
    const Disc& disc = rows[static_cast<std::size_t>(r)].disc;
    Vec3* ring = x.data() + L.vertex(r, 0);
    for (std::size_t j = 0; j < static_cast<std::size_t>(J); ++j) ring[j] = disc.point(disc_angles.cos[j], disc_angles.sin[j]);
  }
}

/// The umbrella noise's tables. The terms that depend on j only are tabulated; the Perlin term
/// depends on (d_i, d_j), which repeat (d_i: row r and rows − 1 − r; d_j: j and J − j), so each
/// distinct pair is evaluated once.
struct UmbrellaNoise {
  std::vector<double> structural, ridge;  // [j]
  std::vector<double> perlin;             // [min(r, rows − 1 − r)][min(j, J − j)], when unstructured
  bool unstructured = false;
  int half_j = 0;
};

UmbrellaNoise umbrella_noise(const ImprovedNoise& noise, const NoiseSettings& ns, double length,
                             const UmbrellaLayout& L, double time_s) {
  const int J = L.disc_points;
  UmbrellaNoise t;
  t.structural.resize(static_cast<std::size_t>(J));
  t.ridge.resize(static_cast<std::size_t>(J));
  for (int j = 0; j < J; ++j) {
    const double sigma = kTwoPi * j / J;  // eq. 7.12
    t.structural[static_cast<std::size_t>(j)] =  // eq. 7.10/7.11 as the ring can draw it: no saw-tooth
        ns.structural_weight * structural_noise_resolved(length, ns.structural_frequency, sigma, ns.structural_absolute, J);
    t.ridge[static_cast<std::size_t>(j)] = compression_ridge(ns.compression_frequency, sigma);
  }
  t.unstructured = ns.unstructured_weight != 0.0;
  const int half_rows = (L.rows - 1) / 2;
  t.half_j = J / 2;
  if (t.unstructured) {
    t.perlin.resize(static_cast<std::size_t>((half_rows + 1) * (t.half_j + 1)));
    for (int ri = 1; ri <= half_rows; ++ri) {
      const double d_i = latitude_distance(ri, 0, L.rows - 1, L.rows - 1);
      for (int jj = 0; jj <= t.half_j; ++jj)
        t.perlin[static_cast<std::size_t>(ri * (t.half_j + 1) + jj)] =
            unstructured_noise(noise, ns, length, d_i, longitude_distance(jj, J), time_s);
    }
  }
  return t;
}

/// Noise along the unperturbed normals (poles stay: d_i = 0 there and σ is undefined).
void perturb_umbrella(const std::vector<Row>& rows, const jellyfish::SliceFrame& frame, const NoiseSettings& ns,
                      double length, const UmbrellaNoise& t, const UmbrellaLayout& L, std::vector<Vec3>& x,
                      const std::vector<Vec3>& n) {
  const int J = L.disc_points;
  for (int r = 1; r + 1 < L.rows; ++r) {
    const Row& row = rows[static_cast<std::size_t>(r)];
    const double kappa = row.exumbrella ? contraction_at(frame.muscles, frame.umbrella.size(), row.u, ns.max_contraction) : 0.0;
    const double compression_scale = length * kappa;  // eq. 7.15: ϑ κ {…}
    const double side = row.exumbrella || !ns.bend_shell ? 1.0 : -1.0;
    const double* noise_row = t.unstructured ? t.perlin.data() + std::min(r, L.rows - 1 - r) * (t.half_j + 1) : nullptr;
    Vec3* ring = x.data() + L.vertex(r, 0);
    const Vec3* normal = n.data() + L.vertex(r, 0);
    for (int j = 0; j < J; ++j) {
      const auto k = static_cast<std::size_t>(j);
      double c = t.structural[k];
      if (row.exumbrella) c += ns.compression_weight * (compression_scale * t.ridge[k]);
      if (t.unstructured) c += side * ns.unstructured_weight * noise_row[std::min(j, J - j)];
      ring[k] += c * normal[k];
    }
  }
}

/// The tentacle strands' noise along a pair's discs: [m][min(j, count − j)].
void strand_noise_table(const ImprovedNoise& noise, const GeometrySettings& s, double length, double time_s,
                        std::size_t M, std::vector<double>& table) {
  const NoiseSettings& ns = s.noise;
  const int half_count = s.tentacle_count / 2;
  table.resize(M * static_cast<std::size_t>(half_count + 1));
  for (std::size_t m = 0; m < M; ++m) {
    const double d_i = static_cast<double>(m) / static_cast<double>(M - 1);
    for (int jj = 0; jj <= half_count; ++jj)
      table[m * static_cast<std::size_t>(half_count + 1) + static_cast<std::size_t>(jj)] =
          ns.unstructured_weight *
          unstructured_noise(noise, ns, length, d_i, longitude_distance(jj, s.tentacle_count), time_s);
  }
}

/// Tentacles: discs between opposing slice tentacles, one 3D strand per angle (an unpaired middle
/// strand stays a single line).
void build_strands(const RenderingSlice& slice, const GeometrySettings& s, const ImprovedNoise& noise, double length,
                   double time_s, std::vector<std::vector<Vec3>>& lines) {
  const std::size_t T = slice.tentacles.size();
  lines.resize(T / 2 * static_cast<std::size_t>(s.tentacle_count) + T % 2);
  const AngleTable strand_angles(s.tentacle_count);
  const std::size_t row_length = static_cast<std::size_t>(s.tentacle_count / 2 + 1);
  const bool noisy = s.noise.tentacles && s.noise.unstructured_weight != 0.0;
  std::vector<Disc> discs;
  std::vector<double> strand_noise;
  std::size_t line_index = 0;
  for (std::size_t t = 0; t < (T + 1) / 2; ++t) {
    const auto& left = slice.tentacles[t];
    const auto& right = slice.tentacles[T - 1 - t];
    const std::size_t M = left.size();
    if (t == T - 1 - t) {
      std::vector<Vec3>& line = lines[line_index++];
      line.resize(M);
      for (std::size_t m = 0; m < M; ++m) line[m] = lift(left[m]);
      continue;
    }
    discs.resize(M);
    for (std::size_t m = 0; m < M; ++m) discs[m] = disc_of(left[m], right[m], slice.axis);
    if (noisy) strand_noise_table(noise, s, length, time_s, M, strand_noise);
    for (int j = 0; j < s.tentacle_count; ++j) {
      const double cs = strand_angles.cos[static_cast<std::size_t>(j)], sn = strand_angles.sin[static_cast<std::size_t>(j)];
      const auto jj = static_cast<std::size_t>(std::min(j, s.tentacle_count - j));
      std::vector<Vec3>& line = lines[line_index++];
      line.resize(M);
      for (std::size_t m = 0; m < M; ++m) {
        Vec3 p = discs[m].point(cs, sn);
        if (noisy) p += strand_noise[m * row_length + jj] * discs[m].direction(cs, sn);
        line[m] = p;
      }
    }
  }
}

}  // namespace

void append_tentacle_tubes(const std::vector<std::vector<Vec3>>& lines, const GeometrySettings& s, Mesh& mesh) {
  const AngleTable tube_angles(s.tube_sides);
  const auto S = static_cast<std::size_t>(s.tube_sides);
  std::size_t vertices = mesh.positions.size(), indices = mesh.indices.size();
  for (const auto& line : lines) {
    vertices += line.size() * S;
    indices += (line.size() - 1) * S * 6;
  }
  const std::size_t first_index = mesh.indices.size();
  std::size_t vertex = mesh.positions.size(), index = first_index;
  mesh.positions.resize(vertices);
  mesh.normals.resize(vertices);
  mesh.indices.resize(indices);
  for (const auto& line : lines) {
    write_tube(line, tube_angles, s.tentacle_radius_m, mesh, vertex, index);
    vertex += line.size() * S;
    index += (line.size() - 1) * S * 6;
  }
  mesh.parts.push_back({"tentacles", static_cast<std::uint32_t>(first_index),
                        static_cast<std::uint32_t>(indices - first_index)});
}

std::uint32_t umbrella_vertex_count(const FrameGeometry& g) {
  const MeshPart* part = g.mesh.part("umbrella");
  if (part == nullptr || part->index_count == 0) return 0;
  const VertexRange r = vertex_range(g.mesh, *part);
  return r.first + r.count;
}

void GeometryBuilder::build(const jellyfish::SliceFrame& frame, FrameGeometry& out) const {
  const GeometrySettings& s = settings_;
  const RenderingSlice slice = make_rendering_slice(frame, s.latitude_samples, s.tentacle_samples, s.interpolant);
  const std::vector<Row> rows = umbrella_rows(slice);

  out.time_s = frame.time_s;
  out.umbrella_uv.clear();  // the ring layout gives the texture coordinates
  UmbrellaLayout& L = out.umbrella;
  L = {static_cast<int>(rows.size()), s.disc_points, (static_cast<int>(rows.size()) - 2) / 2};
  std::vector<Vec3>& x = out.mesh.positions;
  std::vector<Vec3>& n = out.mesh.normals;
  place_discs(rows, L, x);
  umbrella_normals(L, x, n);  // eq. 7.9
  const UmbrellaNoise tables = umbrella_noise(noise_, s.noise, length_scale_m_, L, frame.time_s);
  perturb_umbrella(rows, frame, s.noise, length_scale_m_, tables, L, x, n);
  umbrella_normals(L, x, n);  // §7.4: normals of the perturbed surface

  umbrella_indices(L, out.mesh.indices);
  out.mesh.parts.resize(1);
  out.mesh.parts[0] = {"umbrella", 0, static_cast<std::uint32_t>(out.mesh.indices.size())};

  build_strands(slice, s, noise_, length_scale_m_, frame.time_s, out.tentacle_lines);
  if (!out.tentacle_lines.empty()) append_tentacle_tubes(out.tentacle_lines, s, out.mesh);
}

Animation build_animation(const std::vector<jellyfish::SliceFrame>& frames, const GeometrySettings& settings) {
  if (frames.empty()) throw InputError("no slice frames to build an animation from");
  const GeometryBuilder builder(settings, resolve_noise_length(settings.noise, frames.front()));
  Animation animation;
  for (const auto& frame : frames) {
    animation.times_s.push_back(frame.time_s);
    animation.frames.push_back(builder.build(frame).mesh);
  }
  validate_animation(animation);
  return animation;
}

}  // namespace jellysim::geometry
