#include "jellysim/io/mesh_files.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::io {

static_assert(std::endian::native == std::endian::little, "binary mesh writers assume a little-endian host");

namespace {

using geometry::Mesh;
using geometry::MeshPart;
using geometry::Vec3;

template <typename T>
void append_raw(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

float as_float(double v) { return static_cast<float>(v); }

std::string float_text(double v) { return format_double(static_cast<double>(static_cast<float>(v))); }

void append_vec(std::string& out, const char* tag, Vec3 v) {
  out += tag;
  out += ' ' + float_text(v.x) + ' ' + float_text(v.y) + ' ' + float_text(v.z) + '\n';
}

/// The vertex range [first, first + count) a part's triangles use.
struct VertexRange {
  std::uint32_t first = 0, count = 0;
};

VertexRange vertex_range(const Mesh& mesh, const MeshPart& part) {
  if (part.index_count == 0) throw InputError("mesh part '" + part.name + "' has no triangles");
  const auto begin = mesh.indices.begin() + part.first_index;
  const auto [lo, hi] = std::minmax_element(begin, begin + part.index_count);
  return {*lo, *hi - *lo + 1};
}

}  // namespace

std::string obj_text(const Mesh& mesh, const std::string& comment, const std::string& object) {
  std::string out = "# " + comment + "\n# " + std::to_string(mesh.vertex_count()) + " vertices, " +
                    std::to_string(mesh.triangle_count()) + " triangles (jellysim)\n";
  if (!object.empty()) out += "o " + object + "\n";
  for (const Vec3& p : mesh.positions) append_vec(out, "v", p);
  for (const Vec3& n : mesh.normals) append_vec(out, "vn", n);
  for (const MeshPart& part : mesh.parts) {
    out += (object.empty() ? "g " : "usemtl ") + part.name + "\n";
    for (std::uint32_t k = part.first_index; k < part.first_index + part.index_count; k += 3) {
      out += 'f';
      for (int e = 0; e < 3; ++e) {
        const std::string v = std::to_string(mesh.indices[k + e] + 1);
        out += ' ' + v + "//" + v;
      }
      out += '\n';
    }
  }
  return out;
}

std::string ply_bytes(const Mesh& mesh, const std::string& comment) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment " + comment + "\nelement vertex " +
                    std::to_string(mesh.vertex_count()) +
                    "\nproperty float x\nproperty float y\nproperty float z\n"
                    "property float nx\nproperty float ny\nproperty float nz\nelement face " +
                    std::to_string(mesh.triangle_count()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    for (const Vec3& a : {mesh.positions[v], mesh.normals[v]}) {
      append_raw(out, static_cast<float>(a.x));
      append_raw(out, static_cast<float>(a.y));
      append_raw(out, static_cast<float>(a.z));
    }
  }
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    append_raw(out, static_cast<std::uint8_t>(3));
    for (int e = 0; e < 3; ++e) append_raw(out, mesh.indices[t + e]);
  }
  return out;
}

namespace {

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

/// Builds the BIN chunk and the bufferViews/accessors that describe it.
class GlbBuilder {
 public:
  nlohmann::json buffer_views = nlohmann::json::array();
  nlohmann::json accessors = nlohmann::json::array();
  std::string bin;

  /// A VEC3 float accessor of `count` vectors; min/max computed from the stored floats.
  int vec3(const std::vector<Vec3>& values, std::size_t first, std::size_t count, const Vec3* base) {
    std::array<float, 3> lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::max()};
    std::array<float, 3> hi{-lo[0], -lo[1], -lo[2]};
    const std::size_t offset = begin_view();
    for (std::size_t v = first; v < first + count; ++v) {
      // Deltas are differences of the stored floats, so base + delta reproduces the frame's floats.
      const Vec3 b = base ? base[v] : Vec3{};
      const std::array<float, 3> f = {as_float(values[v].x) - as_float(b.x), as_float(values[v].y) - as_float(b.y),
                                      as_float(values[v].z) - as_float(b.z)};
      for (int c = 0; c < 3; ++c) {
        append_raw(bin, f[static_cast<std::size_t>(c)]);
        lo[static_cast<std::size_t>(c)] = std::min(lo[static_cast<std::size_t>(c)], f[static_cast<std::size_t>(c)]);
        hi[static_cast<std::size_t>(c)] = std::max(hi[static_cast<std::size_t>(c)], f[static_cast<std::size_t>(c)]);
      }
    }
    const int view = end_view(offset, kArrayBuffer);
    return add_accessor(view, kFloat, count, "VEC3", nlohmann::json(lo), nlohmann::json(hi));
  }

