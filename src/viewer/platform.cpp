#include "platform.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cstring>

#include "jellysim/core/errors.hpp"
#include "gl.hpp"

namespace jellysim::viewer {

struct Window::Impl {
  GLFWwindow* window = nullptr;
  std::vector<std::string> keys;  ///< pressed since the last poll
  double wheel = 0.0;
  bool imgui_ready = false;
};

namespace {

std::string glfw_error_text() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown error";
}

const char* key_name(int key) {
  switch (key) {
    case GLFW_KEY_SPACE: return "space";
    case GLFW_KEY_TAB: return "tab";
    case GLFW_KEY_ESCAPE: return "escape";
    case GLFW_KEY_RIGHT: return "right";
    case GLFW_KEY_LEFT: return "left";
    default: break;
  }
  static const char* const letters[26] = {"a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "m",
                                          "n", "o", "p", "q", "r", "s", "t", "u", "v", "w", "x", "y", "z"};
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return letters[key - GLFW_KEY_A];
  return nullptr;
}

Window::Impl& impl_of(GLFWwindow* w) { return *static_cast<Window::Impl*>(glfwGetWindowUserPointer(w)); }

void on_key(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/) {
  ImGuiIO& io = ImGui::GetIO();
  if (key >= 0 && key < static_cast<int>(IM_ARRAYSIZE(io.KeysDown))) io.KeysDown[key] = action != GLFW_RELEASE;
  io.KeyCtrl = glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  io.KeyShift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  if (action != GLFW_PRESS || io.WantTextInput) return;
  if (const char* name = key_name(key)) impl_of(w).keys.emplace_back(name);
}

void on_char(GLFWwindow*, unsigned int c) { ImGui::GetIO().AddInputCharacter(c); }
void on_scroll(GLFWwindow* w, double, double dy) { impl_of(w).wheel += dy; }

void map_imgui_keys(ImGuiIO& io) {
  const std::pair<ImGuiKey, int> keys[] = {
      {ImGuiKey_Tab, GLFW_KEY_TAB},         {ImGuiKey_LeftArrow, GLFW_KEY_LEFT}, {ImGuiKey_RightArrow, GLFW_KEY_RIGHT},
      {ImGuiKey_UpArrow, GLFW_KEY_UP},      {ImGuiKey_DownArrow, GLFW_KEY_DOWN}, {ImGuiKey_Home, GLFW_KEY_HOME},
      {ImGuiKey_End, GLFW_KEY_END},         {ImGuiKey_Delete, GLFW_KEY_DELETE},  {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
      {ImGuiKey_Enter, GLFW_KEY_ENTER},     {ImGuiKey_Escape, GLFW_KEY_ESCAPE},  {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER},
      {ImGuiKey_A, GLFW_KEY_A},             {ImGuiKey_C, GLFW_KEY_C},            {ImGuiKey_V, GLFW_KEY_V},
      {ImGuiKey_X, GLFW_KEY_X},             {ImGuiKey_Y, GLFW_KEY_Y},            {ImGuiKey_Z, GLFW_KEY_Z},
      {ImGuiKey_Space, GLFW_KEY_SPACE}};
  for (const auto& [imgui_key, glfw_key] : keys) io.KeyMap[imgui_key] = glfw_key;
}

GLFWwindow* open_window(int width, int height, const std::string& title) {
  if (!glfwInit()) {
    throw RunError("viewer: cannot open a window (" + glfw_error_text() +
                   "); without a display run it under a virtual one: xvfb-run -a jellysim view …");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w) {
    const std::string why = glfw_error_text();
    glfwTerminate();
    throw RunError("viewer: cannot create an OpenGL 3.3 core window (" + why +
                   "); install libgl1-mesa-dri for software OpenGL");
  }
  return w;
}

}  // namespace

Window::Window(int width_px, int height_px, const std::string& title, bool vsync) : impl_(std::make_unique<Impl>()) {
  impl_->window = open_window(width_px, height_px, title);
  glfwMakeContextCurrent(impl_->window);
  glfwSwapInterval(vsync ? 1 : 0);
  glfwSetWindowUserPointer(impl_->window, impl_.get());
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to the user's files
  io.BackendPlatformName = "jellysim-glfw";
  map_imgui_keys(io);
  glfwSetKeyCallback(impl_->window, on_key);
  glfwSetCharCallback(impl_->window, on_char);
  glfwSetScrollCallback(impl_->window, on_scroll);
  ImGui::StyleColorsDark();
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext();
    glfwDestroyWindow(impl_->window);
    glfwTerminate();
    throw RunError("viewer: Dear ImGui's OpenGL 3 renderer cannot start");
  }
  impl_->imgui_ready = true;
}

Window::~Window() {
  if (impl_->imgui_ready) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(impl_->window);
  glfwTerminate();
}

std::vector<std::string> Window::poll_keys() {
  glfwPollEvents();
  std::vector<std::string> keys;
  keys.swap(impl_->keys);
  return keys;
}

MouseState Window::real_mouse() const {
  MouseState m;
  if (glfwGetWindowAttrib(impl_->window, GLFW_HOVERED)) glfwGetCursorPos(impl_->window, &m.x, &m.y);
  m.down[0] = glfwGetMouseButton(impl_->window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  m.down[1] = glfwGetMouseButton(impl_->window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  m.wheel = impl_->wheel;
  impl_->wheel = 0.0;
  return m;
}

bool Window::close_requested() const { return glfwWindowShouldClose(impl_->window); }

int Window::width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return w;
}

int Window::height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return h;
}

void Window::begin_ui(const MouseState& mouse, double dt_s) {
  ImGuiIO& io = ImGui::GetIO();
  int w = 0, h = 0, fw = 0, fh = 0;
  glfwGetWindowSize(impl_->window, &w, &h);
  glfwGetFramebufferSize(impl_->window, &fw, &fh);
  io.DisplaySize = ImVec2(static_cast<float>(w), static_cast<float>(h));
  if (w > 0 && h > 0) io.DisplayFramebufferScale = ImVec2(static_cast<float>(fw) / w, static_cast<float>(fh) / h);
  io.DeltaTime = static_cast<float>(std::max(dt_s, 1e-4));
  io.MousePos = mouse.x >= 0 && mouse.y >= 0 ? ImVec2(static_cast<float>(mouse.x), static_cast<float>(mouse.y))
                                             : ImVec2(-FLT_MAX, -FLT_MAX);
  io.MouseDown[0] = mouse.down[0];
  io.MouseDown[1] = mouse.down[1];
  io.MouseWheel = static_cast<float>(mouse.wheel);
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

void Window::render_ui() {
  ImGui::Render();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width(), height());
  glClearColor(0.05f, 0.07f, 0.10f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Window::swap() { glfwSwapBuffers(impl_->window); }

std::string Window::renderer_name() const {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return name ? name : "";
}

}  // namespace jellysim::viewer
