#include "mesh_view.hpp"

#include "jellysim/render/gl_program.hpp"
#include "jellysim/render/gl_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace jellysim::viewer {

namespace {

using geometry::Vec3;
using Mat4 = std::array<float, 16>;  // column-major

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
  world_position = position;
  world_normal = normal;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

// The offscreen renderer's lighting (render::kLightingGlsl) with its default look
// (render::RenderStyle): two-sided, the normal turned to the viewer.
const std::string kFragmentShader = std::string("#version 330 core\n") + render::kLightingGlsl + R"(
in vec3 world_position;
in vec3 world_normal;
out vec4 fragment;
void main() {
  vec3 n = normalize(world_normal);
  vec3 v = normalize(eye - world_position);
  if (dot(n, v) < 0.0) n = -n;
  fragment = shade(n, v);
}
)";

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c) {
    for (int row = 0; row < 4; ++row) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
      r[c * 4 + row] = s;
    }
  }
  return r;
}

Mat4 perspective(double fov_y_rad, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(fov_y_rad / 2.0);
  Mat4 m{};
  m[0] = static_cast<float>(f / aspect);
  m[5] = static_cast<float>(f);
  m[10] = static_cast<float>((far + near) / (near - far));
  m[11] = -1.0f;
  m[14] = static_cast<float>(2.0 * far * near / (near - far));
  return m;
}

Mat4 look_at(Vec3 eye, Vec3 target, Vec3 up) {
  const Vec3 f = geometry::normalized(target - eye);
  const Vec3 s = geometry::normalized(geometry::cross(f, up));
  const Vec3 u = geometry::cross(s, f);
  Mat4 m{};
  m[0] = static_cast<float>(s.x), m[4] = static_cast<float>(s.y), m[8] = static_cast<float>(s.z);
  m[1] = static_cast<float>(u.x), m[5] = static_cast<float>(u.y), m[9] = static_cast<float>(u.z);
  m[2] = static_cast<float>(-f.x), m[6] = static_cast<float>(-f.y), m[10] = static_cast<float>(-f.z);
  m[12] = static_cast<float>(-geometry::dot(s, eye));
  m[13] = static_cast<float>(-geometry::dot(u, eye));
  m[14] = static_cast<float>(geometry::dot(f, eye));
  m[15] = 1.0f;
  return m;
}

/// The distance from the bounds' centre, along `direction` (towards the eye), at which all eight
/// corners of the bounds fall inside the view (vertical half-angle tangent `tan_half_v`, width /
/// height `aspect`, up = +y), with a 10 % margin: a corner at x, y across the view and z towards
/// the eye needs (distance − z) tan ≥ |x| horizontally and |y| vertically.
double framing_distance(const geometry::Bounds& b, Vec3 direction, double tan_half_v, double aspect) {
  const Vec3 forward = -direction;
  const Vec3 side = geometry::normalized(geometry::cross(forward, {0.0, 1.0, 0.0}));
  const Vec3 up = geometry::cross(side, forward);
  const double tan_half_h = tan_half_v * aspect;
  double distance = 0.0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{(k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y, (k & 4) ? b.max.z : b.min.z};
    const Vec3 c = corner - b.centre();
    const double towards_eye = geometry::dot(c, direction);
    distance = std::max({distance, towards_eye + 1.1 * std::abs(geometry::dot(c, side)) / tan_half_h,
                         towards_eye + 1.1 * std::abs(geometry::dot(c, up)) / tan_half_v});
  }
  return distance;
}

geometry::Bounds common_bounds(const std::vector<const geometry::Mesh*>& meshes) {
  geometry::Bounds all{};
  bool first = true;
  for (const geometry::Mesh* mesh : meshes) {
    if (mesh->positions.empty()) continue;
    const geometry::Bounds b = geometry::bounds(*mesh);
    if (first) {
      all = b;
      first = false;
      continue;
    }
    all.min = {std::min(all.min.x, b.min.x), std::min(all.min.y, b.min.y), std::min(all.min.z, b.min.z)};
    all.max = {std::max(all.max.x, b.max.x), std::max(all.max.y, b.max.y), std::max(all.max.z, b.max.z)};
  }
  return all;
}

Vec3 orbit_direction(const OrbitCamera& camera) {
  const double az = camera.azimuth_deg * std::numbers::pi / 180.0;
  const double el = camera.elevation_deg * std::numbers::pi / 180.0;
  return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

// The orbit camera framing `bounds` (40° vertical field of view): its view-projection matrix and eye.
struct CameraView {
  Mat4 view_projection;
  Vec3 eye;
};
CameraView orbit_view(const geometry::Bounds& bounds, const OrbitCamera& camera, double aspect) {
  const double extent = std::max(geometry::norm(bounds.max - bounds.min), 1e-3);
  const double fov = 40.0 * std::numbers::pi / 180.0;  // vertical
  const Vec3 direction = orbit_direction(camera);
  const double distance = std::max(framing_distance(bounds, direction, std::tan(fov / 2.0), aspect), 0.5 * extent) /
                          std::max(camera.zoom, 0.05);
  const Vec3 eye = bounds.centre() + distance * direction;
  return {multiply(perspective(fov, aspect, distance * 0.01, distance * 10.0),
                   look_at(eye, bounds.centre(), {0.0, 1.0, 0.0})),
          eye};
}

/// The renderer's default look (lights, ambient, specular, rim) as the program's uniforms.
void set_look_uniforms(GLuint program, const render::RenderStyle& style) {
  glUseProgram(program);
  for (int i = 0; i < 2; ++i) {
    const render::DirectionalLight& light = style.lights[static_cast<std::size_t>(i)];
    const std::string k = "[" + std::to_string(i) + "]";
    glUniform3f(glGetUniformLocation(program, ("light_direction" + k).c_str()), static_cast<float>(light.direction.x),
                static_cast<float>(light.direction.y), static_cast<float>(light.direction.z));
    glUniform3f(glGetUniformLocation(program, ("light_colour" + k).c_str()), static_cast<float>(light.colour[0]),
                static_cast<float>(light.colour[1]), static_cast<float>(light.colour[2]));
  }
  glUniform1f(glGetUniformLocation(program, "ambient"), static_cast<float>(style.ambient));
  glUniform1f(glGetUniformLocation(program, "specular"), static_cast<float>(style.specular));
  glUniform1f(glGetUniformLocation(program, "shininess"), static_cast<float>(style.shininess));
  glUniform1f(glGetUniformLocation(program, "rim"), static_cast<float>(style.rim));
  glUniform3f(glGetUniformLocation(program, "rim_colour"), static_cast<float>(style.rim_colour[0]),
              static_cast<float>(style.rim_colour[1]), static_cast<float>(style.rim_colour[2]));
  glUseProgram(0);
}

/// A part's colour from the renderer's style (RGBA, linear).
std::array<float, 4> rgba_of(const std::array<double, 4>& c) {
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]), static_cast<float>(c[3])};
}

}  // namespace