  int indices(const Mesh& mesh, const MeshPart& part, std::uint32_t first_vertex) {
    const std::size_t offset = begin_view();
    std::uint32_t lo = std::numeric_limits<std::uint32_t>::max(), hi = 0;
    for (std::uint32_t k = part.first_index; k < part.first_index + part.index_count; ++k) {
      const std::uint32_t i = mesh.indices[k] - first_vertex;
      append_raw(bin, i);
      lo = std::min(lo, i);
      hi = std::max(hi, i);
    }
    const int view = end_view(offset, kElementArrayBuffer);
    return add_accessor(view, kUnsignedInt, part.index_count, "SCALAR", nlohmann::json::array({lo}),
                        nlohmann::json::array({hi}));
  }

  int scalars(const std::vector<float>& values, bool with_bounds) {
    const std::size_t offset = begin_view();
    for (float v : values) append_raw(bin, v);
    const int view = end_view(offset, -1);
    if (!with_bounds) return add_accessor(view, kFloat, values.size(), "SCALAR", {}, {});
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    return add_accessor(view, kFloat, values.size(), "SCALAR", nlohmann::json::array({*lo}),
                        nlohmann::json::array({*hi}));
  }

 private:
  std::size_t begin_view() {
    while (bin.size() % 4 != 0) bin.push_back('\0');
    return bin.size();
  }
  int end_view(std::size_t offset, int target) {
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}};
    if (target > 0) view["target"] = target;
    buffer_views.push_back(view);
    return static_cast<int>(buffer_views.size()) - 1;
  }
  int add_accessor(int view, int type, std::size_t count, const char* shape, const nlohmann::json& lo,
                   const nlohmann::json& hi) {
    nlohmann::json a = {{"bufferView", view}, {"componentType", type}, {"count", count}, {"type", shape}};
    if (!lo.is_null()) {
      a["min"] = lo;
      a["max"] = hi;
    }
    accessors.push_back(a);
    return static_cast<int>(accessors.size()) - 1;
  }
};

nlohmann::json material_json(const std::string& name, const GlbMaterial* m) {
  const std::array<double, 4> rgba = m ? m->rgba : std::array<double, 4>{0.8, 0.8, 0.8, 1.0};
  nlohmann::json j = {{"name", name},
                      {"pbrMetallicRoughness",
                       {{"baseColorFactor", rgba}, {"metallicFactor", 0.0}, {"roughnessFactor", m ? m->roughness : 0.5}}},
                      {"doubleSided", true}};
  if (rgba[3] < 1.0) j["alphaMode"] = "BLEND";
  return j;
}

std::string glb_container(const nlohmann::json& json, std::string bin) {
  std::string text = json.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  while (bin.size() % 4 != 0) bin.push_back('\0');
  std::string out;
  append_raw(out, std::uint32_t{0x46546C67});  // "glTF"
  append_raw(out, std::uint32_t{2});
  append_raw(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  append_raw(out, static_cast<std::uint32_t>(text.size()));
  append_raw(out, std::uint32_t{0x4E4F534A});  // "JSON"
  out += text;
  append_raw(out, static_cast<std::uint32_t>(bin.size()));
  append_raw(out, std::uint32_t{0x004E4942});  // "BIN\0"
  out += bin;
  return out;
}

}  // namespace

