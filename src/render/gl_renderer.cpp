#include "render/gl_renderer.hpp"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#define GL_GLCOREARB_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "io/errors.hpp"

namespace jellysim::render {

using geometry::Vec3;

namespace {

// ---- EGL: one surfaceless display per process, initialised on first use ----------------------

struct DisplayRegistry {
  std::mutex mutex;
  EGLDisplay display = EGL_NO_DISPLAY;
  int users = 0;
};
DisplayRegistry& registry() {
  static DisplayRegistry r;
  return r;
}

EGLDisplay acquire_display(std::string* why) {
  DisplayRegistry& r = registry();
  std::lock_guard lock(r.mutex);
  if (r.display != EGL_NO_DISPLAY) {
    ++r.users;
    return r.display;
  }
  // Software rasterisation (llvmpipe) unless the user chose otherwise: same pixels everywhere.
  ::setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
  const auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) {
    if (why) *why = "EGL has no eglGetPlatformDisplayEXT (install libegl-mesa0 libegl-dev)";
    return EGL_NO_DISPLAY;
  }
  EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) {
    if (why) *why = "cannot initialise Mesa's surfaceless EGL platform (install libegl-mesa0 libgl1-mesa-dri)";
    return EGL_NO_DISPLAY;
  }
  r.display = d;
  r.users = 1;
  return d;
}

/// The display stays initialised for the life of the process once made: eglTerminate would unload
/// Mesa's driver, and re-initialising it costs tens of milliseconds (contexts are destroyed).
void release_display() {
  DisplayRegistry& r = registry();
  std::lock_guard lock(r.mutex);
  if (r.users > 0) --r.users;
}

EGLContext create_context(EGLDisplay d, std::string* why) {
  if (!eglBindAPI(EGL_OPENGL_API)) {
    if (why) *why = "EGL cannot bind the desktop OpenGL API";
    return EGL_NO_CONTEXT;
  }
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(d, config_attribs, &config, 1, &count) || count < 1) config = EGL_NO_CONFIG_KHR;
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(d, config, EGL_NO_CONTEXT, context_attribs);
  if (ctx == EGL_NO_CONTEXT) {
    if (why) *why = "EGL cannot create an OpenGL 3.3 core context";
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    eglDestroyContext(d, ctx);
    if (why) *why = "EGL cannot make a surfaceless context current (EGL_KHR_surfaceless_context missing)";
    return EGL_NO_CONTEXT;
  }
  return ctx;
}

// ---- shaders ------------------------------------------------------------------------------------

constexpr const char* kBackgroundVertex = R"(#version 330 core
out vec2 uv;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  uv = 0.5 * (p + 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
})";

// Vertical water gradient, soft light shafts fanning from above, a vignette; gamma-encoded output.
constexpr const char* kBackgroundFragment = R"(#version 330 core
in vec2 uv;
out vec4 colour;
uniform vec3 water_top;
uniform vec3 water_bottom;
uniform float shafts;
uniform float aspect;
void main() {
  vec3 c = mix(water_bottom, water_top, pow(clamp(uv.y, 0.0, 1.0), 1.3));
  vec2 d = vec2((uv.x - 0.3) * aspect, uv.y - 1.8);
  float a = atan(d.x, -d.y);
  float rays = 0.5 + 0.5 * sin(a * 29.0) * sin(a * 13.0 + 1.7);
  c += shafts * 0.10 * pow(rays, 3.0) * smoothstep(0.1, 1.0, uv.y) * vec3(0.55, 0.85, 0.95);
  vec2 v = uv - 0.5;
  c *= 1.0 - 0.6 * dot(v, v);
  colour = vec4(pow(max(c, vec3(0.0)), vec3(1.0 / 2.2)), 1.0);
})";

constexpr const char* kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view_projection;
uniform vec3 origin;
out vec3 world_position;
out vec3 world_normal;
void main() {
  world_position = position;
  world_normal = normal;
  gl_Position = view_projection * vec4(position - origin, 1.0);
})";

