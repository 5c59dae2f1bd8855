#pragma once
// A headless OpenGL 4.5 core context through EGL, with no window system: Mesa's surfaceless
// platform (llvmpipe in CI) or, where that is missing or VT_EGL_PLATFORM=device asks for it, the
// EGL device platform (a GPU's driver such as NVIDIA's, hardware devices before Mesa's software
// one). The context renders into framebuffer objects only. It is made current on the creating
// thread for its whole life.

#include <string>

namespace vt {

class HeadlessContext {
 public:
  // Throws std::runtime_error saying which EGL step failed.
  HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;
  ~HeadlessContext();

  std::string platform() const { return platform_; }  // "surfaceless" or "device"
  std::string renderer() const;                       // GL_RENDERER
  std::string version() const;                        // GL_VERSION

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string platform_;
};

}  // namespace vt
