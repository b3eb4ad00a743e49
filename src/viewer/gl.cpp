#include "gl.hpp"

#include <algorithm>
#include <cstring>

#include "jellysim/core/errors.hpp"
#include "jellysim/render/gl_program.hpp"

namespace jellysim::viewer::gl {

GLuint make_program(const char* vertex_source, const char* fragment_source) {
  return render::link_program(vertex_source, fragment_source);
}

Texture::Texture() { glGenTextures(1, &id_); }
Texture::~Texture() { glDeleteTextures(1, &id_); }

void Texture::upload(int width, int height, const std::vector<std::uint8_t>& rgba) {
  glBindTexture(GL_TEXTURE_2D, id_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
}

RenderTarget::~RenderTarget() { release(); }

void RenderTarget::release() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (colour_) glDeleteTextures(1, &colour_);
  if (ms_framebuffer_) glDeleteFramebuffers(1, &ms_framebuffer_);
  if (ms_colour_) glDeleteRenderbuffers(1, &ms_colour_);
  if (ms_depth_) glDeleteRenderbuffers(1, &ms_depth_);
  framebuffer_ = colour_ = ms_framebuffer_ = ms_colour_ = ms_depth_ = 0;
}

/// The framebuffer drawn into: 4× multisampled colour and depth (antialiased edges, and specks
/// thinner than a pixel covered in part instead of flickering on and off between frames).
void RenderTarget::make_multisampled() {
  GLint most = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &most);
  samples_ = std::max(1, std::min(4, static_cast<int>(most)));
  glGenRenderbuffers(1, &ms_colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, ms_colour_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width_, height_);
  glGenRenderbuffers(1, &ms_depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, ms_depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, width_, height_);
  glGenFramebuffers(1, &ms_framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, ms_framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, ms_depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw RunError("viewer: the multisampled OpenGL framebuffer for the 3D panel is incomplete");
  }
}

void RenderTarget::bind(int width, int height) {
  if (width != width_ || height != height_ || !framebuffer_) {
    release();
    width_ = width;
    height_ = height;
    glGenTextures(1, &colour_);
    glBindTexture(GL_TEXTURE_2D, colour_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw RunError("viewer: the OpenGL framebuffer for the 3D panel is incomplete");
    }
    make_multisampled();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, ms_framebuffer_);
  glViewport(0, 0, width_, height_);
}

void RenderTarget::resolve() {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, ms_framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<std::uint8_t> read_screen_rgb(int width, int height) {
  std::vector<std::uint8_t> bottom_up(static_cast<std::size_t>(width) * height * 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  std::vector<std::uint8_t> top_down(bottom_up.size());
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::memcpy(top_down.data() + static_cast<std::size_t>(y) * row,
                bottom_up.data() + static_cast<std::size_t>(height - 1 - y) * row, row);
  }
  return top_down;
}

}  // namespace jellysim::viewer::gl
