#include "jellysim/render/gl_renderer.hpp"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#define GL_GLCOREARB_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "jellysim/core/errors.hpp"
#include "jellysim/render/gl_program.hpp"

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
  vec2 p = vec2(gl_VertexID == 1 ? 4.0 : -1.0, gl_VertexID == 2 ? 4.0 : -1.0);
  uv = 0.5 * (p + 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
})";

// Vertical water gradient, soft light shafts fanning from above, a vignette; gamma-encoded output.
// Drawn once per style and size into a texture (OffscreenRenderer::Impl::prepare_background).
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

// Copies the cached background texel by texel into a multisampled framebuffer (a blit cannot
// write into one); every sample of a pixel gets the pixel's texel, as the background shader did.
constexpr const char* kCopyFragment = R"(#version 330 core
out vec4 colour;
uniform sampler2D image;
void main() {
  colour = texelFetch(image, ivec2(gl_FragCoord.xy), 0);
})";

// The meshes' lighting (render::kLightingGlsl, gl_program.hpp: ambient, two lights, a rim; `through`
// the tissue's transmission and Beer–Lambert absorption). Blended as colour·α + behind·through (dual
// source), which is the usual "over" when through = 1 − α.
constexpr const char* kLighting = kLightingGlsl;

// The mesh programs' outputs: premultiplied colour, and what the surface lets through of what is
// behind it (the second source of the blend, Impl::set_tissue).
constexpr const char* kBlendOutputs = R"(
layout(location = 0, index = 0) out vec4 colour;
layout(location = 0, index = 1) out vec4 behind;
void emit(vec4 c, vec3 passed) {
  colour = vec4(c.rgb * c.a, c.a);
  behind = vec4(passed, 0.0);
}
)";

// Per-pixel lighting (the default): the vertex shader passes position and normal on.
// What every mesh vertex shader reads: the interleaved vertex, the camera's matrix and target.
constexpr const char* kVertexInputs = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view_projection;
uniform vec3 origin;
)";
constexpr const char* kMeshVertex = R"(
out vec3 world_position;
out vec3 world_normal;
void main() {
  world_position = position;
  world_normal = normal;
  gl_Position = view_projection * vec4(position - origin, 1.0);
})";

// Two-sided: the normal is flipped on back faces.
constexpr const char* kMeshFragmentHead = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
)";
constexpr const char* kMeshFragmentMain = R"(
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(eye - world_position);
  vec4 c = shade(n, v);
  emit(c, through(n, v, c.a));
})";

// Per-vertex (Gouraud) lighting, RenderStyle::per_vertex_lighting: both sides' colours are lit
// at the vertices and interpolated; the fragment shader picks the side.
constexpr const char* kGouraudVertexHead = R"(
out vec4 front_colour;
out vec4 back_colour;
out vec3 front_behind;
out vec3 back_behind;
)";
constexpr const char* kGouraudVertexMain = R"(
void main() {
  vec3 n = normalize(normal);
  vec3 v = normalize(eye - position);
  front_colour = shade(n, v);
  back_colour = shade(-n, v);
  front_behind = through(n, v, front_colour.a);
  back_behind = through(-n, v, back_colour.a);
  gl_Position = view_projection * vec4(position - origin, 1.0);
})";
constexpr const char* kGouraudFragment = R"(#version 330 core
in vec4 front_colour;
in vec4 back_colour;
in vec3 front_behind;
in vec3 back_behind;
)";
constexpr const char* kGouraudFragmentMain = R"(
void main() {
  emit(gl_FrontFacing ? front_colour : back_colour, gl_FrontFacing ? front_behind : back_behind);
})";

// The data passes (OffscreenRenderer::draw_passes): depth along the view axis and the screen-space
// motion from the previous frame (both clip positions interpolated, divided per fragment).
constexpr const char* kPassVertex = R"(
layout(location = 2) in vec3 previous;
uniform mat4 previous_view_projection;
uniform vec3 previous_origin;
uniform vec3 eye;
uniform vec3 forward;
out vec4 now_clip;
out vec4 then_clip;
out float depth;
void main() {
  now_clip = view_projection * vec4(position - origin, 1.0);
  then_clip = previous_view_projection * vec4(previous - previous_origin, 1.0);
  depth = dot(position - eye, forward);
  gl_Position = now_clip;
})";
constexpr const char* kPassFragment = R"(#version 330 core
in vec4 now_clip;
in vec4 then_clip;
in float depth;
uniform vec2 half_size;
out vec4 data;
void main() {
  data = vec4(depth, (now_clip.xy / now_clip.w - then_clip.xy / then_clip.w) * half_size, 1.0);
})";

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

