// The whole virtual-texture fragment shader against Mesa's llvmpipe, bit for bit: the GL program
// (the shared logic included verbatim) and the oracle render the same scene from the same cache
// state, some pages resident and the rest falling back to ancestors; colour and needbuffer must
// agree on every pixel, for exact and hardware bilinear filtering, with and without trilinear
// blending, in both needbuffer encodings.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <random>

#include "build/synthetic_texture.h"
#include "gl/gl_program.h"
#include "gl/headless_context.h"
#include "gl/virtual_texture_program.h"
#include "reference/renderer.h"
#include "test_support.h"

namespace vt {
namespace {

bool cpuHasFma() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string word;
  while (cpuinfo >> word)
    if (word == "fma") return true;
  return false;
}

struct ShadedFrame {
  std::vector<uint8_t> color;
  std::vector<glm::uvec4> need;
};

// Uploads the cache state, draws the mesh with the virtual-texture program, reads back.
ShadedFrame drawWithLlvmpipe(const reference::ClipSpaceMesh& mesh,
                             const reference::CacheState& cache,
                             const reference::RenderSettings& settings) {
  const TextureDescription& d = cache.description;
  const GlProgram program(virtualTextureVertexSource(), virtualTextureFragmentSource());
  const reference::Viewport viewport = settings.viewport;

  GLuint indirection = 0, texels = 0, targets[3] = {};
  glCreateTextures(GL_TEXTURE_2D, 1, &indirection);
  const GLsizei levels = static_cast<GLsizei>(d.levelCount);
  const GLsizei finestSide = static_cast<GLsizei>(pagesPerSide(d.finestLevel()));
  glTextureStorage2D(indirection, levels, GL_RGBA16UI, finestSide, finestSide);
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    const GLsizei side = static_cast<GLsizei>(pagesPerSide(m));
    glTextureSubImage2D(indirection, static_cast<GLint>(d.finestLevel() - m), 0, 0, side, side,
                        GL_RGBA_INTEGER, GL_UNSIGNED_SHORT, cache.indirection[m].data());
  }
  glTextureParameteri(indirection, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTextureParameteri(indirection, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glCreateTextures(GL_TEXTURE_2D, 1, &texels);
  glTextureStorage2D(texels, 1, GL_RGBA8, static_cast<GLsizei>(cache.widthTexels),
                     static_cast<GLsizei>(cache.heightTexels));
  glTextureSubImage2D(texels, 0, 0, 0, static_cast<GLsizei>(cache.widthTexels),
                      static_cast<GLsizei>(cache.heightTexels), GL_RGBA, GL_UNSIGNED_BYTE,
                      cache.texels.data());
  glTextureParameteri(texels, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texels, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texels, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texels, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  glCreateTextures(GL_TEXTURE_2D, 3, targets);
  glTextureStorage2D(targets[0], 1, GL_RGBA8, viewport.width, viewport.height);
  glTextureStorage2D(targets[1], 1, settings.need8 ? GL_RGBA8UI : GL_RGBA32UI, viewport.width,
                     viewport.height);
  glTextureStorage2D(targets[2], 1, GL_DEPTH_COMPONENT32F, viewport.width, viewport.height);
  GLuint framebuffer = 0;
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, targets[0], 0);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT1, targets[1], 0);
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, targets[2], 0);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer, 2, buffers);
  const GLfloat clearColor[4] = {0, 0, 0, 0}, one = 1.0f;
  const glm::uvec4 clearNeed = reference::needClearValue(settings.need8);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, clearColor);
  glClearNamedFramebufferuiv(framebuffer, GL_COLOR, 1, &clearNeed.x);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);

  GLuint vertexArray = 0, buffer = 0, indices = 0;
  glCreateVertexArrays(1, &vertexArray);
  glCreateBuffers(1, &buffer);
  glCreateBuffers(1, &indices);
  glNamedBufferData(buffer,
                    static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(reference::ClipVertex)),
                    mesh.vertices.data(), GL_STATIC_DRAW);
  glNamedBufferData(indices, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                    mesh.indices.data(), GL_STATIC_DRAW);
  glVertexArrayVertexBuffer(vertexArray, 0, buffer, 0, sizeof(reference::ClipVertex));
  glVertexArrayElementBuffer(vertexArray, indices);
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vertexArray, a);
    glVertexArrayAttribBinding(vertexArray, a, 0);
  }
  glVertexArrayAttribFormat(vertexArray, 0, 4, GL_FLOAT, GL_FALSE,
                            offsetof(reference::ClipVertex, position));
  glVertexArrayAttribFormat(vertexArray, 1, 2, GL_FLOAT, GL_FALSE,
                            offsetof(reference::ClipVertex, uv));

  glUseProgram(program.id());
  glUniform1i(program.uniform("uVt.pageSize"), static_cast<GLint>(d.pageSize));
  glUniform1i(program.uniform("uVt.border"), static_cast<GLint>(d.border));
  glUniform1i(program.uniform("uVt.finestLevel"), static_cast<GLint>(d.finestLevel()));
  glUniform1i(program.uniform("uVt.trilinear"), settings.trilinear ? 1 : 0);
  glUniform1i(program.uniform("uVt.exactFilter"), settings.exactFilter ? 1 : 0);
  glUniform1i(program.uniform("uVt.need8"), settings.need8 ? 1 : 0);
  glUniform2f(program.uniform("uVt.cacheSize"), static_cast<float>(cache.widthTexels),
              static_cast<float>(cache.heightTexels));
  glUniform1i(program.uniform("uFinestLevel"), static_cast<GLint>(d.finestLevel()));
  glUniform1i(program.uniform("uIndirection"), 0);
  glUniform1i(program.uniform("uCache"), 1);
  glBindTextureUnit(0, indirection);
  glBindTextureUnit(1, texels);

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, viewport.width, viewport.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(vertexArray);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);

  const size_t pixels = static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height);
  ShadedFrame frame{std::vector<uint8_t>(pixels * 4), std::vector<glm::uvec4>(pixels)};
  glGetTextureImage(targets[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels * 4),
                    frame.color.data());
  if (settings.need8) {
    std::vector<glm::u8vec4> need(pixels);
    glGetTextureImage(targets[1], 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE,
                      static_cast<GLsizei>(pixels * 4), need.data());
    for (size_t i = 0; i < pixels; ++i) frame.need[i] = glm::uvec4(need[i]);
  } else {
    glGetTextureImage(targets[1], 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                      static_cast<GLsizei>(pixels * 16), frame.need.data());
  }
  EXPECT_EQ(glGetError(), GLenum{GL_NO_ERROR});
  glDeleteBuffers(1, &buffer);
  glDeleteBuffers(1, &indices);
  glDeleteVertexArrays(1, &vertexArray);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(3, targets);
  glDeleteTextures(1, &texels);
  glDeleteTextures(1, &indirection);
  return frame;
}

