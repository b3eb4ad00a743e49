#include "jellysim/io/point_caches.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::io {
namespace {

using geometry::Vec3;

/// Appends a 32-bit value in the byte order the format wants (PC2 little-endian, MDD big-endian).
template <class T>
void append32(std::string& out, T value, bool big_endian) {
  static_assert(sizeof(T) == 4);
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  if (big_endian == (std::endian::native == std::endian::little))
    bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
  char bytes[4];
  std::memcpy(bytes, &bits, 4);
  out.append(bytes, 4);
}

void append_points(std::string& out, const std::vector<Vec3>& points, bool big_endian) {
  for (const Vec3& p : points)
    for (double c : {p.x, p.y, p.z}) append32(out, static_cast<float>(c), big_endian);
}

void check_frames(const PointFrames& frames, const char* format) {
  if (frames.empty()) throw InputError(std::string(format) + ": no frames to write");
  for (std::size_t k = 1; k < frames.size(); ++k)
    if (frames[k].size() != frames.front().size())
      throw InputError(std::string(format) + ": frame " + std::to_string(k) + " has " +
                       std::to_string(frames[k].size()) + " points, frame 0 has " + std::to_string(frames.front().size()));
}

/// The shortest text that reads back to the same float32 (USD's point3f).
std::string f32(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));
  return std::string(buf, end);
}

std::string tuple(const Vec3& p, bool single) {
  return single ? "(" + f32(p.x) + ", " + f32(p.y) + ", " + f32(p.z) + ")"
                : "(" + format_double(p.x) + ", " + format_double(p.y) + ", " + format_double(p.z) + ")";
}