std::array<double, 2> screen_position(const Camera& camera, Vec3 p) {
  // The same look-at frame and perspective as the renderer's view and projection matrices.
  const Vec3 forward = geometry::normalized(camera.target - camera.eye);
  const Vec3 right = geometry::normalized(geometry::cross(forward, camera.up));
  const Vec3 up = geometry::cross(right, forward);
  const Vec3 d = p - camera.eye;
  const double depth = geometry::dot(d, forward);
  const double half_height = depth * std::tan(0.5 * camera.fov_y_deg * std::numbers::pi / 180.0);
  return {0.5 * geometry::dot(d, right) / half_height, 0.5 * geometry::dot(d, up) / half_height};
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
  int samples = 4;  ///< in use (1: single-sample framebuffer)
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint ms_fbo = 0, ms_colour = 0, ms_depth = 0;  ///< multisampled target (samples > 1)
  GLuint fbo = 0, colour = 0, depth = 0;           ///< single-sample target, or the resolve target
  GLuint draw_fbo = 0;                             ///< ms_fbo or fbo
  GLuint background_fbo = 0, background_texture = 0;
  GLuint background = 0, copy = 0, vao = 0, vbo = 0, ibo = 0;
  GLuint screen_vao = 0;  ///< no attributes: the full-screen passes (positions from gl_VertexID)
  std::size_t vbo_bytes = 0, ibo_bytes = 0;
  /// The data passes (made on first use): float target, program, vertex array with the previous
  /// positions as attribute 2.
  GLuint pass_fbo = 0, pass_colour = 0, pass_depth = 0, pass_program = 0, pass_vao = 0, previous_vbo = 0;

  /// A mesh program and its uniform locations.
  struct MeshProgram {
    GLuint program = 0;
    GLint view_projection = -1, origin = -1, eye = -1, light_direction[2] = {-1, -1}, light_colour[2] = {-1, -1},
          ambient = -1, specular = -1, shininess = -1, rim = -1, base = -1, rim_colour = -1, transmission = -1,
          absorption = -1, half_thickness = -1;
  };
  MeshProgram per_pixel, per_vertex;  ///< per_vertex is linked on first use
  const MeshProgram* mesh_program = nullptr;  ///< the one in use for this frame

  /// The style the cached background was drawn for (valid when has_background).
  bool has_background = false;
  std::array<double, 3> background_top{}, background_bottom{};
  bool background_shafts = false;

  std::vector<float> vertex_data;
  std::vector<std::uint32_t> index_data;
  std::vector<std::pair<float, std::uint32_t>> triangle_order;  ///< umbrella triangles by distance
  std::vector<std::uint8_t> rgba;
  std::vector<float> pass_data, previous_data;

  /// Every call: another context (another renderer, a viewer's window) may have been made current
  /// in between; with the same context current it costs well under a microsecond (Mesa 22).
  void make_current() const {
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      throw RunError("EGL cannot make the renderer's context current");
  }
  void make_framebuffers(int requested_samples);
  void prepare_background(const RenderStyle& style);
  void draw_background(const RenderStyle& style);
  static MeshProgram make_mesh_program(const std::string& vertex, const std::string& fragment);
  void set_mesh_uniforms(const Camera& camera, const RenderStyle& style);
  /// The umbrella's tissue (transmission, absorption) for `umbrella`, clear tissue otherwise.
  void set_tissue(const RenderStyle& style, bool umbrella) const;
  /// Uploads the vertices and the draw order; returns the index ranges (offset, count) in
  /// index_data of the obstacles, the marine snow, the tentacles and the umbrella (its triangles
  /// from the farthest to the nearest).
  std::array<std::pair<std::size_t, std::size_t>, 4> upload(const geometry::Mesh& mesh, Vec3 eye);
  void draw_range(std::pair<std::size_t, std::size_t> range, const std::array<double, 4>& rgba);
  void make_pass_target();
  void read_rgba();
  /// Reads the data passes' float target into `passes` (top row first).
  void read_passes(FramePasses& passes);
};

