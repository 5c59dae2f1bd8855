// The oracle's rasterization against Mesa's llvmpipe, bit for bit: which triangle each pixel
// shows, its texture coordinates, their fine derivatives (helper pixels included) and its depth.
// llvmpipe's settings that results depend on are pinned here; the oracle's llvmpipe profile uses
// fused multiply-adds exactly when this CPU has FMA (as llvmpipe does), plain ones otherwise.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include "build/synthetic_texture.h"
#include "gl/gl_program.h"
#include "gl/headless_context.h"
#include "reference/renderer.h"
#include "test_support.h"

namespace vt {
namespace {

const char* kVertex = R"(#version 450 core
layout(location = 0) in vec4 aClipPosition;
layout(location = 1) in vec2 aUV;
out vec2 vUV;
void main() { vUV = aUV; gl_Position = aClipPosition; }
)";

const char* kFragment = R"(#version 450 core
in vec2 vUV;
layout(location = 0) out uvec4 outTriangle;
layout(location = 1) out vec4 outUV;
layout(location = 2) out vec4 outDerivatives;
void main() {
  outTriangle = uvec4(uint(gl_PrimitiveID) + 1u, 0u, 0u, 0u);
  outUV = vec4(vUV, 0.0, 0.0);
  outDerivatives = vec4(dFdxFine(vUV), dFdyFine(vUV));
}
)";

struct Readback {
  std::vector<glm::uvec4> triangle;
  std::vector<glm::vec4> uv, derivatives;
  std::vector<float> depth;
};

// Draws `mesh` into 32-bit targets and a 32F depth buffer (GL_LESS, cleared to 1).
Readback drawWithLlvmpipe(const reference::ClipSpaceMesh& mesh, reference::Viewport viewport) {
  const GlProgram program(kVertex, kFragment);
  GLuint targets[4];
  glCreateTextures(GL_TEXTURE_2D, 4, targets);
  glTextureStorage2D(targets[0], 1, GL_RGBA32UI, viewport.width, viewport.height);
  glTextureStorage2D(targets[1], 1, GL_RGBA32F, viewport.width, viewport.height);
  glTextureStorage2D(targets[2], 1, GL_RGBA32F, viewport.width, viewport.height);
  glTextureStorage2D(targets[3], 1, GL_DEPTH_COMPONENT32F, viewport.width, viewport.height);
  GLuint framebuffer = 0;
  glCreateFramebuffers(1, &framebuffer);
  for (int k = 0; k < 3; ++k)
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0 + k, targets[k], 0);
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, targets[3], 0);
  const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glNamedFramebufferDrawBuffers(framebuffer, 3, buffers);
  const GLuint zero[4] = {0, 0, 0, 0};
  const GLfloat zeros[4] = {0, 0, 0, 0}, one = 1.0f;
  glClearNamedFramebufferuiv(framebuffer, GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, zeros);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 2, zeros);
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
  glEnableVertexArrayAttrib(vertexArray, 0);
  glEnableVertexArrayAttrib(vertexArray, 1);
  glVertexArrayAttribFormat(vertexArray, 0, 4, GL_FLOAT, GL_FALSE,
                            offsetof(reference::ClipVertex, position));
  glVertexArrayAttribFormat(vertexArray, 1, 2, GL_FLOAT, GL_FALSE,
                            offsetof(reference::ClipVertex, uv));
  glVertexArrayAttribBinding(vertexArray, 0, 0);
  glVertexArrayAttribBinding(vertexArray, 1, 0);

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, viewport.width, viewport.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(program.id());
  glBindVertexArray(vertexArray);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);

  const size_t pixels = static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height);
  Readback result{std::vector<glm::uvec4>(pixels), std::vector<glm::vec4>(pixels),
                  std::vector<glm::vec4>(pixels), std::vector<float>(pixels)};
  const auto bytes = [&](size_t element) { return static_cast<GLsizei>(pixels * element); };
  glGetTextureImage(targets[0], 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, bytes(16),
                    result.triangle.data());
  glGetTextureImage(targets[1], 0, GL_RGBA, GL_FLOAT, bytes(16), result.uv.data());
  glGetTextureImage(targets[2], 0, GL_RGBA, GL_FLOAT, bytes(16), result.derivatives.data());
  glGetTextureImage(targets[3], 0, GL_DEPTH_COMPONENT, GL_FLOAT, bytes(4), result.depth.data());
  EXPECT_EQ(glGetError(), GLenum{GL_NO_ERROR});

  glDeleteBuffers(1, &buffer);
  glDeleteBuffers(1, &indices);
  glDeleteVertexArrays(1, &vertexArray);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(4, targets);
  return result;
}