bool is_identifier(const std::string& name) {
  if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

/// `name = [v0, v1, …]` sample lists: one line per frame.
void append_time_samples(std::string& out, const std::string& declaration, const PointFrames& frames) {
  out += "            " + declaration + ".timeSamples = {\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    out += "                " + std::to_string(k) + ": [";
    for (std::size_t p = 0; p < frames[k].size(); ++p) out += (p ? ", " : "") + tuple(frames[k][p], true);
    out += "],\n";
  }
  out += "            }\n";
}

/// primvars:st, face-varying: the per-vertex coordinates and each part's seam duplicates, indexed
/// per face corner.
void append_texture_coordinates(std::string& out, const UsdBody& b) {
  const geometry::Mesh& m = b.topology;
  std::vector<geometry::TexCoord> st = b.uv;
  std::vector<std::uint32_t> corners;
  for (const geometry::MeshPart& part : m.parts) {
    geometry::SeamSplit split = geometry::split_u_seam(b.uv, m.indices, part.first_index, part.index_count);
    const auto shift = static_cast<std::uint32_t>(st.size() - b.uv.size());
    for (std::uint32_t c : split.corners) corners.push_back(c >= b.uv.size() ? c + shift : c);
    st.insert(st.end(), split.uv.begin() + static_cast<std::ptrdiff_t>(b.uv.size()), split.uv.end());
  }
  out += "            texCoord2f[] primvars:st = [";
  for (std::size_t i = 0; i < st.size(); ++i) out += (i ? ", (" : "(") + f32(st[i][0]) + ", " + f32(st[i][1]) + ")";
  out += "] (\n                interpolation = \"faceVarying\"\n            )\n            int[] primvars:st:indices = [";
  for (std::size_t i = 0; i < corners.size(); ++i) out += (i ? ", " : "") + std::to_string(corners[i]);
  out += "]\n";
}

void append_subsets(std::string& out, const geometry::Mesh& m) {
  for (const geometry::MeshPart& part : m.parts) {
    if (!is_identifier(part.name)) continue;
    out += "\n            def GeomSubset \"" + part.name + "\" (\n                prepend apiSchemas = [\"MaterialBindingAPI\"]\n"
           "            )\n            {\n"
           "                uniform token elementType = \"face\"\n"
           "                uniform token familyName = \"materialBind\"\n                int[] indices = [";
    for (std::uint32_t t = part.first_index / 3; t < (part.first_index + part.index_count) / 3; ++t)
      out += (t == part.first_index / 3 ? "" : ", ") + std::to_string(t);
    out += "]\n                rel material:binding = </jellysim/Looks/" + part.name + ">\n            }\n";
  }
}

void append_mesh_prim(std::string& out, const UsdBody& b, double fps) {
  const geometry::Mesh& m = b.topology;
  out += "        def Mesh \"mesh\"\n        {\n            int[] faceVertexCounts = [";
  for (std::size_t t = 0; t < m.triangle_count(); ++t) out += t ? ", 3" : "3";
  out += "]\n            int[] faceVertexIndices = [";
  for (std::size_t i = 0; i < m.indices.size(); ++i) out += (i ? ", " : "") + std::to_string(m.indices[i]);
  out += "]\n";
  append_time_samples(out, "point3f[] points", b.points);
  if (b.velocities) {
    std::vector<double> times;
    for (std::size_t k = 0; k < b.points.size(); ++k) times.push_back(static_cast<double>(k) / fps);
    append_time_samples(out, "vector3f[] velocities", vertex_velocities(b.points, times));
  }
  out += "            uniform token orientation = \"rightHanded\"\n"
         "            uniform token subdivisionScheme = \"none\"\n"
         "            color3f[] primvars:displayColor = [" +
         tuple({b.colour[0], b.colour[1], b.colour[2]}, true) + "]\n";
  if (!b.uv.empty()) append_texture_coordinates(out, b);
  append_subsets(out, m);
  out += "        }\n";
}

/// One UsdPreviewSurface material /jellysim/Looks/NAME.
void append_material(std::string& out, const std::string& name, const std::array<double, 4>& rgba, double roughness,
                     double ior) {
  out += "        def Material \"" + name + "\"\n        {\n            token outputs:surface.connect = </jellysim/Looks/" +
         name + "/surface.outputs:surface>\n\n            def Shader \"surface\"\n            {\n"
         "                uniform token info:id = \"UsdPreviewSurface\"\n"
         "                color3f inputs:diffuseColor = " + tuple({rgba[0], rgba[1], rgba[2]}, true) + "\n"
         "                float inputs:opacity = " + f32(rgba[3]) + "\n"
         "                float inputs:roughness = " + f32(roughness) + "\n"
         "                float inputs:metallic = 0\n"
         "                float inputs:ior = " + f32(ior) + "\n"
         "                token outputs:surface\n            }\n        }\n";
}

void append_looks(std::string& out, const ExportLook& look) {
  const auto& b = look.bell_color;
  const auto& t = look.tentacle_color;
  out += "    def Scope \"Looks\"\n    {\n";
  append_material(out, "umbrella", {b[0], b[1], b[2], look.umbrella_opacity}, look.bell_roughness, look.ior);
  append_material(out, "tentacles", {t[0], t[1], t[2], look.tentacle_opacity}, look.tentacle_roughness, look.ior);
  append_material(out, "obstacles", look.obstacle_rgba, 0.9, 1.5);
  append_material(out, "snow", look.snow_rgba, 0.6, 1.5);
  out += "    }\n\n";
}

/// The camera's transform: rows right, up, back (USD's row vectors) and the eye.
std::string camera_matrix(const CameraFrame& f) {
  const auto [x, y, z] = camera_axes(f);
  auto row = [](Vec3 v, double w) {
    return "(" + format_double(v.x) + ", " + format_double(v.y) + ", " + format_double(v.z) + ", " + format_double(w) + ")";
  };
  return "( " + row(x, 0.0) + ", " + row(y, 0.0) + ", " + row(z, 0.0) + ", " + row(f.eye, 1.0) + " )";
}

void append_camera(std::string& out, const ExportCamera& camera) {
  // Apertures and focal length in the same unit: only their ratio (the field of view) matters here.
  const double focal = 50.0;
  const double vertical = 2.0 * focal * std::tan(0.5 * camera.fov_y_deg * std::acos(-1.0) / 180.0);
  out += "\n    def Camera \"camera\"\n    {\n        token projection = \"perspective\"\n"
         "        float focalLength = " + f32(focal) + "\n        float verticalAperture = " + f32(vertical) +
         "\n        float horizontalAperture = " + f32(vertical * camera.aspect) +
         "\n        float2 clippingRange = (" + f32(camera.near_m()) + ", " + f32(camera.far_m()) + ")\n";
  if (camera.still()) {
    out += "        matrix4d xformOp:transform = " + camera_matrix(camera.frames.front()) + "\n";
  } else {
    out += "        matrix4d xformOp:transform.timeSamples = {\n";
    for (std::size_t k = 0; k < camera.frames.size(); ++k)
      out += "            " + std::to_string(k) + ": " + camera_matrix(camera.frames[k]) + ",\n";
    out += "        }\n";
  }
  out += "        uniform token[] xformOpOrder = [\"xformOp:transform\"]\n    }\n";
}

}  // namespace

