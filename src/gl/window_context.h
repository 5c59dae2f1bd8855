#pragma once
// An on-screen window with an OpenGL 4.5 core context (GLFW, X11), for the interactive viewer; the
// headless context (headless_context.h) serves everything else. RAII: GLFW is initialised for the
// window's lifetime. Throws std::runtime_error when there is no display or no 4.5 context.

#include <glm/glm.hpp>
#include <string>

struct GLFWwindow;

namespace vt {

class WindowContext {
 public:
  WindowContext(int width, int height, const std::string& title);
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;
  ~WindowContext();

  bool shouldClose() const;
  void close();
  void swapAndPoll();
  glm::ivec2 framebufferSize() const;
  bool keyDown(int glfwKey) const;
  // True once per press.
  bool keyPressed(int glfwKey);
  bool mouseButtonDown(int glfwButton) const;
  glm::dvec2 cursor() const;
  std::string renderer() const;

 private:
  GLFWwindow* window_ = nullptr;
  bool previous_[512] = {};
};

}  // namespace vt
