#include "geometry/extrapolation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "io/errors.hpp"

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
  /// Unit direction of angle σ on the disc: cos σ ê − sin σ ẑ.
  Vec3 direction(double sigma) const {
    return {std::cos(sigma) * e.x, std::cos(sigma) * e.y, -std::sin(sigma)};
  }
  Vec3 point(double sigma) const { return lift(centre) + radius * direction(sigma); }
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

void umbrella_indices(const UmbrellaLayout& L, std::vector<std::uint32_t>& idx) {
  const int J = L.disc_points;
  for (int j = 0; j < J; ++j) {  // fan around the exumbrellar apex
    const int jn = (j + 1) % J;
    idx.insert(idx.end(), {L.vertex(0, 0), L.vertex(1, j), L.vertex(1, jn)});
  }
  for (int r = 1; r + 2 < L.rows; ++r) {  // quads between rings r and r + 1, split into two triangles
    for (int j = 0; j < J; ++j) {
      const int jn = (j + 1) % J;
      const std::uint32_t a = L.vertex(r, j), b = L.vertex(r + 1, j), c = L.vertex(r + 1, jn), d = L.vertex(r, jn);
      idx.insert(idx.end(), {a, b, c, a, c, d});
    }
  }
  const int last = L.rows - 1;
  for (int j = 0; j < J; ++j) {  // fan around the subumbrellar apex
    const int jn = (j + 1) % J;
    idx.insert(idx.end(), {L.vertex(last - 1, j), L.vertex(last, 0), L.vertex(last - 1, jn)});
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

/// A tube around `line` (parallel-transported frames), appended to `mesh`.
void append_tube(const std::vector<Vec3>& line, int sides, double radius_m, Mesh& mesh) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  const std::size_t count = line.size();
  Vec3 normal = any_orthogonal(polyline_tangent(line, 0));
  for (std::size_t m = 0; m < count; ++m) {
    const Vec3 t = polyline_tangent(line, m);
    const Vec3 projected = normal - dot(normal, t) * t;
    normal = norm(projected) > 1e-12 ? normalized(projected) : any_orthogonal(t);
    const Vec3 binormal = cross(t, normal);
    const double r = radius_m * (1.0 - 0.7 * static_cast<double>(m) / static_cast<double>(count - 1));
    for (int s = 0; s < sides; ++s) {
      const double phi = kTwoPi * s / sides;
      const Vec3 dir = std::cos(phi) * normal + std::sin(phi) * binormal;
      mesh.positions.push_back(line[m] + r * dir);
      mesh.normals.push_back(dir);
    }
  }
  const auto S = static_cast<std::uint32_t>(sides);
  for (std::uint32_t m = 0; m + 1 < count; ++m) {
    for (std::uint32_t s = 0; s < S; ++s) {
      const std::uint32_t sn = (s + 1) % S;
      const std::uint32_t a = first + m * S + s, b = first + (m + 1) * S + s;
      const std::uint32_t c = first + (m + 1) * S + sn, d = first + m * S + sn;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, a, d, c});
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
  for (int r = 1; r + 1 < L.rows; ++r) {
    for (int j = 0; j < J; ++j) {
      const Vec3 along = x[L.vertex(r + 1, j)] - x[L.vertex(r - 1, j)];
      const Vec3 around = x[L.vertex(r, (j + 1) % J)] - x[L.vertex(r, (j + J - 1) % J)];
      normals[L.vertex(r, j)] = normalized(cross(along, around));  // eq. 7.9
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
  const GeometrySettings& s = settings_;
  const NoiseSettings& ns = s.noise;
  const RenderingSlice slice = make_rendering_slice(frame, s.latitude_samples, s.tentacle_samples, s.interpolant);
  const std::vector<Row> rows = umbrella_rows(slice);

  FrameGeometry out;
  out.time_s = frame.time_s;
  UmbrellaLayout& L = out.umbrella;
  L = {static_cast<int>(rows.size()), s.disc_points, (static_cast<int>(rows.size()) - 2) / 2};
  const int J = L.disc_points;
  const double length = length_scale_m_;

  // Unperturbed discs (Figure 7.6) and their eq. 7.9 normals.
  std::vector<Vec3> x(L.vertex_count()), n;
  x[L.vertex(0, 0)] = lift(rows.front().disc.centre);
  x[L.vertex(L.rows - 1, 0)] = lift(rows.back().disc.centre);
  for (int r = 1; r + 1 < L.rows; ++r)
    for (int j = 0; j < J; ++j) x[L.vertex(r, j)] = rows[static_cast<std::size_t>(r)].disc.point(kTwoPi * j / J);
  umbrella_normals(L, x, n);

  // Noise along the unperturbed normals (poles stay: d_i = 0 there and σ is undefined).
  for (int r = 1; r + 1 < L.rows; ++r) {
    const Row& row = rows[static_cast<std::size_t>(r)];
    const double d_i = latitude_distance(r, 0, L.rows - 1, L.rows - 1);
    const double kappa = row.exumbrella ? contraction_at(frame.muscles, frame.umbrella.size(), row.u, ns.max_contraction) : 0.0;
    for (int j = 0; j < J; ++j) {
      const double sigma = kTwoPi * j / J;  // eq. 7.12
      double c = ns.structural_weight * structural_noise(length, ns.structural_frequency, sigma, ns.structural_absolute);
      if (row.exumbrella) c += ns.compression_weight * compression_noise(length, kappa, ns.compression_frequency, sigma);
      if (ns.unstructured_weight != 0.0) {
        const double side = row.exumbrella || !ns.bend_shell ? 1.0 : -1.0;
        c += side * ns.unstructured_weight *
             unstructured_noise(noise_, ns, length, d_i, longitude_distance(j, J), frame.time_s);
      }
      x[L.vertex(r, j)] += c * n[L.vertex(r, j)];
    }
  }
  umbrella_normals(L, x, n);  // §7.4: normals of the perturbed surface

  out.mesh.positions = std::move(x);
  out.mesh.normals = std::move(n);
  umbrella_indices(L, out.mesh.indices);
  out.mesh.parts.push_back({"umbrella", 0, static_cast<std::uint32_t>(out.mesh.indices.size())});

  // Tentacles: discs between opposing slice tentacles, one 3D strand per angle.
  const std::size_t T = slice.tentacles.size();
  for (std::size_t t = 0; t < (T + 1) / 2; ++t) {
    const auto& left = slice.tentacles[t];
    const auto& right = slice.tentacles[T - 1 - t];
    if (t == T - 1 - t) {  // an unpaired middle strand stays a single line
      std::vector<Vec3> line;
      for (const Vec2& p : left) line.push_back(lift(p));
      out.tentacle_lines.push_back(std::move(line));
      continue;
    }
    for (int j = 0; j < s.tentacle_count; ++j) {
      const double sigma = kTwoPi * j / s.tentacle_count;
      const double d_j = longitude_distance(j, s.tentacle_count);
      std::vector<Vec3> line;
      for (std::size_t m = 0; m < left.size(); ++m) {
        const Disc disc = disc_of(left[m], right[m], slice.axis);
        Vec3 p = disc.point(sigma);
        if (ns.tentacles && ns.unstructured_weight != 0.0) {
          const double d_i = static_cast<double>(m) / static_cast<double>(left.size() - 1);
          p += ns.unstructured_weight * unstructured_noise(noise_, ns, length, d_i, d_j, frame.time_s) *
               disc.direction(sigma);
        }
        line.push_back(p);
      }
      out.tentacle_lines.push_back(std::move(line));
    }
  }
  if (!out.tentacle_lines.empty()) {
    const auto first_index = static_cast<std::uint32_t>(out.mesh.indices.size());
    for (const auto& line : out.tentacle_lines) append_tube(line, s.tube_sides, s.tentacle_radius_m, out.mesh);
    out.mesh.parts.push_back({"tentacles", first_index, static_cast<std::uint32_t>(out.mesh.indices.size()) - first_index});
  }
  return out;
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