std::string glb_bytes(const geometry::Animation& animation, const std::vector<GlbMaterial>& materials) {
  geometry::validate_animation(animation);
  const Mesh& first = animation.frames.front();
  const std::size_t frames = animation.frames.size();
  GlbBuilder b;
  nlohmann::json primitives = nlohmann::json::array(), json_materials = nlohmann::json::array();
  for (const MeshPart& part : first.parts) {
    const VertexRange range = vertex_range(first, part);
    nlohmann::json targets = nlohmann::json::array();
    nlohmann::json primitive = {
        {"attributes",
         {{"POSITION", b.vec3(first.positions, range.first, range.count, nullptr)},
          {"NORMAL", b.vec3(first.normals, range.first, range.count, nullptr)}}},
        {"indices", b.indices(first, part, range.first)},
        {"material", json_materials.size()},
        {"mode", 4}};
    for (std::size_t k = 1; k < frames; ++k) {
      const Mesh& f = animation.frames[k];
      targets.push_back({{"POSITION", b.vec3(f.positions, range.first, range.count, first.positions.data())},
                         {"NORMAL", b.vec3(f.normals, range.first, range.count, first.normals.data())}});
    }
    if (frames > 1) primitive["targets"] = targets;
    primitives.push_back(primitive);
    const auto m = std::find_if(materials.begin(), materials.end(), [&](const GlbMaterial& g) { return g.part == part.name; });
    json_materials.push_back(material_json(part.name, m == materials.end() ? nullptr : &*m));
  }
  nlohmann::json mesh = {{"name", "jellyfish"}, {"primitives", primitives}};
  nlohmann::json json = {{"asset", {{"version", "2.0"}, {"generator", "jellysim " JELLYSIM_VERSION}}},
                         {"scene", 0},
                         {"scenes", {{{"nodes", {0}}}}},
                         {"nodes", {{{"name", "jellyfish"}, {"mesh", 0}}}},
                         {"materials", json_materials}};
  if (frames > 1) {
    mesh["weights"] = std::vector<double>(frames - 1, 0.0);
    std::vector<float> times, weights;
    for (std::size_t k = 0; k < frames; ++k) {
      times.push_back(static_cast<float>(animation.times_s[k] - animation.times_s[0]));
      for (std::size_t t = 1; t < frames; ++t) weights.push_back(t == k ? 1.0f : 0.0f);
    }
    for (std::size_t k = 1; k < frames; ++k)
      if (!(times[k] > times[k - 1])) throw InputError("animation frame times too close for single precision");
    const int input = b.scalars(times, true), output = b.scalars(weights, false);
    nlohmann::json sampler = {{"input", input}, {"output", output}, {"interpolation", "LINEAR"}};
    nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}};
    nlohmann::json swim = {{"name", "swim"}};
    swim["samplers"] = nlohmann::json::array({sampler});
    swim["channels"] = nlohmann::json::array({channel});
    json["animations"] = nlohmann::json::array({swim});
  }
  json["meshes"] = {mesh};
  json["accessors"] = b.accessors;
  json["bufferViews"] = b.buffer_views;
  while (b.bin.size() % 4 != 0) b.bin.push_back('\0');
  json["buffers"] = {{{"byteLength", b.bin.size()}}};
  return glb_container(json, std::move(b.bin));
}

GlbContents parse_glb(const std::string& bytes) {
  auto u32 = [&](std::size_t at) {
    if (at + 4 > bytes.size()) throw InputError("glb: truncated file");
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  if (u32(0) != 0x46546C67 || u32(4) != 2) throw InputError("glb: not a glTF 2.0 binary");
  if (u32(8) != bytes.size()) throw InputError("glb: header length differs from the file size");
  const std::uint32_t json_length = u32(12);
  if (u32(16) != 0x4E4F534A || 20 + json_length > bytes.size()) throw InputError("glb: bad JSON chunk");
  GlbContents c;
  c.json = nlohmann::json::parse(bytes.substr(20, json_length));
  const std::size_t bin_at = 20 + json_length;
  if (bin_at < bytes.size()) {
    const std::uint32_t bin_length = u32(bin_at);
    if (u32(bin_at + 4) != 0x004E4942 || bin_at + 8 + bin_length > bytes.size()) throw InputError("glb: bad BIN chunk");
    c.bin = bytes.substr(bin_at + 8, bin_length);
  }
  return c;
}

}  // namespace jellysim::io