// Three-term lighting (ambient + Lambert diffuse + Blinn–Phong specular) with directional lights,
// two-sided, plus a view-dependent rim that makes grazing parts more opaque and brighter.
constexpr const char* kMeshFragment = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
out vec4 colour;
uniform vec4 base;
uniform vec3 eye;
uniform vec3 light_direction[2];
uniform vec3 light_colour[2];
uniform float ambient;
uniform float specular;
uniform float shininess;
uniform float rim;
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(eye - world_position);
  vec3 c = ambient * base.rgb;
  for (int i = 0; i < 2; ++i) {
    vec3 l = normalize(light_direction[i]);
    vec3 h = normalize(l + v);
    c += light_colour[i] * (max(dot(n, l), 0.0) * base.rgb + specular * pow(max(dot(n, h), 0.0), shininess));
  }
  float grazing = pow(1.0 - abs(dot(n, v)), 2.0);
  c += rim * grazing * vec3(0.45, 0.65, 0.75);
  colour = vec4(pow(max(c, vec3(0.0)), vec3(1.0 / 2.2)), clamp(base.a + rim * grazing, 0.0, 1.0));
})";

GLuint compile(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw RunError(std::string("OpenGL shader does not compile: ") + log);
  }
  return shader;
}

GLuint link(const char* vertex, const char* fragment) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw RunError(std::string("OpenGL program does not link: ") + log);
  }
  return program;
}

// ---- matrices (column-major floats, positions relative to the camera target) -----------------

using Mat4 = std::array<float, 16>;

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += a[static_cast<std::size_t>(k * 4 + r)] * b[static_cast<std::size_t>(c * 4 + k)];
      m[static_cast<std::size_t>(c * 4 + r)] = s;
    }
  return m;
}

/// View matrix for an eye at `eye` (relative to the origin used for the vertices).
Mat4 look_at(Vec3 eye, Vec3 target, Vec3 up) {
  const Vec3 f = geometry::normalized(target - eye);
  const Vec3 s = geometry::normalized(geometry::cross(f, up));
  const Vec3 u = geometry::cross(s, f);
  auto F = [](double v) { return static_cast<float>(v); };
  return {F(s.x), F(u.x), F(-f.x), 0.0f, F(s.y), F(u.y), F(-f.y), 0.0f, F(s.z), F(u.z), F(-f.z), 0.0f,
          F(-geometry::dot(s, eye)), F(-geometry::dot(u, eye)), F(geometry::dot(f, eye)), 1.0f};
}

Mat4 perspective(double fov_y_deg, double aspect, double near_m, double far_m) {
  const double t = 1.0 / std::tan(0.5 * fov_y_deg * std::numbers::pi / 180.0);
  Mat4 m{};
  m[0] = static_cast<float>(t / aspect);
  m[5] = static_cast<float>(t);
  m[10] = static_cast<float>((far_m + near_m) / (near_m - far_m));
  m[11] = -1.0f;
  m[14] = static_cast<float>(2.0 * far_m * near_m / (near_m - far_m));
  return m;
}

}  // namespace

Camera camera_looking_at(Vec3 target, Vec3 from, double distance_m, double fov_y_deg) {
  Camera c;
  c.target = target;
  c.eye = target + distance_m * geometry::normalized(from);
  c.fov_y_deg = fov_y_deg;
  return c;
}

bool offscreen_gl_available(std::string* why) {
  EGLDisplay d = acquire_display(why);
  if (d == EGL_NO_DISPLAY) return false;
  EGLContext ctx = create_context(d, why);
  const bool ok = ctx != EGL_NO_CONTEXT;
  if (ok) {
    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(d, ctx);
  }
  release_display();
  return ok;
}

struct OffscreenRenderer::Impl {
  int width = 0, height = 0;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint ms_fbo = 0, ms_colour = 0, ms_depth = 0, fbo = 0, colour = 0;
  GLuint background = 0, shaded = 0, vao = 0, vbo = 0, ibo = 0;
  std::vector<float> vertex_data;
  std::vector<std::uint8_t> rgba;

  int samples = 4;
  void make_framebuffers();
  void draw_background(const RenderStyle& style);
  void draw_part(const geometry::MeshPart& part, const std::array<double, 4>& rgba);
  void set_mesh_uniforms(const Camera& camera, const RenderStyle& style);
  void upload(const geometry::Mesh& mesh);
};