namespace {

GLuint make_renderbuffer(GLsizei samples, GLenum format, int width, int height) {
  GLuint rb = 0;
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  if (samples > 1)
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  else
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  return rb;
}

GLuint make_framebuffer(GLuint colour, GLuint depth, const char* what) {
  GLuint fb = 0;
  glGenFramebuffers(1, &fb);
  glBindFramebuffer(GL_FRAMEBUFFER, fb);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  if (depth) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RunError(std::string("OpenGL ") + what + " framebuffer is incomplete");
  return fb;
}

void set_vec3(GLint location, Vec3 v) {
  glUniform3f(location, static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
}

}  // namespace

void OffscreenRenderer::Impl::make_framebuffers(int requested_samples) {
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  const GLsizei count = std::min(requested_samples, static_cast<int>(max_samples));
  if (count > 1) {
    ms_colour = make_renderbuffer(count, GL_RGBA8, width, height);
    ms_depth = make_renderbuffer(count, GL_DEPTH_COMPONENT24, width, height);
    ms_fbo = make_framebuffer(ms_colour, ms_depth, "multisampled");
    GLint got = 0;  // the driver may round the count up (llvmpipe offers 4 only)
    glGetIntegerv(GL_SAMPLES, &got);
    samples = std::max(1, static_cast<int>(got));
    colour = make_renderbuffer(1, GL_RGBA8, width, height);
    fbo = make_framebuffer(colour, 0, "resolve");
    draw_fbo = ms_fbo;
  } else {
    samples = 1;
    colour = make_renderbuffer(1, GL_RGBA8, width, height);
    depth = make_renderbuffer(1, GL_DEPTH_COMPONENT24, width, height);
    fbo = make_framebuffer(colour, depth, "single-sample");
    draw_fbo = fbo;
  }
  glGenTextures(1, &background_texture);
  glBindTexture(GL_TEXTURE_2D, background_texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  glGenFramebuffers(1, &background_fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, background_fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, background_texture, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RunError("OpenGL background framebuffer is incomplete");
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
  std::string why;
  m.display = acquire_display(&why);
  if (m.display == EGL_NO_DISPLAY) throw RunError("no offscreen OpenGL: " + why);
  m.context = create_context(m.display, &why);
  if (m.context == EGL_NO_CONTEXT) {
    release_display();
    throw RunError("no offscreen OpenGL: " + why);
  }
  try {
    m.make_framebuffers(samples);
    m.background = link_program(kBackgroundVertex, kBackgroundFragment);
    m.copy = link_program(kBackgroundVertex, kCopyFragment);
    m.per_pixel = Impl::make_mesh_program(std::string(kVertexInputs) + kMeshVertex, std::string(kMeshFragmentHead) + kBlendOutputs + kLighting + kMeshFragmentMain);
  } catch (...) {
    eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(m.display, m.context);
    release_display();
    throw;
  }
  glUseProgram(m.copy);
  glUniform1i(glGetUniformLocation(m.copy, "image"), 0);
  glGenVertexArrays(1, &m.screen_vao);
  glGenVertexArrays(1, &m.vao);
  glGenBuffers(1, &m.vbo);
  glGenBuffers(1, &m.ibo);
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);  // part of the vertex array's state
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<const void*>(3 * sizeof(float)));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glDepthFunc(GL_LESS);
  // Blending: Impl::set_tissue (per part).
}

OffscreenRenderer::~OffscreenRenderer() {
  Impl& m = *impl_;
  eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, m.context);
  glDeleteBuffers(1, &m.vbo);
  glDeleteBuffers(1, &m.ibo);
  glDeleteVertexArrays(1, &m.vao);
  glDeleteVertexArrays(1, &m.screen_vao);
  glDeleteProgram(m.background);
  glDeleteProgram(m.copy);
  glDeleteProgram(m.per_pixel.program);
  if (m.per_vertex.program) glDeleteProgram(m.per_vertex.program);
  if (m.pass_program) glDeleteProgram(m.pass_program);
  glDeleteBuffers(1, &m.previous_vbo);
  glDeleteVertexArrays(1, &m.pass_vao);
  const GLuint framebuffers[] = {m.ms_fbo, m.fbo, m.background_fbo, m.pass_fbo};
  glDeleteFramebuffers(4, framebuffers);
  glDeleteTextures(1, &m.background_texture);
  const GLuint buffers[] = {m.ms_colour, m.ms_depth, m.colour, m.depth, m.pass_colour, m.pass_depth};
  glDeleteRenderbuffers(6, buffers);
  eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(m.display, m.context);
  release_display();
}

