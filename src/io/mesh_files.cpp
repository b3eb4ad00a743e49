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
using geometry::VertexRange;
using geometry::vertex_range;

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

constexpr int kFloat = 5126, kUnsignedInt = 5125, kShort = 5122, kUnsignedByte = 5121;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

/// Builds the BIN chunk and the bufferViews/accessors that describe it.
class GlbBuilder {
 public:
  nlohmann::json buffer_views = nlohmann::json::array();
  nlohmann::json accessors = nlohmann::json::array();
  std::string bin;

  /// A VEC3 float accessor of `count` vectors; min/max computed from the stored floats.
  int vec3(const std::vector<Vec3>& values, std::size_t first, std::size_t count, const Vec3* base,
           bool vertex_attribute = true) {
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
    const int view = end_view(offset, vertex_attribute ? kArrayBuffer : -1);
    return add_accessor(view, kFloat, count, "VEC3", nlohmann::json(lo), nlohmann::json(hi));
  }

  /// Position differences (frame − base) of `count` vertices as normalized shorts of `scale`
  /// (KHR_mesh_quantization), each vertex padded to 8 bytes (vertex attributes align to 4).
  int quantized_differences(const std::vector<Vec3>& frame, const std::vector<Vec3>& base, std::size_t first,
                            std::size_t count, double scale) {
    std::array<int, 3> lo{32767, 32767, 32767}, hi{-32767, -32767, -32767};
    const std::size_t offset = begin_view();
    for (std::size_t v = first; v < first + count; ++v) {
      const Vec3 d = frame[v] - base[v];
      const std::array<double, 3> c{d.x, d.y, d.z};
      for (std::size_t i = 0; i < 3; ++i) {
        const auto q = static_cast<std::int16_t>(std::clamp(std::lround(c[i] / scale * 32767.0), -32767L, 32767L));
        append_raw(bin, q);
        lo[i] = std::min(lo[i], static_cast<int>(q));
        hi[i] = std::max(hi[i], static_cast<int>(q));
      }
      append_raw(bin, std::int16_t{0});
    }
    const int view = end_view(offset, kArrayBuffer, 8);
    // Bounds of a normalized integer accessor are its raw integers.
    const int a = add_accessor(view, kShort, count, "VEC3", nlohmann::json(lo), nlohmann::json(hi));
    accessors[static_cast<std::size_t>(a)]["normalized"] = true;
    return a;
  }

