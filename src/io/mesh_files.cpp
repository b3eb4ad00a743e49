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

namespace {

/// The texture coordinates of an OBJ file: per part (those whose vertices all have one) the
/// seam-split corners, and the `vt` list they index (the per-vertex entries, then each part's duplicates).
struct ObjTexture {
  std::vector<geometry::TexCoord> vt;
  std::vector<std::vector<std::uint32_t>> corners;  ///< per part: empty (no vt) or one per index
};

ObjTexture obj_texture(const Mesh& mesh, const std::vector<geometry::TexCoord>& uv) {
  ObjTexture t{uv, std::vector<std::vector<std::uint32_t>>(mesh.parts.size())};
  if (uv.empty()) return t;
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    const auto begin = mesh.indices.begin() + part.first_index;
    if (part.index_count == 0 || *std::max_element(begin, begin + part.index_count) >= uv.size()) continue;
    geometry::SeamSplit split = geometry::split_u_seam(uv, mesh.indices, part.first_index, part.index_count);
    const auto shift = static_cast<std::uint32_t>(t.vt.size() - uv.size());  // earlier parts' duplicates
    for (std::uint32_t& c : split.corners)
      if (c >= uv.size()) c += shift;
    t.vt.insert(t.vt.end(), split.uv.begin() + static_cast<std::ptrdiff_t>(uv.size()), split.uv.end());
    t.corners[p] = std::move(split.corners);
  }
  return t;
}

}  // namespace

