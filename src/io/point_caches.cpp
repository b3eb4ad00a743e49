#include "jellysim/io/point_caches.hpp"

#include <bit>
#include <charconv>
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

void append_mesh_prim(std::string& out, const UsdBody& b) {
  const geometry::Mesh& m = b.topology;
  out += "        def Mesh \"mesh\"\n        {\n            int[] faceVertexCounts = [";
  for (std::size_t t = 0; t < m.triangle_count(); ++t) out += t ? ", 3" : "3";
  out += "]\n            int[] faceVertexIndices = [";
  for (std::size_t i = 0; i < m.indices.size(); ++i) out += (i ? ", " : "") + std::to_string(m.indices[i]);
  out += "]\n            point3f[] points.timeSamples = {\n";
  for (std::size_t k = 0; k < b.points.size(); ++k) {
    out += "                " + std::to_string(k) + ": [";
    for (std::size_t p = 0; p < b.points[k].size(); ++p) out += (p ? ", " : "") + tuple(b.points[k][p], true);
    out += "],\n";
  }
  out += "            }\n            uniform token orientation = \"rightHanded\"\n"
         "            uniform token subdivisionScheme = \"none\"\n"
         "            color3f[] primvars:displayColor = [" +
         tuple({b.colour[0], b.colour[1], b.colour[2]}, true) + "]\n";
  for (const geometry::MeshPart& part : m.parts) {
    if (!is_identifier(part.name)) continue;
    out += "\n            def GeomSubset \"" + part.name + "\"\n            {\n"
           "                uniform token elementType = \"face\"\n"
           "                uniform token familyName = \"materialBind\"\n                int[] indices = [";
    for (std::uint32_t t = part.first_index / 3; t < (part.first_index + part.index_count) / 3; ++t)
      out += (t == part.first_index / 3 ? "" : ", ") + std::to_string(t);
    out += "]\n            }\n";
  }
  out += "        }\n";
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

std::string usda_text(const std::vector<UsdBody>& bodies, double fps, const std::string& comment) {
  std::size_t frames = 0;
  for (const UsdBody& b : bodies) {
    if (!is_identifier(b.name)) throw InputError("USD: '" + b.name + "' is not a prim name");
    check_frames(b.points, "USD");
    if (b.root.size() != b.points.size()) throw InputError("USD: " + b.name + " needs one root position per frame");
    if (frames != 0 && b.points.size() != frames) throw InputError("USD: the bodies have different frame counts");
    frames = b.points.size();
  }
  if (frames == 0) throw InputError("USD: no bodies to write");
  std::string out = "#usda 1.0\n(\n    doc = \"" + comment +
                    "\"\n    defaultPrim = \"jellysim\"\n    upAxis = \"Y\"\n    metersPerUnit = 1\n"
                    "    timeCodesPerSecond = " + format_double(fps) + "\n    framesPerSecond = " + format_double(fps) +
                    "\n    startTimeCode = 0\n    endTimeCode = " + std::to_string(frames - 1) +
                    "\n)\n\ndef Xform \"jellysim\"\n{\n";
  for (const UsdBody& b : bodies) {
    out += "    def Xform \"" + b.name + "\"\n    {\n        double3 xformOp:translate.timeSamples = {\n";
    for (std::size_t k = 0; k < frames; ++k) out += "            " + std::to_string(k) + ": " + tuple(b.root[k], false) + ",\n";
    out += "        }\n        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n\n";
    append_mesh_prim(out, b);
    out += "    }\n";
  }
  out += "}\n";
  return out;
}

}  // namespace jellysim::io
