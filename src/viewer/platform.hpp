#pragma once
// The window (GLFW, OpenGL 3.3 core) and the Dear ImGui platform glue. Input reaches ImGui and the
// viewer through one MouseState per frame, which comes from the real mouse or from an input script,
// so injected events drive exactly the code paths a person's do.
#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace jellysim::viewer {

struct MouseState {
  double x = -1.0, y = -1.0;     ///< window pixels, y down; negative: outside
  bool down[2] = {false, false}; ///< left, right
  double wheel = 0.0;            ///< scroll this frame
};

class Window {
 public:
  /// Opens the window and initialises ImGui with its OpenGL 3 renderer. Throws RunError naming
  /// what is missing (no display: run under `xvfb-run -a`; no OpenGL 3.3).
  Window(int width_px, int height_px, const std::string& title, bool vsync);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// Polls the window system; returns the key names pressed since the last call ("space", "s",
  /// "tab", "escape", "right", …) unless ImGui is typing into a text field.
  std::vector<std::string> poll_keys();
  MouseState real_mouse() const;
  bool close_requested() const;
  int width() const;   ///< framebuffer pixels
  int height() const;

  /// Starts an ImGui frame with this mouse state.
  void begin_ui(const MouseState& mouse, double dt_s);
  /// Draws ImGui's lists into the default framebuffer (cleared first).
  void render_ui();
  void swap();
  std::string renderer_name() const;  ///< GL_RENDERER

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace jellysim::viewer