std::string obj_text(const Mesh& mesh, const std::string& comment, const std::string& object,
                     const std::vector<geometry::TexCoord>& uv) {
  std::string out = "# " + comment + "\n# " + std::to_string(mesh.vertex_count()) + " vertices, " +
                    std::to_string(mesh.triangle_count()) + " triangles (jellysim)\n";
  if (!object.empty()) out += "o " + object + "\n";
  for (const Vec3& p : mesh.positions) append_vec(out, "v", p);
  for (const Vec3& n : mesh.normals) append_vec(out, "vn", n);
  const ObjTexture texture = obj_texture(mesh, uv);
  for (const geometry::TexCoord& t : texture.vt) out += "vt " + float_text(t[0]) + ' ' + float_text(t[1]) + '\n';
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    const std::vector<std::uint32_t>& corners = texture.corners[p];
    out += (object.empty() ? "g " : "usemtl ") + part.name + "\n";
    for (std::uint32_t k = part.first_index; k < part.first_index + part.index_count; k += 3) {
      out += 'f';
      for (std::uint32_t e = 0; e < 3; ++e) {
        const std::string v = std::to_string(mesh.indices[k + e] + 1);
        const std::string t = corners.empty() ? "" : std::to_string(corners[k - part.first_index + e] + 1);
        out += ' ' + v + '/' + t + '/' + v;
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

constexpr int kFloat = 5126, kUnsignedInt = 5125, kShort = 5122, kByte = 5120, kUnsignedByte = 5121;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

/// The vertices first … first + count − 1.
std::vector<std::uint32_t> vertex_ids(std::size_t first, std::size_t count) {
  std::vector<std::uint32_t> ids(count);
  for (std::size_t i = 0; i < count; ++i) ids[i] = static_cast<std::uint32_t>(first + i);
  return ids;
}

/// Builds the BIN chunk and the bufferViews/accessors that describe it.
class GlbBuilder {
 public:
  nlohmann::json buffer_views = nlohmann::json::array();
  nlohmann::json accessors = nlohmann::json::array();
  std::string bin;

  /// A VEC3 float accessor of the vectors values[ids[i]]; min/max computed from the stored floats.
  int vec3(const std::vector<Vec3>& values, const std::vector<std::uint32_t>& ids, bool vertex_attribute = true) {
    std::vector<float> flat;
    for (std::uint32_t v : ids)
      for (double c : {values[v].x, values[v].y, values[v].z}) flat.push_back(as_float(c));
    return floats(flat, 3, vertex_attribute ? kArrayBuffer : -1);
  }

  /// `width` floats per element ("SCALAR", "VEC2", "VEC3", "VEC4"), with min/max.
  int floats(const std::vector<float>& flat, std::size_t width, int target) {
    static constexpr const char* kShapes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    std::vector<float> lo(width, std::numeric_limits<float>::max()), hi(width, -std::numeric_limits<float>::max());
    const std::size_t offset = begin_view();
    for (std::size_t i = 0; i < flat.size(); ++i) {
      append_raw(bin, flat[i]);
      lo[i % width] = std::min(lo[i % width], flat[i]);
      hi[i % width] = std::max(hi[i % width], flat[i]);
    }
    const int view = end_view(offset, target);
    return add_accessor(view, kFloat, flat.size() / width, kShapes[width], nlohmann::json(lo), nlohmann::json(hi));
  }

  /// (values[v] − minus[v]) / scale of the vertices `ids` as normalized integers of type I (short
  /// or signed byte; KHR_mesh_quantization), each vertex padded to a multiple of 4 bytes.
  template <typename I>
  int normalized_vec3(const std::vector<Vec3>& values, const std::vector<Vec3>* minus,
                      const std::vector<std::uint32_t>& ids, double scale) {
    constexpr long kMax = std::numeric_limits<I>::max();
    std::array<int, 3> lo{static_cast<int>(kMax), static_cast<int>(kMax), static_cast<int>(kMax)};
    std::array<int, 3> hi{-lo[0], -lo[1], -lo[2]};
    const std::size_t offset = begin_view();
    for (std::uint32_t v : ids) {
      const Vec3 d = minus ? values[v] - (*minus)[v] : values[v];
      const std::array<double, 3> c{d.x, d.y, d.z};
      for (std::size_t i = 0; i < 3; ++i) {
        const auto q = static_cast<I>(std::clamp(std::lround(c[i] / scale * static_cast<double>(kMax)), -kMax, kMax));
        append_raw(bin, q);
        lo[i] = std::min(lo[i], static_cast<int>(q));
        hi[i] = std::max(hi[i], static_cast<int>(q));
      }
      append_raw(bin, I{0});
    }
    const int view = end_view(offset, kArrayBuffer, sizeof(I) == 2 ? 8 : 4);
    // Bounds of a normalized integer accessor are its raw integers.
    const int a = add_accessor(view, sizeof(I) == 2 ? kShort : kByte, ids.size(), "VEC3", nlohmann::json(lo),
                               nlohmann::json(hi));
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

  int indices(const std::vector<std::uint32_t>& local) {
    const std::size_t offset = begin_view();
    for (std::uint32_t i : local) append_raw(bin, i);
    const auto [lo, hi] = std::minmax_element(local.begin(), local.end());
    const int view = end_view(offset, kElementArrayBuffer);
    return add_accessor(view, kUnsignedInt, local.size(), "SCALAR", nlohmann::json::array({*lo}),
                        nlohmann::json::array({*hi}));
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

/// A glTF material. The bell's tissue is alpha blending, as our renderer draws it (docs/rendering.md,
/// "Look development exports"): the umbrella covers α of what is behind it and lets the rest
/// through, dimmed by its transmission and absorption. KHR_materials_transmission would make the
/// covered part refracting glass (Blender and three.js showed the bell nearly invisible), so the
/// tissue's figures go to the material's extras instead.
nlohmann::json material_json(const std::string& name, const GlbMaterial* m) {
  const std::array<double, 4> rgba = m ? m->rgba : std::array<double, 4>{0.8, 0.8, 0.8, 1.0};
  nlohmann::json j = {{"name", name},
                      {"pbrMetallicRoughness",
                       {{"baseColorFactor", rgba}, {"metallicFactor", 0.0}, {"roughnessFactor", m ? m->roughness : 0.5}}},
                      {"doubleSided", true}};
  if (rgba[3] < 1.0) j["alphaMode"] = "BLEND";
  if (m && m->transmission > 0.0) {
    j["extras"] = {{"jellysim_transmission", m->transmission},
                   {"jellysim_attenuation_distance_m", m->attenuation_distance_m},
                   {"jellysim_tissue_thickness_m", m->thickness_m}};
  }
  if (m && m->ior > 0.0) j["extensions"]["KHR_materials_ior"] = {{"ior", m->ior}};
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
    if (!body.uv.empty() && body.uv.size() != body.first.positions.size())
      throw InputError("glb: " + body.name + " needs one texture coordinate per vertex");
  }
}

/// A loop's closing frame (glb_bytes's closes_loop): at least two frames before it, and every
/// body's vertices there frame 0's, relative to its root.
void check_loop_closure(const std::vector<GlbBody>& bodies, const std::vector<double>& times_s) {
  if (times_s.size() < 3) throw InputError("glb: a loop needs two frames and its closing frame");
  for (const GlbBody& body : bodies)
    if (body.positions.back() != body.positions.front())
      throw InputError("glb: " + body.name + "'s closing frame of the loop is not its first frame");
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

/// A body's vertex velocities (m/s, relative to its pivot) per frame and their quantization scale:
/// the largest component of frame 0's or of a kept frame's difference from frame 0.
struct BodyVelocities {
  std::vector<std::vector<Vec3>> v;  ///< per frame; empty: none written
  double scale = 1.0;
};

BodyVelocities body_velocities(const GlbBody& body, const std::vector<double>& times_s,
                               const std::vector<std::size_t>& kept) {
  BodyVelocities b;
  if (!body.velocities) return b;
  b.v = vertex_velocities(body.positions, times_s);
  double s = 0.0;
  for (const Vec3& v : b.v.front()) s = std::max({s, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  for (std::size_t k : kept)
    for (std::size_t i = 0; i < b.v[k].size(); ++i) {
      const Vec3 d = b.v[k][i] - b.v.front()[i];
      s = std::max({s, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
  b.scale = s > 0.0 ? s : 1.0;
  return b;
}

/// A primitive's vertices: the part's block of the body's mesh, then the duplicates of its u seam;
/// its triangles in them (0-based), and their texture coordinates (u, v, … or empty).
struct PrimitiveVertices {
  std::vector<std::uint32_t> ids, local;
  std::vector<float> uv;
};

PrimitiveVertices primitive_vertices(const GlbBody& body, const MeshPart& part) {
  const Mesh& first = body.first;
  const VertexRange range = vertex_range(first, part);
  PrimitiveVertices p{vertex_ids(range.first, range.count), {}, {}};
  if (body.uv.empty()) {
    for (std::uint32_t k = part.first_index; k < part.first_index + part.index_count; ++k)
      p.local.push_back(first.indices[k] - range.first);
    return p;
  }
  const geometry::SeamSplit split = geometry::split_u_seam(body.uv, first.indices, part.first_index, part.index_count);
  const auto n = static_cast<std::uint32_t>(body.uv.size());
  for (std::uint32_t c : split.corners) p.local.push_back(c < n ? c - range.first : range.count + (c - n));
  p.ids.insert(p.ids.end(), split.duplicated.begin(), split.duplicated.end());
  for (std::uint32_t v = range.first; v < range.first + range.count; ++v) p.uv.insert(p.uv.end(), split.uv[v].begin(), split.uv[v].end());
  for (std::size_t e = n; e < split.uv.size(); ++e) p.uv.insert(p.uv.end(), split.uv[e].begin(), split.uv[e].end());
  return p;
}

/// The glTF document of glb_bytes, a body at a time: every body a root node (its translation) over
/// a mesh node (the quantization scale), its frames after the first as morph targets.
class GlbScene {
 public:
  /// `closes_loop`: the last frame is frame 0 again (a seamless loop's closing key): no morph
  /// target of its own, its weights all 0 (the base, frame 0's shape), not counted in frame_count.
  GlbScene(const std::vector<double>& times_s, const std::vector<GlbMaterial>& materials, int every, bool closes_loop)
      : materials_(materials), times_s_(times_s), frames_(times_s.size()), closes_loop_(closes_loop),
        kept_(kept_frames(frames_ - (closes_loop ? 1 : 0), every)) {
    const std::vector<float> times = single_precision_times(times_s);
    all_times_ = frames_ > 1 ? b_.scalars(times, true) : -1;
    if (!kept_.empty()) {
      std::vector<float> t{times.front()};
      for (std::size_t k : kept_) t.push_back(times[k]);
      if (closes_loop_) t.push_back(times.back());
      kept_times_ = t.size() == frames_ ? all_times_ : b_.scalars(t, true);
    }
  }

  void add_body(const GlbBody& body) {
    const double scale = largest_difference(body, kept_);
    const BodyVelocities velocities = body_velocities(body, times_s_, kept_);
    nlohmann::json mesh = {{"name", body.name}, {"primitives", nlohmann::json::array()}};
    std::vector<Vec3> base(body.first.positions);
    for (Vec3& p : base) p = (1.0 / scale) * p;
    for (const MeshPart& part : body.first.parts) mesh["primitives"].push_back(primitive(body, part, base, scale, velocities));
    if (!kept_.empty()) mesh["weights"] = std::vector<double>(kept_.size(), 0.0);
    if (!velocities.v.empty()) mesh["extras"] = {{"velocity_scale_m_per_s", velocities.scale}};
    meshes_.push_back(mesh);
    const int mesh_node = static_cast<int>(nodes_.size()) + 1;
    nlohmann::json root_node = {{"name", body.name}, {"children", {mesh_node}}};
    if (!body.root.empty()) root_node["translation"] = {body.root[0].x, body.root[0].y, body.root[0].z};
    scene_nodes_.push_back(nodes_.size());
    nodes_.push_back(root_node);
    nodes_.push_back({{"name", body.name + "_mesh"}, {"mesh", meshes_.size() - 1}, {"scale", {scale, scale, scale}}});
    if (!kept_.empty()) animate_weights(mesh_node);
    if (root_moves(body) && frames_ > 1)
      animate(mesh_node - 1, "translation", b_.vec3(body.root, vertex_ids(0, frames_), false));
  }

  void add_camera(const ExportCamera& camera) {
    if (camera.frames.empty()) return;
    if (camera.frames.size() != frames_) throw InputError("glb: the camera needs one frame per animation frame");
    const double yfov = camera.fov_y_deg * std::acos(-1.0) / 180.0;
    nlohmann::json c = {{"name", "camera"},
                        {"type", "perspective"},
                        {"perspective",
                         {{"yfov", yfov}, {"aspectRatio", camera.aspect}, {"znear", camera.near_m()}, {"zfar", camera.far_m()}}}};
    if (camera.width_px > 0) c["extras"] = {{"width_px", camera.width_px}, {"height_px", camera.height_px}};
    cameras_.push_back(c);
    std::vector<float> eyes, rotations;
    std::array<double, 4> previous{0.0, 0.0, 0.0, 1.0};
    for (const CameraFrame& f : camera.frames) {
      std::array<double, 4> q = camera_rotation(f);
      // The same rotation with the sign nearer the previous frame's, so interpolation takes the short way.
      if (q[0] * previous[0] + q[1] * previous[1] + q[2] * previous[2] + q[3] * previous[3] < 0.0)
        for (double& c2 : q) c2 = -c2;
      previous = q;
      for (double e : {f.eye.x, f.eye.y, f.eye.z}) eyes.push_back(as_float(e));
      for (double e : q) rotations.push_back(as_float(e));
    }
    const CameraFrame& f0 = camera.frames.front();
    const std::array<double, 4> q0 = camera_rotation(f0);
    scene_nodes_.push_back(nodes_.size());
    nodes_.push_back({{"name", "camera"}, {"camera", 0}, {"translation", {f0.eye.x, f0.eye.y, f0.eye.z}}, {"rotation", q0}});
    if (camera.still() || frames_ < 2) return;
    const int node = static_cast<int>(nodes_.size()) - 1;
    animate(node, "translation", b_.floats(eyes, 3, -1));
    animate(node, "rotation", b_.floats(rotations, 4, -1));
  }

  std::string bytes(double frames_per_second) {
    nlohmann::json json = {{"asset", asset(frames_per_second)},
                           {"scene", 0},
                           {"scenes", {{{"nodes", scene_nodes_}}}},
                           {"nodes", nodes_},
                           {"materials", materials_json_},
                           {"meshes", meshes_}};
    if (!cameras_.empty()) json["cameras"] = cameras_;
    const nlohmann::json used = extensions_used();
    if (!used.empty()) json["extensionsUsed"] = used;
    if (!kept_.empty()) json["extensionsRequired"] = {"KHR_mesh_quantization"};
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

  nlohmann::json primitive(const GlbBody& body, const MeshPart& part, const std::vector<Vec3>& base, double scale,
                           const BodyVelocities& velocities) {
    const PrimitiveVertices pv = primitive_vertices(body, part);
    nlohmann::json attributes = {{"POSITION", b_.vec3(base, pv.ids)}, {"NORMAL", b_.vec3(body.first.normals, pv.ids)}};
    if (!pv.uv.empty()) attributes["TEXCOORD_0"] = b_.floats(pv.uv, 2, kArrayBuffer);
    if (!velocities.v.empty())
      attributes["_VELOCITY"] = b_.normalized_vec3<std::int8_t>(velocities.v.front(), nullptr, pv.ids, velocities.scale);
    nlohmann::json primitive = {
        {"attributes", attributes}, {"indices", b_.indices(pv.local)}, {"material", material_for(part.name)}, {"mode", 4}};
    nlohmann::json targets = nlohmann::json::array();
    for (std::size_t k : kept_) {
      nlohmann::json target = {
          {"POSITION", b_.normalized_vec3<std::int16_t>(body.positions[k], &body.first.positions, pv.ids, scale)}};
      if (!velocities.v.empty())
        target["_VELOCITY"] =
            b_.normalized_vec3<std::int8_t>(velocities.v[k], &velocities.v.front(), pv.ids, velocities.scale);
      targets.push_back(target);
    }
    if (!targets.empty()) primitive["targets"] = targets;
    return primitive;
  }

  /// A LINEAR channel over every frame's time.
  void animate(int node, const char* path, int output) {
    samplers_.push_back({{"input", all_times_}, {"output", output}, {"interpolation", "LINEAR"}});
    channels_.push_back({{"sampler", samplers_.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
  }

  /// The morph weights' animation: frame 0 with no target, then one target after another (and,
  /// closing a loop, frame 0 again: no target).
  void animate_weights(int mesh_node) {
    std::vector<std::uint8_t> weights;
    for (std::size_t key = 0; key <= kept_.size(); ++key)
      for (std::size_t t = 1; t <= kept_.size(); ++t) weights.push_back(t == key ? 255 : 0);
    if (closes_loop_) weights.insert(weights.end(), kept_.size(), 0);
    samplers_.push_back({{"input", kept_times_}, {"output", b_.unit_bytes(weights)}, {"interpolation", "LINEAR"}});
    channels_.push_back({{"sampler", samplers_.size() - 1}, {"target", {{"node", mesh_node}, {"path", "weights"}}}});
  }

  /// KHR_mesh_quantization (morph targets) and the materials' extensions, in that order.
  nlohmann::json extensions_used() const {
    nlohmann::json used = nlohmann::json::array();
    if (!kept_.empty()) used.push_back("KHR_mesh_quantization");
    for (const char* name : {"KHR_materials_ior"})
      if (std::any_of(materials_json_.begin(), materials_json_.end(),
                      [&](const nlohmann::json& m) { return m.contains("extensions") && m["extensions"].contains(name); }))
        used.push_back(name);
    return used;
  }

  /// The frame rate and count, for tools that set a scene up from the file (blender_import.py).
  nlohmann::json asset(double frames_per_second) const {
    nlohmann::json a = {{"version", "2.0"}, {"generator", "jellysim " JELLYSIM_VERSION}};
    a["extras"] = {{"frame_count", frames_ - (closes_loop_ ? 1 : 0)}};
    if (frames_per_second > 0.0) a["extras"]["frames_per_second"] = frames_per_second;
    if (closes_loop_) a["extras"]["loop"] = true;
    return a;
  }

  const std::vector<GlbMaterial>& materials_;
  const std::vector<double>& times_s_;
  std::size_t frames_;
  bool closes_loop_ = false;
  std::vector<std::size_t> kept_;
  GlbBuilder b_;
  int all_times_ = -1, kept_times_ = -1;
  nlohmann::json nodes_ = nlohmann::json::array(), meshes_ = nlohmann::json::array(),
                 materials_json_ = nlohmann::json::array(), scene_nodes_ = nlohmann::json::array(),
                 samplers_ = nlohmann::json::array(), channels_ = nlohmann::json::array(),
                 cameras_ = nlohmann::json::array();
  std::vector<std::string> material_names_;
};

}  // namespace

std::vector<GlbMaterial> glb_materials(const ExportLook& look) {
  const auto& b = look.bell_color;
  const auto& t = look.tentacle_color;
  GlbMaterial umbrella{"umbrella", {b[0], b[1], b[2], look.umbrella_opacity}, look.bell_roughness};
  umbrella.transmission = look.transmission;
  umbrella.attenuation_distance_m = look.attenuation_distance_m;
  umbrella.thickness_m = look.tissue_thickness_m;
  umbrella.ior = look.ior;
  return {umbrella,
          {"tentacles", {t[0], t[1], t[2], look.tentacle_opacity}, look.tentacle_roughness},
          {"obstacles", look.obstacle_rgba, 0.9},
          {"snow", look.snow_rgba, 0.6}};
}

std::string glb_bytes(const std::vector<GlbBody>& bodies, const std::vector<double>& times_s,
                      const std::vector<GlbMaterial>& materials, int every, double frames_per_second,
                      const ExportCamera& camera, bool closes_loop) {
  validate_glb_bodies(bodies, times_s, every);
  if (closes_loop) check_loop_closure(bodies, times_s);
  GlbScene scene(times_s, materials, every, closes_loop);
  for (const GlbBody& body : bodies) scene.add_body(body);
  scene.add_camera(camera);
  return scene.bytes(frames_per_second);
}

std::string glb_bytes(const geometry::Animation& animation, const std::vector<GlbMaterial>& materials) {
  geometry::validate_animation(animation);
  GlbBody body{"jellyfish", animation.frames.front(), {}, {}, {}, true};
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
