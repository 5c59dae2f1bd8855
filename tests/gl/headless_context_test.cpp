#include "gl/headless_context.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <array>

namespace vt {
namespace {

TEST(HeadlessContext, GivesOpenGl45CoreWithoutAWindowSystem) {
  const HeadlessContext context;
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45) << context.version();
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_FALSE(context.renderer().empty());
  RecordProperty("GL_RENDERER", context.renderer());
  RecordProperty("GL_VERSION", context.version());
}

TEST(HeadlessContext, RendersIntoAFramebufferObject) {
  const HeadlessContext context;
  GLuint texture = 0, framebuffer = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA8, 4, 4);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
  ASSERT_EQ(glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER),
            GLenum{GL_FRAMEBUFFER_COMPLETE});
  const std::array<GLfloat, 4> color = {1.0f, 0.25f, 0.0f, 1.0f};
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, color.data());
  std::array<uint8_t, 4 * 4 * 4> pixels{};
  glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.size(), pixels.data());
  // 0.25 * 255 = 63.75 converts to 64 (the nearest representable value).
  for (size_t i = 0; i < pixels.size(); i += 4) {
    EXPECT_EQ(pixels[i + 0], 255);
    EXPECT_EQ(pixels[i + 1], 64);
    EXPECT_EQ(pixels[i + 2], 0);
    EXPECT_EQ(pixels[i + 3], 255);
  }
  EXPECT_EQ(glGetError(), GLenum{GL_NO_ERROR});
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &texture);
}

}  // namespace
}  // namespace vt