std::string pc2_bytes(const PointFrames& frames, double start_frame) {
  check_frames(frames, "PC2");
  std::string out("POINTCACHE2\0", 12);
  append32(out, std::int32_t{1}, false);
  append32(out, static_cast<std::int32_t>(frames.front().size()), false);
  append32(out, static_cast<float>(start_frame), false);
  append32(out, 1.0f, false);  // one sample per frame
  append32(out, static_cast<std::int32_t>(frames.size()), false);
  for (const auto& f : frames) append_points(out, f, false);
  return out;
}

std::string mdd_bytes(const PointFrames& frames, const std::vector<double>& times_s) {
  check_frames(frames, "MDD");
  if (times_s.size() != frames.size()) throw InputError("MDD: one time per frame is needed");
  std::string out;
  append32(out, static_cast<std::int32_t>(frames.size()), true);
  append32(out, static_cast<std::int32_t>(frames.front().size()), true);
  for (double t : times_s) append32(out, static_cast<float>(t), true);
  for (const auto& f : frames) append_points(out, f, true);
  return out;
}

std::string usda_text(const std::vector<UsdBody>& bodies, double fps, const std::string& comment,
                      const ExportLook& look, const ExportCamera& camera) {
  std::size_t frames = 0;
  for (const UsdBody& b : bodies) {
    if (!is_identifier(b.name)) throw InputError("USD: '" + b.name + "' is not a prim name");
    check_frames(b.points, "USD");
    if (!b.uv.empty() && b.uv.size() != b.points.front().size())
      throw InputError("USD: " + b.name + " needs one texture coordinate per point");
    if (b.root.size() != b.points.size()) throw InputError("USD: " + b.name + " needs one root position per frame");
    if (frames != 0 && b.points.size() != frames) throw InputError("USD: the bodies have different frame counts");
    frames = b.points.size();
  }
  if (frames == 0) throw InputError("USD: no bodies to write");
  if (!camera.frames.empty() && camera.frames.size() != frames)
    throw InputError("USD: the camera needs one frame per time code");
  std::string out = "#usda 1.0\n(\n    doc = \"" + comment +
                    "\"\n    defaultPrim = \"jellysim\"\n    upAxis = \"Y\"\n    metersPerUnit = 1\n"
                    "    timeCodesPerSecond = " + format_double(fps) + "\n    framesPerSecond = " + format_double(fps) +
                    "\n    startTimeCode = 0\n    endTimeCode = " + std::to_string(frames - 1) +
                    "\n)\n\ndef Xform \"jellysim\"\n{\n";
  append_looks(out, look);
  for (const UsdBody& b : bodies) {
    out += "    def Xform \"" + b.name + "\"\n    {\n        double3 xformOp:translate.timeSamples = {\n";
    for (std::size_t k = 0; k < frames; ++k) out += "            " + std::to_string(k) + ": " + tuple(b.root[k], false) + ",\n";
    out += "        }\n        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n\n";
    append_mesh_prim(out, b, fps);
    out += "    }\n";
  }
  if (!camera.frames.empty()) append_camera(out, camera);
  out += "}\n";
  return out;
}

}  // namespace jellysim::io