MeshView::MeshView() {
  program_ = gl::make_program(kVertexShader, kFragmentShader.c_str());
  u_view_projection_ = glGetUniformLocation(program_, "view_projection");
  u_eye_ = glGetUniformLocation(program_, "eye");
  u_colour_ = glGetUniformLocation(program_, "base");
  set_look_uniforms(program_, render::RenderStyle{});
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vertex_buffer_);
  glGenBuffers(1, &index_buffer_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  glBindVertexArray(0);
}

MeshView::~MeshView() {
  glDeleteBuffers(1, &vertex_buffer_);
  glDeleteBuffers(1, &index_buffer_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

void MeshView::upload(const geometry::Mesh& mesh) {
  vertex_scratch_.resize(mesh.positions.size() * 6);
  for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
    const Vec3 p = mesh.positions[k];
    const Vec3 n = k < mesh.normals.size() ? mesh.normals[k] : Vec3{0.0, 0.0, 1.0};
    const float values[6] = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z),
                             static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)};
    std::copy(values, values + 6, vertex_scratch_.begin() + static_cast<std::ptrdiff_t>(6 * k));
  }
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertex_scratch_.size() * sizeof(float)),
               vertex_scratch_.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STREAM_DRAW);
}

void MeshView::draw_part(const geometry::Mesh& mesh, const char* part_name, const float rgba[4]) {
  const geometry::MeshPart* part = mesh.part(part_name);
  if (!part || part->index_count == 0) return;
  glUniform4fv(u_colour_, 1, rgba);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(part->index_count), GL_UNSIGNED_INT,
                 reinterpret_cast<void*>(static_cast<std::uintptr_t>(part->first_index) * sizeof(std::uint32_t)));
}

GLuint MeshView::draw(const std::vector<const geometry::Mesh*>& meshes, const OrbitCamera& camera, int width,
                      int height, const geometry::Mesh* obstacles, const geometry::Mesh* snow) {
  target_.bind(std::max(width, 16), std::max(height, 16));
  glClearColor(0.03f, 0.12f, 0.20f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const CameraView view =
      orbit_view(common_bounds(meshes), camera, static_cast<double>(target_.width()) / target_.height());
  glUseProgram(program_);
  glUniformMatrix4fv(u_view_projection_, 1, GL_FALSE, view.view_projection.data());
  glUniform3f(u_eye_, static_cast<float>(view.eye.x), static_cast<float>(view.eye.y), static_cast<float>(view.eye.z));
  glBindVertexArray(vao_);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  static const render::RenderStyle look;  // the offscreen renderer's default colours
  static const std::array<float, 4> kTentacles = rgba_of(look.tentacles), kUmbrella = rgba_of(look.umbrella),
                                    kObstacles = rgba_of(look.obstacles), kSnow = rgba_of(look.snow);
  if (obstacles != nullptr && !obstacles->positions.empty()) {  // opaque, first, writing depth
    upload(*obstacles);
    glDepthMask(GL_TRUE);
    draw_part(*obstacles, "obstacles", kObstacles.data());
  }
  if (snow != nullptr && !snow->positions.empty()) {  // marine snow specks, writing depth
    upload(*snow);
    glDepthMask(GL_TRUE);
    draw_part(*snow, "snow", kSnow.data());
  }
  for (const geometry::Mesh* mesh : meshes) {  // opaque-ish tentacles first, with depth writes
    upload(*mesh);
    glDepthMask(GL_TRUE);
    draw_part(*mesh, "tentacles", kTentacles.data());
    // The tubes are often thinner than a pixel: their edges as lines keep each tentacle a
    // continuous line instead of a dotted one (the filled tube covers them when it is wider).
    glDepthFunc(GL_LEQUAL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    draw_part(*mesh, "tentacles", kTentacles.data());
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDepthFunc(GL_LESS);
    // Then the translucent umbrella over them without depth writes: its back faces, then its
    // front faces (a closed shell blends right in that order; in mesh order, far triangles blended
    // over near ones drew dark saw-teeth along the outline).
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    draw_part(*mesh, "umbrella", kUmbrella.data());
    glCullFace(GL_BACK);
    draw_part(*mesh, "umbrella", kUmbrella.data());
    glDisable(GL_CULL_FACE);
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  target_.resolve();
  return target_.colour_texture();
}

}  // namespace jellysim::viewer