// Textured triangles at many scales and angles: magnified, minified, grazing, some clipped.
reference::ClipSpaceMesh texturedScene(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), wRange(0.4f, 4.0f);
  reference::ClipSpaceMesh mesh;
  for (int k = 0; k < 80; ++k) {
    const float spread = k % 4 == 0 ? 0.02f : (k % 4 == 1 ? 0.2f : 0.6f);
    const glm::vec2 centre(0.5f + 0.45f * unit(random), 0.5f + 0.45f * unit(random));
    const glm::vec2 xy(unit(random), unit(random));
    for (int corner = 0; corner < 3; ++corner) {
      const float w = wRange(random);
      const glm::vec2 p = xy + 0.8f * glm::vec2(unit(random), unit(random));
      mesh.vertices.push_back(
          {{p.x * w, p.y * w, 0.9f * unit(random) * w, w},
           glm::clamp(centre + spread * glm::vec2(unit(random), unit(random)), 0.0f, 1.0f)});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  }
  // s and t exactly 0 and 1 at the corners of a screen-filling background quad drawn last.
  const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
  for (const auto& [x, y] :
       std::vector<std::pair<float, float>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    mesh.vertices.push_back({{x, y, 0.99f, 1.0f}, {(x + 1) / 2, (y + 1) / 2}});
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  return mesh;
}

struct Mode {
  bool exactFilter, trilinear, need8;
};

class LlvmpipeShading : public ::testing::TestWithParam<Mode> {};

TEST_P(LlvmpipeShading, OracleMatchesColourAndNeedbufferBitForBit) {
  ::setenv("LP_NUM_THREADS", "2", 1);
  const HeadlessContext context;
  if (context.renderer().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not llvmpipe: " << context.renderer();
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 16, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
  const VirtualTextureReader reader(dir / "t.vt");
  // Levels 0..2 resident, every other page of level 3, a few of level 4: the rest falls back.
  std::vector<uint64_t> resident;
  for (uint64_t p = 0; p < pageCount(2); ++p) resident.push_back(p);
  for (uint64_t p = firstPageOfLevel(3); p < firstPageOfLevel(4); p += 2) resident.push_back(p);
  for (uint64_t p = firstPageOfLevel(4); p < pageCount(4); p += 7) resident.push_back(p);
  const reference::CacheState cache = reference::makeCacheState(reader, resident, 12, 8);

  reference::RenderSettings settings;
  settings.viewport = {192, 128};
  settings.profile =
      cpuHasFma() ? reference::PrecisionProfile::kLlvmpipe : reference::PrecisionProfile::kExact;
  settings.exactFilter = GetParam().exactFilter;
  settings.trilinear = GetParam().trilinear;
  settings.need8 = GetParam().need8;
  for (const unsigned seed : {11u, 12u}) {
    const reference::ClipSpaceMesh mesh = texturedScene(seed);
    const ShadedFrame gl = drawWithLlvmpipe(mesh, cache, settings);
    const reference::Frame oracle = reference::renderFrame(mesh, cache, settings);
    size_t colour = 0, need = 0, maxDifference = 0, covered = 0;
    for (size_t i = 0; i < oracle.need.size(); ++i) {
      covered += oracle.triangle[i] >= 0;
      need += gl.need[i] != oracle.need[i];
      for (size_t c = 0; c < 4; ++c) {
        const int difference = std::abs(int{gl.color[i * 4 + c]} - int{oracle.color[i * 4 + c]});
        colour += difference != 0;
        maxDifference = std::max(maxDifference, static_cast<size_t>(difference));
      }
    }
    EXPECT_EQ(covered, oracle.need.size()) << "the background quad covers every pixel";
    EXPECT_EQ(need, 0u) << "seed " << seed;
    EXPECT_EQ(colour, 0u) << "seed " << seed << ", largest difference " << maxDifference;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, LlvmpipeShading,
                         ::testing::Values(Mode{true, true, false}, Mode{true, false, true},
                                           Mode{false, true, false}, Mode{false, false, true}),
                         [](const auto& info) {
                           return std::string(info.param.exactFilter ? "TexelFetch"
                                                                     : "HardwareLinear") +
                                  (info.param.trilinear ? "Trilinear" : "Bilinear") +
                                  (info.param.need8 ? "Need8" : "Need32");
                         });

}  // namespace
}  // namespace vt