int OffscreenRenderer::width() const { return impl_->width; }
int OffscreenRenderer::height() const { return impl_->height; }
int OffscreenRenderer::samples() const { return impl_->samples; }

std::string OffscreenRenderer::renderer_name() const {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context);
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return name ? name : "unknown";
}

OffscreenRenderer::Impl::MeshProgram OffscreenRenderer::Impl::make_mesh_program(const std::string& vertex,
                                                                               const std::string& fragment) {
  MeshProgram m;
  const GLuint p = m.program = link_program(vertex, fragment);
  m.view_projection = glGetUniformLocation(p, "view_projection");
  m.origin = glGetUniformLocation(p, "origin");
  m.eye = glGetUniformLocation(p, "eye");
  m.light_direction[0] = glGetUniformLocation(p, "light_direction[0]");
  m.light_direction[1] = glGetUniformLocation(p, "light_direction[1]");
  m.light_colour[0] = glGetUniformLocation(p, "light_colour[0]");
  m.light_colour[1] = glGetUniformLocation(p, "light_colour[1]");
  m.ambient = glGetUniformLocation(p, "ambient");
  m.specular = glGetUniformLocation(p, "specular");
  m.shininess = glGetUniformLocation(p, "shininess");
  m.rim = glGetUniformLocation(p, "rim");
  m.base = glGetUniformLocation(p, "base");
  m.rim_colour = glGetUniformLocation(p, "rim_colour");
  m.transmission = glGetUniformLocation(p, "transmission");
  m.absorption = glGetUniformLocation(p, "absorption");
  m.half_thickness = glGetUniformLocation(p, "half_thickness");
  return m;
}

