#include "gl/headless_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace vt {
namespace {

[[noreturn]] void fail(const std::string& step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  throw std::runtime_error("headless OpenGL: " + step + " failed (EGL error " + code + ")");
}

EGLDisplay surfacelessDisplay() {
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
    return EGL_NO_DISPLAY;
  EGLDisplay display =
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  return display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr) ? display
                                                                               : EGL_NO_DISPLAY;
}

// The first EGL device that initialises; a hardware device (not Mesa's software one) first.
EGLDisplay deviceDisplay() {
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) return EGL_NO_DISPLAY;
  EGLint count = 0;
  eglQueryDevicesEXT(0, nullptr, &count);
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  if (count <= 0 || !eglQueryDevicesEXT(count, devices.data(), &count)) return EGL_NO_DISPLAY;
  for (const bool software : {false, true})
    for (EGLDeviceEXT device : devices) {
      const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
      const bool isSoftware =
          extensions &&
          std::string(extensions).find("EGL_MESA_device_software") != std::string::npos;
      if (isSoftware != software) continue;
      EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
      if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
    }
  return EGL_NO_DISPLAY;
}

// VT_EGL_PLATFORM=device picks the EGL device platform (a GPU's driver, e.g. NVIDIA's, where
// Mesa is installed too), =surfaceless Mesa's surfaceless platform; unset: surfaceless, then
// device.
EGLDisplay openDisplay(std::string& platform) {
  const char* wanted = std::getenv("VT_EGL_PLATFORM");
  const std::string choice = wanted ? wanted : "";
  if (choice != "device") {
    if (EGLDisplay display = surfacelessDisplay(); display != EGL_NO_DISPLAY) {
      platform = "surfaceless";
      return display;
    }
  }
  if (choice != "surfaceless") {
    if (EGLDisplay display = deviceDisplay(); display != EGL_NO_DISPLAY) {
      platform = "device";
      return display;
    }
  }
  fail("opening a " + (choice.empty() ? std::string("surfaceless or device") : choice) +
       " EGL display");
}

}  // namespace

HeadlessContext::HeadlessContext() {
  EGLDisplay display = openDisplay(platform_);
  display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");

  const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, configAttributes, &config, 1, &configs) || configs < 1)
    fail("eglChooseConfig (pbuffer, OpenGL)");

  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    fail("eglCreateContext (OpenGL 4.5 core)");
  }
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    eglTerminate(display);
    fail("eglMakeCurrent without a surface");
  }
}

HeadlessContext::~HeadlessContext() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

std::string HeadlessContext::renderer() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

std::string HeadlessContext::version() const {
  return reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

}  // namespace vt
