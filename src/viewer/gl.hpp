#pragma once
// OpenGL 3.3 core entry points for the viewer (GLVND's libOpenGL dispatches to the window's
// current context) and small helpers: shader programs, textures, an offscreen colour target.
#define GL_GLEXT_PROTOTYPES
#define GL_GLCOREARB_PROTOTYPES
#include <GL/glcorearb.h>

#include <cstdint>
#include <string>
#include <vector>

namespace jellysim::viewer::gl {

/// Compiles and links a vertex + fragment shader; throws RunError with the driver's log.
GLuint make_program(const char* vertex_source, const char* fragment_source);

/// An RGBA8 texture with linear filtering and clamped edges (for images drawn through ImGui).
class Texture {
 public:
  Texture();
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  /// Uploads width × height RGBA8 pixels, row 0 at the bottom.
  void upload(int width, int height, const std::vector<std::uint8_t>& rgba);
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

/// A colour texture with a depth buffer to render into (the 3D panel).
class RenderTarget {
 public:
  RenderTarget() = default;
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  /// (Re)creates the buffers when the size changed; binds the multisampled framebuffer and sets
  /// the viewport.
  void bind(int width, int height);
  /// Resolves the samples into colour_texture() (a box filter over each pixel's samples) and binds
  /// the default framebuffer.
  void resolve();
  GLuint colour_texture() const { return colour_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// Samples per pixel of the framebuffer drawn into (4, or fewer where the driver has fewer).
  int samples() const { return samples_; }

 private:
  void release();
  void make_multisampled();
  GLuint framebuffer_ = 0, colour_ = 0;                         // the resolved picture
  GLuint ms_framebuffer_ = 0, ms_colour_ = 0, ms_depth_ = 0;    // the multisampled one drawn into
  int width_ = 0, height_ = 0, samples_ = 0;
};

/// Reads the default framebuffer's pixels as RGB8, top row first.
std::vector<std::uint8_t> read_screen_rgb(int width, int height);

}  // namespace jellysim::viewer::gl