void OffscreenRenderer::Impl::prepare_background(const RenderStyle& style) {
  if (style.background != Background::water) return;  // cleared each frame instead
  if (has_background && background_top == style.water_top && background_bottom == style.water_bottom &&
      background_shafts == style.light_shafts)
    return;
  glBindFramebuffer(GL_FRAMEBUFFER, background_fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(background);
  glUniform3f(glGetUniformLocation(background, "water_top"), static_cast<float>(style.water_top[0]),
              static_cast<float>(style.water_top[1]), static_cast<float>(style.water_top[2]));
  glUniform3f(glGetUniformLocation(background, "water_bottom"), static_cast<float>(style.water_bottom[0]),
              static_cast<float>(style.water_bottom[1]), static_cast<float>(style.water_bottom[2]));
  glUniform1f(glGetUniformLocation(background, "shafts"), style.light_shafts ? 1.0f : 0.0f);
  glUniform1f(glGetUniformLocation(background, "aspect"), static_cast<float>(width) / static_cast<float>(height));
  glBindVertexArray(screen_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  has_background = true;
  background_top = style.water_top;
  background_bottom = style.water_bottom;
  background_shafts = style.light_shafts;
}

/// The cached background into the draw framebuffer (bound): a copy for a single-sample target,
/// a texel-fetch pass for a multisampled one; depth cleared.
void OffscreenRenderer::Impl::draw_background(const RenderStyle& style) {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  if (style.background != Background::water) {  // one colour (gamma-encoded like the shading), or none
    const auto& c = style.background_colour;
    const auto encode = [](double v) { return static_cast<float>(std::pow(std::max(v, 0.0), 1.0 / 2.2)); };
    if (style.background == Background::solid)
      glClearColor(encode(c[0]), encode(c[1]), encode(c[2]), 1.0f);
    else
      glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    return;
  }
  glClear(GL_DEPTH_BUFFER_BIT);
  if (samples == 1) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, background_fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo);
    return;
  }
  glUseProgram(copy);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, background_texture);
  glBindVertexArray(screen_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

namespace {

// Interleaved float position and normal, six floats per vertex.
void interleave_vertices(const geometry::Mesh& mesh, std::vector<float>& vertex_data) {
  const std::size_t nv = mesh.vertex_count();
  vertex_data.resize(nv * 6);
  float* out = vertex_data.data();
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3 p = mesh.positions[v], n = mesh.normals[v];
    out[6 * v + 0] = static_cast<float>(p.x);
    out[6 * v + 1] = static_cast<float>(p.y);
    out[6 * v + 2] = static_cast<float>(p.z);
    out[6 * v + 3] = static_cast<float>(n.x);
    out[6 * v + 4] = static_cast<float>(n.y);
    out[6 * v + 5] = static_cast<float>(n.z);
  }
}

bool is_umbrella_part(const geometry::MeshPart& part) {
  return part.name != "tentacles" && part.name != "obstacles" && part.name != "snow";
}

// The umbrella's triangles (every part but tentacles, obstacles and snow) from the farthest to the
// nearest as seen from `eye`, appended at `fill`: a counting sort of the centroids' distances into
// kDepthBuckets equal slices of their range, mesh order within a slice (stable, so neighbouring
// triangles stay together for the rasteriser: a full sort cost ≈ 4 ms a frame at 640×480, mostly
// in drawing the scattered order). Painter's order draws the translucent shell's far wall before
// its near one and, with depth writes, an opaque bell front-most (the former back faces, then front
// faces order drew the cavity's far inner wall, a front face, over the near outer one).
void sort_umbrella_faces(const geometry::Mesh& mesh, Vec3 eye, std::vector<std::pair<float, std::uint32_t>>& order,
                         std::vector<std::uint32_t>& index_data, std::size_t& fill) {
  constexpr std::size_t kDepthBuckets = 256;
  order.clear();
  float nearest = INFINITY, farthest = -INFINITY;
  for (const geometry::MeshPart& part : mesh.parts) {
    if (!is_umbrella_part(part)) continue;
    for (std::uint32_t t = part.first_index; t + 2 < part.first_index + part.index_count; t += 3) {
      const Vec3 c = mesh.positions[mesh.indices[t]] + mesh.positions[mesh.indices[t + 1]] + mesh.positions[mesh.indices[t + 2]];
      const float d = static_cast<float>(geometry::norm((1.0 / 3.0) * c - eye));
      nearest = std::min(nearest, d);
      farthest = std::max(farthest, d);
      order.emplace_back(d, t);
    }
  }
  std::array<std::size_t, kDepthBuckets + 1> start{};
  const float scale = farthest > nearest ? (kDepthBuckets - 1) / (farthest - nearest) : 0.0f;
  const auto bucket = [&](float d) { return kDepthBuckets - 1 - static_cast<std::size_t>((d - nearest) * scale); };
  for (const auto& entry : order) ++start[bucket(entry.first) + 1];
  for (std::size_t b = 1; b <= kDepthBuckets; ++b) start[b] += start[b - 1];
  for (const auto& [d, t] : order) {
    std::copy_n(mesh.indices.begin() + t, 3, index_data.begin() + static_cast<long>(fill + 3 * start[bucket(d)]++));
  }
  fill += 3 * order.size();
}

}  // namespace