void OffscreenRenderer::Impl::make_framebuffers() {
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  const GLsizei count = std::min(samples, static_cast<int>(max_samples));
  glGenRenderbuffers(1, &ms_colour);
  glBindRenderbuffer(GL_RENDERBUFFER, ms_colour);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, count, GL_RGBA8, width, height);
  glGenRenderbuffers(1, &ms_depth);
  glBindRenderbuffer(GL_RENDERBUFFER, ms_depth);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, count, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &ms_fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_colour);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, ms_depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RunError("OpenGL multisampled framebuffer is incomplete");
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RunError("OpenGL resolve framebuffer is incomplete");
}

OffscreenRenderer::OffscreenRenderer(int width_px, int height_px, int samples) : impl_(std::make_unique<Impl>()) {
  if (samples < 1 || samples > 16)
    throw InputError("multisampling = " + std::to_string(samples) + " is out of range [1, 16]");
  if (width_px < 16 || height_px < 16 || width_px > 8192 || height_px > 8192)
    throw InputError("image size " + std::to_string(width_px) + "×" + std::to_string(height_px) +
                     " is out of range [16, 8192] pixels per side");
  Impl& m = *impl_;
  m.width = width_px;
  m.height = height_px;
  m.samples = samples;
  std::string why;
  m.display = acquire_display(&why);
  if (m.display == EGL_NO_DISPLAY) throw RunError("no offscreen OpenGL: " + why);
  m.context = create_context(m.display, &why);
  if (m.context == EGL_NO_CONTEXT) {
    release_display();
    throw RunError("no offscreen OpenGL: " + why);
  }
  try {
    m.make_framebuffers();
    m.background = link(kBackgroundVertex, kBackgroundFragment);
    m.shaded = link(kMeshVertex, kMeshFragment);
  } catch (...) {
    eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(m.display, m.context);
    release_display();
    throw;
  }
  glGenVertexArrays(1, &m.vao);
  glGenBuffers(1, &m.vbo);
  glGenBuffers(1, &m.ibo);
}

OffscreenRenderer::~OffscreenRenderer() {
  Impl& m = *impl_;
  eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, m.context);
  glDeleteBuffers(1, &m.vbo);
  glDeleteBuffers(1, &m.ibo);
  glDeleteVertexArrays(1, &m.vao);
  glDeleteProgram(m.background);
  glDeleteProgram(m.shaded);
  glDeleteFramebuffers(1, &m.ms_fbo);
  glDeleteFramebuffers(1, &m.fbo);
  const GLuint buffers[] = {m.ms_colour, m.ms_depth, m.colour};
  glDeleteRenderbuffers(3, buffers);
  eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(m.display, m.context);
  release_display();
}

int OffscreenRenderer::width() const { return impl_->width; }
int OffscreenRenderer::height() const { return impl_->height; }

std::string OffscreenRenderer::renderer_name() const {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context);
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return name ? name : "unknown";
}

void OffscreenRenderer::Impl::draw_background(const RenderStyle& style) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(background);
  glUniform3f(glGetUniformLocation(background, "water_top"), static_cast<float>(style.water_top[0]),
              static_cast<float>(style.water_top[1]), static_cast<float>(style.water_top[2]));
  glUniform3f(glGetUniformLocation(background, "water_bottom"), static_cast<float>(style.water_bottom[0]),
              static_cast<float>(style.water_bottom[1]), static_cast<float>(style.water_bottom[2]));
  glUniform1f(glGetUniformLocation(background, "shafts"), style.light_shafts ? 1.0f : 0.0f);
  glUniform1f(glGetUniformLocation(background, "aspect"), static_cast<float>(width) / static_cast<float>(height));
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void OffscreenRenderer::Impl::upload(const geometry::Mesh& mesh) {
  // Interleaved float position and normal; the vertex shader subtracts the camera target
  // (`origin`) before projecting.
  vertex_data.resize(mesh.vertex_count() * 6);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = mesh.positions[v], n = mesh.normals[v];
    const float values[6] = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z),
                             static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)};
    std::copy(values, values + 6, vertex_data.begin() + static_cast<long>(v * 6));
  }
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertex_data.size() * sizeof(float)), vertex_data.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STREAM_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<const void*>(3 * sizeof(float)));
}

