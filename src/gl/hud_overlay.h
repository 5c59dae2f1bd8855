#pragma once
// Draws a HudImage (hud_text.h) into the top-left corner of the current context's window.

#include <epoxy/gl.h>

#include <glm/glm.hpp>

#include "gl/gl_objects.h"
#include "gl/hud_text.h"

namespace vt {

class HudOverlay {
 public:
  HudOverlay() : framebuffer_(createFramebuffer()) {}

  void draw(const HudImage& image, glm::ivec2 window);

 private:
  GlFramebuffer framebuffer_;
  GlTexture texture_;
  uint32_t width_ = 0, height_ = 0;
};

}  // namespace vt