std::array<std::pair<std::size_t, std::size_t>, 4> OffscreenRenderer::Impl::upload(const geometry::Mesh& mesh,
                                                                                     Vec3 eye) {
  // Interleaved float position and normal; the vertex shader subtracts the camera target
  // (`origin`) before projecting.
  interleave_vertices(mesh, vertex_data);
  // Draw order: the opaque obstacles, the marine snow, the tentacles, then the umbrella far to near.
  std::size_t total = 0;
  for (const geometry::MeshPart& part : mesh.parts) total += part.index_count;
  index_data.resize(total);
  std::size_t fill = 0;
  const auto copy_part = [&](const char* name) {
    const std::size_t start = fill;
    for (const geometry::MeshPart& part : mesh.parts) {
      if (part.name != name) continue;
      std::copy_n(mesh.indices.begin() + part.first_index, part.index_count, index_data.begin() + static_cast<long>(fill));
      fill += part.index_count;
    }
    return std::pair<std::size_t, std::size_t>{start, fill - start};
  };
  std::array<std::pair<std::size_t, std::size_t>, 4> ranges{};
  ranges[0] = copy_part("obstacles");
  ranges[1] = copy_part("snow");
  ranges[2] = copy_part("tentacles");
  const std::size_t umbrella_start = fill;
  sort_umbrella_faces(mesh, eye, triangle_order, index_data, fill);
  ranges[3] = {umbrella_start, fill - umbrella_start};

  const std::size_t vbytes = vertex_data.size() * sizeof(float), ibytes = fill * sizeof(std::uint32_t);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  if (vbytes > vbo_bytes) {
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vbytes), vertex_data.data(), GL_STREAM_DRAW);
    vbo_bytes = vbytes;
  } else {
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(vbytes), vertex_data.data());
  }
  if (ibytes > ibo_bytes) {
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(ibytes), index_data.data(), GL_STREAM_DRAW);
    ibo_bytes = ibytes;
  } else if (ibytes > 0) {
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(ibytes), index_data.data());
  }
  return ranges;
}

namespace {

/// The projection and view of `camera` for a picture of this aspect, vertices relative to the
/// camera's target.
Mat4 view_projection_of(const Camera& camera, int width, int height) {
  const double distance = geometry::norm(camera.eye - camera.target);
  const Mat4 view = look_at(camera.eye - camera.target, Vec3{}, camera.up);
  const Mat4 projection = perspective(camera.fov_y_deg, static_cast<double>(width) / height, 0.02 * distance, 50.0 * distance);
  return multiply(projection, view);
}

void set_rgb(GLint location, const std::array<double, 3>& c) { set_vec3(location, {c[0], c[1], c[2]}); }

}  // namespace

void OffscreenRenderer::Impl::set_mesh_uniforms(const Camera& camera, const RenderStyle& style) {
  if (style.per_vertex_lighting && !per_vertex.program)
    per_vertex = make_mesh_program(std::string(kVertexInputs) + kGouraudVertexHead + kLighting + kGouraudVertexMain,
                                   std::string(kGouraudFragment) + kBlendOutputs + kGouraudFragmentMain);
  mesh_program = style.per_vertex_lighting ? &per_vertex : &per_pixel;
  const MeshProgram& u = *mesh_program;
  glUseProgram(u.program);
  const Mat4 vp = view_projection_of(camera, width, height);
  glUniformMatrix4fv(u.view_projection, 1, GL_FALSE, vp.data());
  set_vec3(u.origin, camera.target);
  set_vec3(u.eye, camera.eye);
  for (std::size_t i = 0; i < 2; ++i) {
    const DirectionalLight& l = style.lights[i];
    set_vec3(u.light_direction[i], l.direction);
    set_rgb(u.light_colour[i], l.colour);
  }
  glUniform1f(u.ambient, static_cast<float>(style.ambient));
  glUniform1f(u.specular, static_cast<float>(style.specular));
  glUniform1f(u.shininess, static_cast<float>(style.shininess));
  glUniform1f(u.rim, static_cast<float>(style.rim));
  set_rgb(u.rim_colour, style.rim_colour);
}

void OffscreenRenderer::Impl::set_tissue(const RenderStyle& style, bool umbrella) const {
  const MeshProgram& u = *mesh_program;
  std::array<double, 3> absorption{};  // per metre: −ln(colour) / distance (Beer–Lambert)
  double strongest = 0.0;
  if (umbrella)
    for (std::size_t k = 0; k < 3; ++k) {
      absorption[k] = -std::log(std::max(style.umbrella[k], 1e-6)) / style.attenuation_distance_m;
      strongest = std::max(strongest, absorption[k]);
    }
  const double transmission = umbrella ? style.transmission : 1.0;
  const double half_thickness = umbrella ? 0.5 * style.tissue_thickness_m : 0.0;
  glUniform1f(u.transmission, static_cast<float>(transmission));
  set_rgb(u.absorption, absorption);
  glUniform1f(u.half_thickness, static_cast<float>(half_thickness));
  // Clear tissue (no light lost even on the most grazing path, 10 × the half thickness, to within
  // 1/1024): the plain "over" of the premultiplied colour, which llvmpipe blends ≈ 1 ms a frame
  // faster than the dual-source form; otherwise what is behind is multiplied by `through`.
  const bool clear = transmission == 1.0 && strongest * 10.0 * half_thickness < 1.0 / 1024.0;
  glBlendFuncSeparate(GL_ONE, clear ? GL_ONE_MINUS_SRC_ALPHA : GL_SRC1_COLOR, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

void OffscreenRenderer::Impl::draw_range(std::pair<std::size_t, std::size_t> range, const std::array<double, 4>& c) {
  if (range.second == 0) return;
  glUniform4f(mesh_program->base, static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]),
              static_cast<float>(c[3]));
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(range.second), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(range.first * sizeof(std::uint32_t)));
}

