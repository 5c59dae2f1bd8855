// Two places where Mesa's softpipe breaks the OpenGL 4.5 rules, each as the smallest draw that
// shows it, run on llvmpipe (which follows the rule) and on softpipe (which does not), with the
// form the GL path uses instead (src/gl/gl_frame_renderer.cpp), correct on both. These are why
// `vt crosscheck` on softpipe left pixels unexplained before the GL path avoided them
// (docs/precision-models.md, "Soundness and sharpness").
//
// 1. texelFetch(sampler, P, lod) reads level `lod` of each fragment (GLSL 4.50, section 8.9.2:
//    "Use integer texture coordinate P to lookup a single texel from sampler. The level-of-detail
//    lod ..."; GL 4.5 core, section 8.14: texel fetches use the level given, no derivatives
//    involved). softpipe reads the level of the first fragment of each 2x2 quad for all four.
// 2. A colour buffer cleared (GL 4.5 core, section 17.4.3: ClearBuffer* sets every pixel of the
//    buffer to the clear value) keeps that value where a later draw writes nothing. softpipe
//    loses the clear of an unsigned-integer colour buffer when the depth buffer is cleared
//    separately before the draw.
//
// Each driver is selected by GALLIUM_DRIVER before its context is created (the test process has
// no other context then), so each case is its own test.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <vector>

#include "gl/gl_program.h"
#include "gl/headless_context.h"

namespace vt {
namespace {

constexpr int kSize = 16;

const char* const kFullScreenVertex = R"(#version 450 core
// Two triangles over the left `cover` part of the view (cover = 1: all of it).
uniform float cover;
void main() {
  const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1),
                                 vec2(0, 1));
  vec2 c = corners[gl_VertexID];
  gl_Position = vec4(-1.0 + 2.0 * c.x * cover, -1.0 + 2.0 * c.y, 0.5, 1.0);
}
)";

void selectDriver(bool softpipe) {
  if (softpipe) {
    ::setenv("GALLIUM_DRIVER", "softpipe", 1);
    ::setenv("MESA_GL_VERSION_OVERRIDE", "4.5", 1);
    ::setenv("MESA_GLSL_VERSION_OVERRIDE", "450", 1);
  } else {
    ::setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  }
}

// An unsigned-integer colour target (and a depth buffer) of kSize x kSize, bound for drawing.
class Target {
 public:
  explicit Target(GLenum format) {
    glCreateTextures(GL_TEXTURE_2D, 1, &color_);
    glTextureStorage2D(color_, 1, format, kSize, kSize);
    glCreateRenderbuffers(1, &depth_);
    glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT24, kSize, kSize);
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, color_, 0);
    glNamedFramebufferRenderbuffer(framebuffer_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, kSize, kSize);
    glCreateVertexArrays(1, &vertexArray_);
    glBindVertexArray(vertexArray_);
  }
  ~Target() {
    glDeleteVertexArrays(1, &vertexArray_);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteRenderbuffers(1, &depth_);
    glDeleteTextures(1, &color_);
  }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  GLuint color() const { return color_; }
  std::vector<GLuint> read() const {
    std::vector<GLuint> texels(kSize * kSize * 4);
    glReadPixels(0, 0, kSize, kSize, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels.data());
    return texels;
  }

 private:
  GLuint color_ = 0, depth_ = 0, framebuffer_ = 0, vertexArray_ = 0;
};