  /// Values in [0, 1] as normalized unsigned bytes (0 or 255 for morph weights).
  int unit_bytes(const std::vector<std::uint8_t>& values) {
    const std::size_t offset = begin_view();
    bin.append(reinterpret_cast<const char*>(values.data()), values.size());
    const int view = end_view(offset, -1);
    const int a = add_accessor(view, kUnsignedByte, values.size(), "SCALAR", {}, {});
    accessors[static_cast<std::size_t>(a)]["normalized"] = true;
    return a;
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
  int end_view(std::size_t offset, int target, int stride = 0) {
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}};
    if (target > 0) view["target"] = target;
    if (stride > 0) view["byteStride"] = stride;
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

namespace {

/// The frames of a body kept as morph targets: every `every`-th after frame 0, and the last.
std::vector<std::size_t> kept_frames(std::size_t frames, int every) {
  std::vector<std::size_t> kept;
  for (std::size_t k = 1; k < frames; ++k)
    if (k % static_cast<std::size_t>(every) == 0 || k + 1 == frames) kept.push_back(k);
  return kept;
}

/// The largest position difference from frame 0 (metres) over the kept frames: the quantization scale.
double largest_difference(const GlbBody& body, const std::vector<std::size_t>& kept) {
  double s = 0.0;
  const Mesh& first = body.first;
  for (std::size_t k : kept)
    for (std::size_t v = 0; v < first.positions.size(); ++v) {
      const Vec3 d = body.positions[k][v] - first.positions[v];
      s = std::max({s, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
  return s > 0.0 ? s : 1.0;
}

}  // namespace

namespace {

void validate_glb_bodies(const std::vector<GlbBody>& bodies, const std::vector<double>& times_s, int every) {
  if (bodies.empty() || times_s.empty()) throw InputError("glb: no bodies or no frames");
  if (every < 1) throw InputError("glb: every must be at least 1");
  for (const GlbBody& body : bodies) {
    if (body.positions.size() != times_s.size())
      throw InputError("glb: " + body.name + " has " + std::to_string(body.positions.size()) + " frames for " +
                       std::to_string(times_s.size()) + " times");
    for (const auto& f : body.positions)
      if (f.size() != body.first.positions.size()) throw InputError("glb: " + body.name + " changes its vertex count");
    if (!body.root.empty() && body.root.size() != times_s.size())
      throw InputError("glb: " + body.name + " needs one root position per frame");
  }
}

/// The frame times from the first, in single precision (strictly increasing there, or InputError).
std::vector<float> single_precision_times(const std::vector<double>& times_s) {
  std::vector<float> times;
  for (double t : times_s) times.push_back(static_cast<float>(t - times_s.front()));
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1])) throw InputError("animation frame times too close for single precision");
  return times;
}

bool root_moves(const GlbBody& body) {
  return !body.root.empty() && std::any_of(body.root.begin(), body.root.end(), [&](const Vec3& r) {
           return r.x != body.root[0].x || r.y != body.root[0].y || r.z != body.root[0].z;
         });
}

/// The glTF document of glb_bytes, a body at a time: every body a root node (its translation) over
/// a mesh node (the quantization scale), its frames after the first as morph targets.
class GlbScene {
 public:
  GlbScene(const std::vector<double>& times_s, const std::vector<GlbMaterial>& materials, int every)
      : materials_(materials), frames_(times_s.size()), kept_(kept_frames(frames_, every)) {
    const std::vector<float> times = single_precision_times(times_s);
    all_times_ = frames_ > 1 ? b_.scalars(times, true) : -1;
    if (!kept_.empty()) {
      std::vector<float> t{times.front()};
      for (std::size_t k : kept_) t.push_back(times[k]);
      kept_times_ = kept_.size() + 1 == frames_ ? all_times_ : b_.scalars(t, true);
    }
  }

  void add_body(const GlbBody& body) {
    const double scale = largest_difference(body, kept_);
    nlohmann::json mesh = {{"name", body.name}, {"primitives", primitives(body, scale)}};
    if (!kept_.empty()) mesh["weights"] = std::vector<double>(kept_.size(), 0.0);
    meshes_.push_back(mesh);
    const int mesh_node = static_cast<int>(nodes_.size()) + 1;
    nlohmann::json root_node = {{"name", body.name}, {"children", {mesh_node}}};
    if (!body.root.empty()) root_node["translation"] = {body.root[0].x, body.root[0].y, body.root[0].z};
    scene_nodes_.push_back(nodes_.size());
    nodes_.push_back(root_node);
    nodes_.push_back({{"name", body.name + "_mesh"}, {"mesh", meshes_.size() - 1}, {"scale", {scale, scale, scale}}});
    if (!kept_.empty()) animate_weights(mesh_node);
    if (root_moves(body) && frames_ > 1) {
      samplers_.push_back(
          {{"input", all_times_}, {"output", b_.vec3(body.root, 0, frames_, nullptr, false)}, {"interpolation", "LINEAR"}});
      channels_.push_back({{"sampler", samplers_.size() - 1}, {"target", {{"node", mesh_node - 1}, {"path", "translation"}}}});
    }
  }

  std::string bytes(double frames_per_second) {
    nlohmann::json json = {{"asset", asset(frames_per_second)},
                           {"scene", 0},
                           {"scenes", {{{"nodes", scene_nodes_}}}},
                           {"nodes", nodes_},
                           {"materials", materials_json_},
                           {"meshes", meshes_}};
    if (!kept_.empty()) {
      json["extensionsUsed"] = {"KHR_mesh_quantization"};
      json["extensionsRequired"] = {"KHR_mesh_quantization"};
    }
    if (!channels_.empty()) {
      nlohmann::json swim = {{"name", "swim"}};
      swim["samplers"] = samplers_;
      swim["channels"] = channels_;
      json["animations"] = nlohmann::json::array({swim});
    }
    json["accessors"] = b_.accessors;
    json["bufferViews"] = b_.buffer_views;
    while (b_.bin.size() % 4 != 0) b_.bin.push_back('\0');
    json["buffers"] = {{{"byteLength", b_.bin.size()}}};
    return glb_container(json, std::move(b_.bin));
  }

