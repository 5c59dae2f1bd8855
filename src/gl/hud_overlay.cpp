#include "gl/hud_overlay.h"

namespace vt {

void HudOverlay::draw(const HudImage& image, glm::ivec2 window) {
  if (image.width == 0 || image.height == 0) return;
  if (image.width != width_ || image.height != height_) {  // texture storage is immutable
    texture_.reset();
    texture_ = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture_.get(), 1, GL_RGBA8, static_cast<GLsizei>(image.width),
                       static_cast<GLsizei>(image.height));
    glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, texture_.get(), 0);
    width_ = image.width;
    height_ = image.height;
  }
  glTextureSubImage2D(texture_.get(), 0, 0, 0, static_cast<GLsizei>(image.width),
                      static_cast<GLsizei>(image.height), GL_RGBA, GL_UNSIGNED_BYTE,
                      image.rgba.data());
  glNamedFramebufferReadBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT0);
  const auto w = static_cast<GLint>(image.width), h = static_cast<GLint>(image.height);
  glBlitNamedFramebuffer(framebuffer_.get(), 0, 0, 0, w, h, 0, window.y - h, w, window.y,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

}  // namespace vt