// Rule 1: pixels whose texelFetch read another level than the one each fragment asked for. The
// level alternates inside every 2x2 quad (a checkerboard).
int texelFetchLevelErrors() {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 2, GL_R32UI, 4, 4);
  // An integer texture is complete only with NEAREST filters (GL 4.5 core, section 8.17).
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const std::vector<GLuint> level0(16, 10u), level1(4, 20u);
  glTextureSubImage2D(texture, 0, 0, 0, 4, 4, GL_RED_INTEGER, GL_UNSIGNED_INT, level0.data());
  glTextureSubImage2D(texture, 1, 0, 0, 2, 2, GL_RED_INTEGER, GL_UNSIGNED_INT, level1.data());
  glBindTextureUnit(0, texture);
  const GlProgram program(kFullScreenVertex, R"(#version 450 core
layout(binding = 0) uniform usampler2D levels;
out uvec4 result;
void main() {
  int level = (int(gl_FragCoord.x) + int(gl_FragCoord.y)) & 1;
  result = uvec4(texelFetch(levels, ivec2(0), level).r, uint(level), 0u, 1u);
}
)");
  const Target target(GL_RGBA32UI);
  glUseProgram(program.id());
  glUniform1f(program.uniform("cover"), 1.0f);
  glDrawArrays(GL_TRIANGLES, 0, 6);
  const std::vector<GLuint> texels = target.read();
  glDeleteTextures(1, &texture);
  int errors = 0;
  for (int i = 0; i < kSize * kSize; ++i)
    errors += texels[static_cast<size_t>(i) * 4] !=
              (texels[static_cast<size_t>(i) * 4 + 1] == 0 ? 10u : 20u);
  return errors;
}

// Rule 2: pixels of the right half, where nothing is drawn, that lost the clear value. The
// colour is cleared with ClearBufferuiv (the rule) or ClearTexImage (the GL path's form).
int integerClearErrors(bool clearTexImage) {
  const Target target(GL_RGBA8UI);
  const std::array<GLuint, 4> clear{0u, 0u, 255u, 0u};
  if (clearTexImage) {
    const std::array<GLubyte, 4> bytes{0, 0, 255, 0};
    glClearTexImage(target.color(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, bytes.data());
  } else {
    glClearBufferuiv(GL_COLOR, 0, clear.data());
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  const GlProgram program(kFullScreenVertex, R"(#version 450 core
out uvec4 result;
void main() { result = uvec4(1u, 2u, 3u, 4u); }
)");
  glUseProgram(program.id());
  glUniform1f(program.uniform("cover"), 0.5f);  // the left half only
  glDrawArrays(GL_TRIANGLES, 0, 6);
  glDisable(GL_DEPTH_TEST);
  const std::vector<GLuint> texels = target.read();
  int errors = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = kSize / 2; x < kSize; ++x)
      for (int c = 0; c < 4; ++c)
        if (texels[static_cast<size_t>((y * kSize + x) * 4 + c)] != clear[static_cast<size_t>(c)]) {
          ++errors;
          break;
        }
  return errors;
}

TEST(SoftpipeRules, LlvmpipeFetchesEachFragmentsLevel) {
  selectDriver(false);
  const HeadlessContext context;
  if (context.renderer().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not llvmpipe: " << context.renderer();
  EXPECT_EQ(texelFetchLevelErrors(), 0);
}

TEST(SoftpipeRules, SoftpipeFetchesTheQuadsFirstLevelForAllFour) {
  selectDriver(true);
  const HeadlessContext context;
  ASSERT_EQ(context.renderer(), "softpipe");
  // In every quad the two fragments whose level differs from the first fragment's read wrong:
  // half of the pixels. Should softpipe be fixed, this fails and docs/ must say so.
  EXPECT_EQ(texelFetchLevelErrors(), kSize * kSize / 2);
}

TEST(SoftpipeRules, LlvmpipeKeepsAnIntegerClearUnderADepthClearAndADraw) {
  selectDriver(false);
  const HeadlessContext context;
  if (context.renderer().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not llvmpipe: " << context.renderer();
  EXPECT_EQ(integerClearErrors(false), 0);
  EXPECT_EQ(integerClearErrors(true), 0);
}

TEST(SoftpipeRules, SoftpipeLosesAnIntegerClearButNotAClearTexImage) {
  selectDriver(true);
  const HeadlessContext context;
  ASSERT_EQ(context.renderer(), "softpipe");
  const int lost = integerClearErrors(false);
  std::cout << "softpipe lost the clear value at " << lost << " of " << kSize * kSize / 2
            << " pixels not drawn\n";
  EXPECT_GT(lost, 0);                      // the rule broken
  EXPECT_EQ(integerClearErrors(true), 0);  // the GL path's form
}

}  // namespace
}  // namespace vt