 private:
  /// The index of the material of a mesh part (added on first use).
  int material_for(const std::string& part) {
    const auto at = std::find(material_names_.begin(), material_names_.end(), part);
    if (at != material_names_.end()) return static_cast<int>(at - material_names_.begin());
    const auto m = std::find_if(materials_.begin(), materials_.end(), [&](const GlbMaterial& g) { return g.part == part; });
    materials_json_.push_back(material_json(part, m == materials_.end() ? nullptr : &*m));
    material_names_.push_back(part);
    return static_cast<int>(material_names_.size()) - 1;
  }

  nlohmann::json primitives(const GlbBody& body, double scale) {
    const Mesh& first = body.first;
    std::vector<Vec3> base(first.positions);
    for (Vec3& p : base) p = (1.0 / scale) * p;
    nlohmann::json list = nlohmann::json::array();
    for (const MeshPart& part : first.parts) {
      const VertexRange range = vertex_range(first, part);
      nlohmann::json primitive = {
          {"attributes",
           {{"POSITION", b_.vec3(base, range.first, range.count, nullptr)},
            {"NORMAL", b_.vec3(first.normals, range.first, range.count, nullptr)}}},
          {"indices", b_.indices(first, part, range.first)},
          {"material", material_for(part.name)},
          {"mode", 4}};
      nlohmann::json targets = nlohmann::json::array();
      for (std::size_t k : kept_)
        targets.push_back({{"POSITION", b_.quantized_differences(body.positions[k], first.positions, range.first,
                                                                 range.count, scale)}});
      if (!targets.empty()) primitive["targets"] = targets;
      list.push_back(primitive);
    }
    return list;
  }

  /// The morph weights' animation: frame 0 with no target, then one target after another.
  void animate_weights(int mesh_node) {
    std::vector<std::uint8_t> weights;
    for (std::size_t key = 0; key <= kept_.size(); ++key)
      for (std::size_t t = 1; t <= kept_.size(); ++t) weights.push_back(t == key ? 255 : 0);
    samplers_.push_back({{"input", kept_times_}, {"output", b_.unit_bytes(weights)}, {"interpolation", "LINEAR"}});
    channels_.push_back({{"sampler", samplers_.size() - 1}, {"target", {{"node", mesh_node}, {"path", "weights"}}}});
  }

  /// The frame rate and count, for tools that set a scene up from the file (blender_import.py).
  nlohmann::json asset(double frames_per_second) const {
    nlohmann::json a = {{"version", "2.0"}, {"generator", "jellysim " JELLYSIM_VERSION}};
    a["extras"] = {{"frame_count", frames_}};
    if (frames_per_second > 0.0) a["extras"]["frames_per_second"] = frames_per_second;
    return a;
  }

  const std::vector<GlbMaterial>& materials_;
  std::size_t frames_;
  std::vector<std::size_t> kept_;
  GlbBuilder b_;
  int all_times_ = -1, kept_times_ = -1;
  nlohmann::json nodes_ = nlohmann::json::array(), meshes_ = nlohmann::json::array(),
                 materials_json_ = nlohmann::json::array(), scene_nodes_ = nlohmann::json::array(),
                 samplers_ = nlohmann::json::array(), channels_ = nlohmann::json::array();
  std::vector<std::string> material_names_;
};

}  // namespace

std::string glb_bytes(const std::vector<GlbBody>& bodies, const std::vector<double>& times_s,
                      const std::vector<GlbMaterial>& materials, int every, double frames_per_second) {
  validate_glb_bodies(bodies, times_s, every);
  GlbScene scene(times_s, materials, every);
  for (const GlbBody& body : bodies) scene.add_body(body);
  return scene.bytes(frames_per_second);
}

std::string glb_bytes(const geometry::Animation& animation, const std::vector<GlbMaterial>& materials) {
  geometry::validate_animation(animation);
  GlbBody body{"jellyfish", animation.frames.front(), {}, {}};
  for (const Mesh& f : animation.frames) body.positions.push_back(f.positions);
  return glb_bytes({body}, animation.times_s, materials, 1);
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
