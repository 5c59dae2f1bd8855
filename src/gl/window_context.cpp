#include "gl/window_context.h"

#include <epoxy/gl.h>
// GLFW after epoxy, without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace vt {

WindowContext::WindowContext(int width, int height, const std::string& title) {
  if (!glfwInit()) throw std::runtime_error("cannot open a window: GLFW found no display");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window with an OpenGL 4.5 core context");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
}

WindowContext::~WindowContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool WindowContext::shouldClose() const { return glfwWindowShouldClose(window_); }
void WindowContext::close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void WindowContext::swapAndPoll() {
  glfwSwapBuffers(window_);
  glfwPollEvents();
}

glm::ivec2 WindowContext::framebufferSize() const {
  glm::ivec2 size;
  glfwGetFramebufferSize(window_, &size.x, &size.y);
  return size;
}

bool WindowContext::keyDown(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }

bool WindowContext::keyPressed(int key) {
  const bool down = keyDown(key);
  const bool pressed = down && !previous_[key & 511];
  previous_[key & 511] = down;
  return pressed;
}

bool WindowContext::mouseButtonDown(int button) const {
  return glfwGetMouseButton(window_, button) == GLFW_PRESS;
}

glm::dvec2 WindowContext::cursor() const {
  glm::dvec2 position;
  glfwGetCursorPos(window_, &position.x, &position.y);
  return position;
}

std::string WindowContext::renderer() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

}  // namespace vt