void OffscreenRenderer::Impl::set_mesh_uniforms(const Camera& camera, const RenderStyle& style) {
  glUseProgram(shaded);
  const double distance = geometry::norm(camera.eye - camera.target);
  const Mat4 view = look_at(camera.eye - camera.target, Vec3{}, camera.up);
  const Mat4 projection = perspective(camera.fov_y_deg, static_cast<double>(width) / height, 0.02 * distance, 50.0 * distance);
  const Mat4 vp = multiply(projection, view);
  glUniformMatrix4fv(glGetUniformLocation(shaded, "view_projection"), 1, GL_FALSE, vp.data());
  auto vec3 = [&](const char* name, Vec3 v) {
    glUniform3f(glGetUniformLocation(shaded, name), static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
  };
  vec3("origin", camera.target);
  vec3("eye", camera.eye);
  for (int i = 0; i < 2; ++i) {
    const DirectionalLight& l = style.lights[static_cast<std::size_t>(i)];
    const std::string k = "[" + std::to_string(i) + "]";
    vec3(("light_direction" + k).c_str(), l.direction);
    vec3(("light_colour" + k).c_str(), {l.colour[0], l.colour[1], l.colour[2]});
  }
  glUniform1f(glGetUniformLocation(shaded, "ambient"), static_cast<float>(style.ambient));
  glUniform1f(glGetUniformLocation(shaded, "specular"), static_cast<float>(style.specular));
  glUniform1f(glGetUniformLocation(shaded, "shininess"), static_cast<float>(style.shininess));
  glUniform1f(glGetUniformLocation(shaded, "rim"), static_cast<float>(style.rim));
}

void OffscreenRenderer::Impl::draw_part(const geometry::MeshPart& part, const std::array<double, 4>& c) {
  glUniform4f(glGetUniformLocation(shaded, "base"), static_cast<float>(c[0]), static_cast<float>(c[1]),
              static_cast<float>(c[2]), static_cast<float>(c[3]));
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(part.index_count), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(static_cast<std::uintptr_t>(part.first_index) * sizeof(std::uint32_t)));
}

RgbImage OffscreenRenderer::render(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style) {
  Impl& m = *impl_;
  if (!eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, m.context))
    throw RunError("EGL cannot make the renderer's context current");
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo);
  glViewport(0, 0, m.width, m.height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m.draw_background(style);

  m.upload(mesh);
  m.set_mesh_uniforms(camera, style);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  // Tentacles first, writing depth; then the translucent umbrella without depth writes: its back
  // faces, then its front faces (a closed shell blends correctly in that order from most views).
  for (const geometry::MeshPart& part : mesh.parts) {
    if (part.name != "tentacles") continue;
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    m.draw_part(part, style.tentacles);
  }
  glDepthMask(GL_FALSE);
  glEnable(GL_CULL_FACE);
  for (GLenum culled : {GL_FRONT, GL_BACK}) {
    glCullFace(culled);
    for (const geometry::MeshPart& part : mesh.parts)
      if (part.name != "tentacles") m.draw_part(part, style.umbrella);
  }
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_TRUE);

  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.ms_fbo);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.fbo);
  glBlitFramebuffer(0, 0, m.width, m.height, 0, 0, m.width, m.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.fbo);
  m.rgba.resize(static_cast<std::size_t>(m.width) * m.height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, m.width, m.height, GL_RGBA, GL_UNSIGNED_BYTE, m.rgba.data());
  if (glGetError() != GL_NO_ERROR) throw RunError("OpenGL reported an error while rendering a frame");
  RgbImage image(m.width, m.height);
  for (int y = 0; y < m.height; ++y) {  // OpenGL's first row is the bottom one
    const std::uint8_t* src = m.rgba.data() + static_cast<std::size_t>(m.height - 1 - y) * m.width * 4;
    std::uint8_t* dst = image.pixels.data() + static_cast<std::size_t>(y) * m.width * 3;
    for (int x = 0; x < m.width; ++x) std::copy(src + x * 4, src + x * 4 + 3, dst + x * 3);
  }
  return image;
}

}  // namespace jellysim::render