void OffscreenRenderer::draw(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style) {
  Impl& m = *impl_;
  m.make_current();
  m.prepare_background(style);
  glBindFramebuffer(GL_FRAMEBUFFER, m.draw_fbo);
  glViewport(0, 0, m.width, m.height);
  m.draw_background(style);

  const auto ranges = m.upload(mesh, camera.eye);
  m.set_mesh_uniforms(camera, style);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glDepthMask(GL_TRUE);
  // Obstacles, snow and tentacles first, then the umbrella from its farthest triangle to its
  // nearest, every part writing depth: an opaque bell is drawn front-most, a translucent one blends
  // its far wall under its near one.
  m.set_tissue(style, false);
  m.draw_range(ranges[0], style.obstacles);
  m.draw_range(ranges[2], style.tentacles);
  m.draw_range(ranges[1], style.snow);
  m.set_tissue(style, true);
  m.draw_range(ranges[3], style.umbrella);
}

/// Resolves the multisampled framebuffer and reads the frame's RGBA bytes (bottom row first) into rgba.
void OffscreenRenderer::Impl::read_rgba() {
  make_current();
  if (samples > 1) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  if (glGetError() != GL_NO_ERROR) throw RunError("OpenGL reported an error while rendering a frame");
}

void OffscreenRenderer::read_back(RgbImage& image) {
  Impl& m = *impl_;
  m.read_rgba();
  const std::size_t w = static_cast<std::size_t>(m.width), h = static_cast<std::size_t>(m.height);
  if (image.width != m.width || image.height != m.height || image.pixels.size() != w * h * 3) {
    image.width = m.width;
    image.height = m.height;
    image.pixels.resize(w * h * 3);
  }
  for (std::size_t y = 0; y < h; ++y) {  // OpenGL's first row is the bottom one
    const std::uint8_t* src = m.rgba.data() + (h - 1 - y) * w * 4;
    std::uint8_t* dst = image.pixels.data() + y * w * 3;
    // RGBA → RGB: four bytes per pixel, each write's alpha overwritten by the next pixel's red.
    for (std::size_t x = 0; x + 1 < w; ++x) std::memcpy(dst + 3 * x, src + 4 * x, 4);
    std::memcpy(dst + 3 * (w - 1), src + 4 * (w - 1), 3);
  }
}

void OffscreenRenderer::read_back(RgbaImage& image) {
  Impl& m = *impl_;
  m.read_rgba();
  const std::size_t w = static_cast<std::size_t>(m.width), h = static_cast<std::size_t>(m.height);
  image.width = m.width;
  image.height = m.height;
  image.pixels.resize(w * h * 4);
  for (std::size_t y = 0; y < h; ++y) {  // bottom row first → top row first
    const std::uint8_t* src = m.rgba.data() + (h - 1 - y) * w * 4;
    std::uint8_t* dst = image.pixels.data() + y * w * 4;
    for (std::size_t x = 0; x < w; ++x) {
      // The framebuffer holds premultiplied colour (over a transparent background); PNG wants straight.
      const unsigned a = src[4 * x + 3];
      for (std::size_t k = 0; k < 3; ++k) {
        const unsigned c = src[4 * x + k];
        dst[4 * x + k] = a == 0 ? 0 : static_cast<std::uint8_t>(std::min(255u, (c * 255u + a / 2) / a));
      }
      dst[4 * x + 3] = static_cast<std::uint8_t>(a);
    }
  }
}

