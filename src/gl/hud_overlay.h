#pragma once
// Draws a HudImage (hud_text.h) into the top-left corner of the current context's window.

#include <epoxy/gl.h>

#include <glm/glm.hpp>

#include "gl/hud_text.h"

namespace vt {

class HudOverlay {
 public:
  HudOverlay();
  ~HudOverlay();
  HudOverlay(const HudOverlay&) = delete;
  HudOverlay& operator=(const HudOverlay&) = delete;

  void draw(const HudImage& image, glm::ivec2 window);

 private:
  GLuint texture_ = 0, framebuffer_ = 0;
  uint32_t width_ = 0, height_ = 0;
};

}  // namespace vt