// Random triangles of all sizes, perspective, overlapping, some crossing the near plane and the
// frustum's sides, some slivers and a coplanar duplicate.
reference::ClipSpaceMesh randomScene(unsigned seed, int triangles) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), wRange(0.3f, 3.0f);
  reference::ClipSpaceMesh mesh;
  const auto add = [&](glm::vec4 p, glm::vec2 uv) {
    mesh.vertices.push_back({p, uv});
    mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
  };
  for (int k = 0; k < triangles; ++k) {
    const float scale = k % 3 == 0 ? 0.05f : (k % 3 == 1 ? 0.4f : 1.6f);
    const glm::vec2 centre(unit(random), unit(random));
    for (int corner = 0; corner < 3; ++corner) {
      const float w = k % 7 == 0 && corner == 0 ? -0.5f : wRange(random);
      const glm::vec2 xy = centre + scale * glm::vec2(unit(random), unit(random));
      const float z = 0.8f * unit(random);
      add({xy.x * std::fabs(w), xy.y * std::fabs(w), z * std::fabs(w) - (w < 0 ? 1.0f : 0.0f), w},
          {0.5f + 0.5f * unit(random), 0.5f + 0.5f * unit(random)});
    }
  }
  for (int corner = 0; corner < 3; ++corner)
    add(mesh.vertices[static_cast<size_t>(corner)].position, {0.1f, 0.9f});
  return mesh;
}

class LlvmpipeRasterization : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("LP_NUM_THREADS", "2", 1);
    ::unsetenv("GALLIVM_PERF");
    ::unsetenv("GALLIUM_OVERRIDE_CPU_CAPS");
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4}, std::nullopt});
  }
  test::ScratchDirectory dir_;
};

TEST_F(LlvmpipeRasterization, OracleMatchesEveryPixelBitForBit) {
  const HeadlessContext context;
  if (context.renderer().find("llvmpipe") == std::string::npos)
    GTEST_SKIP() << "not llvmpipe: " << context.renderer();
  const VirtualTextureReader reader(dir_ / "t.vt");
  const reference::ResidentTexture texture(reader);
  reference::RenderSettings settings;
  settings.debugChannels = true;
  settings.profile = __builtin_cpu_supports("fma") ? reference::PrecisionProfile::kLlvmpipe
                                                   : reference::PrecisionProfile::kExact;
  settings.viewport = {160, 120};
  for (const unsigned seed : {1u, 2u, 3u}) {
    const reference::ClipSpaceMesh mesh = randomScene(seed, 120);
    const Readback gl = drawWithLlvmpipe(mesh, settings.viewport);
    const reference::Frame oracle = reference::renderFrame(mesh, texture, settings);
    size_t coverage = 0, uv = 0, derivatives = 0, depth = 0, covered = 0;
    for (size_t i = 0; i < oracle.triangle.size(); ++i) {
      const int32_t glTriangle = static_cast<int32_t>(gl.triangle[i].x) - 1;
      coverage += glTriangle != oracle.triangle[i];
      if (glTriangle < 0 || glTriangle != oracle.triangle[i]) continue;
      ++covered;
      uv += std::bit_cast<uint32_t>(gl.uv[i].x) != std::bit_cast<uint32_t>(oracle.uv[i].x) ||
            std::bit_cast<uint32_t>(gl.uv[i].y) != std::bit_cast<uint32_t>(oracle.uv[i].y);
      for (int c = 0; c < 4; ++c)
        derivatives += std::bit_cast<uint32_t>(gl.derivatives[i][c]) !=
                       std::bit_cast<uint32_t>(oracle.derivatives[i][c]);
      depth += std::bit_cast<uint32_t>(gl.depth[i]) != std::bit_cast<uint32_t>(oracle.depth[i]);
    }
    EXPECT_GT(covered, oracle.triangle.size() / 2) << "seed " << seed;
    EXPECT_EQ(coverage, 0u) << "seed " << seed << ": pixels showing another triangle";
    EXPECT_EQ(uv, 0u) << "seed " << seed << " of " << covered << " covered pixels";
    EXPECT_EQ(derivatives, 0u) << "seed " << seed;
    EXPECT_EQ(depth, 0u) << "seed " << seed;
  }
}

}  // namespace
}  // namespace vt