void OffscreenRenderer::Impl::make_pass_target() {
  if (pass_fbo) return;
  pass_colour = make_renderbuffer(1, GL_RGBA32F, width, height);
  pass_depth = make_renderbuffer(1, GL_DEPTH_COMPONENT24, width, height);
  pass_fbo = make_framebuffer(pass_colour, pass_depth, "data-pass");
  pass_program = link_program(std::string(kVertexInputs) + kPassVertex, kPassFragment);
  glGenVertexArrays(1, &pass_vao);
  glGenBuffers(1, &previous_vbo);
  glBindVertexArray(pass_vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, previous_vbo);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
}

void OffscreenRenderer::draw_passes(const geometry::Mesh& mesh, const std::vector<Vec3>& previous_positions,
                                    const Camera& camera, const Camera& previous_camera, FramePasses& passes) {
  if (previous_positions.size() != mesh.vertex_count())
    throw InputError("the velocity pass needs one previous position per vertex");
  Impl& m = *impl_;
  m.make_current();
  const auto ranges = m.upload(mesh, camera.eye);
  m.make_pass_target();
  m.previous_data.resize(3 * previous_positions.size());
  for (std::size_t v = 0; v < previous_positions.size(); ++v) {
    m.previous_data[3 * v + 0] = static_cast<float>(previous_positions[v].x);
    m.previous_data[3 * v + 1] = static_cast<float>(previous_positions[v].y);
    m.previous_data[3 * v + 2] = static_cast<float>(previous_positions[v].z);
  }
  glBindBuffer(GL_ARRAY_BUFFER, m.previous_vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.previous_data.size() * sizeof(float)), m.previous_data.data(),
               GL_STREAM_DRAW);
  glBindFramebuffer(GL_FRAMEBUFFER, m.pass_fbo);
  glViewport(0, 0, m.width, m.height);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glClearColor(kBackgroundDepth, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const GLuint p = m.pass_program;
  glUseProgram(p);
  const Mat4 now = view_projection_of(camera, m.width, m.height), then = view_projection_of(previous_camera, m.width, m.height);
  glUniformMatrix4fv(glGetUniformLocation(p, "view_projection"), 1, GL_FALSE, now.data());
  glUniformMatrix4fv(glGetUniformLocation(p, "previous_view_projection"), 1, GL_FALSE, then.data());
  set_vec3(glGetUniformLocation(p, "origin"), camera.target);
  set_vec3(glGetUniformLocation(p, "previous_origin"), previous_camera.target);
  set_vec3(glGetUniformLocation(p, "eye"), camera.eye);
  set_vec3(glGetUniformLocation(p, "forward"), geometry::normalized(camera.target - camera.eye));
  glUniform2f(glGetUniformLocation(p, "half_size"), 0.5f * static_cast<float>(m.width), 0.5f * static_cast<float>(m.height));
  glBindVertexArray(m.pass_vao);
  const std::size_t first = ranges[0].first, count = ranges[3].first + ranges[3].second - first;
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT, reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
  m.read_passes(passes);
  glBindVertexArray(m.vao);
}

void OffscreenRenderer::Impl::read_passes(FramePasses& passes) {
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  pass_data.resize(w * h * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, pass_fbo);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pass_data.data());
  if (glGetError() != GL_NO_ERROR) throw RunError("OpenGL reported an error while drawing the data passes");
  passes.width = width;
  passes.height = height;
  passes.depth_m.resize(w * h);
  passes.velocity_px.resize(w * h * 2);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const float* src = pass_data.data() + ((h - 1 - y) * w + x) * 4;
      const std::size_t i = y * w + x;
      passes.depth_m[i] = src[0];
      passes.velocity_px[2 * i] = src[1];
      passes.velocity_px[2 * i + 1] = src[2];
    }
}

void OffscreenRenderer::finish() {
  Impl& m = *impl_;
  m.make_current();
  glFinish();
}

void OffscreenRenderer::render(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style,
                               RgbImage& image) {
  draw(mesh, camera, style);
  read_back(image);
}

RgbImage OffscreenRenderer::render(const geometry::Mesh& mesh, const Camera& camera, const RenderStyle& style) {
  RgbImage image;
  render(mesh, camera, style, image);
  return image;
}

}  // namespace jellysim::render
