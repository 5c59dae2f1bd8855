#include "gl/gl_frame_renderer.h"

#include <cstddef>
#include <vector>

#include "gl/virtual_texture_program.h"

namespace vt {
namespace {

// A needbuffer of `pixels` values fetched by read(destination, bytes) in the target's encoding;
// the 8-bit encoding's channels are widened to 32 bits.
template <class Read>
std::vector<glm::uvec4> readNeed(size_t pixels, bool need8, Read read) {
  std::vector<glm::uvec4> need(pixels);
  if (!need8) {
    read(need.data(), pixels * sizeof(glm::uvec4));
    return need;
  }
  std::vector<glm::u8vec4> narrow(pixels);
  read(narrow.data(), pixels * sizeof(glm::u8vec4));
  for (size_t i = 0; i < pixels; ++i) need[i] = glm::uvec4(narrow[i]);
  return need;
}

}  // namespace

GlFrameRenderer::GlFrameRenderer(const reference::CacheState& cache)
    : GlFrameRenderer(cache, virtualTextureFragmentSource()) {}

GlFrameRenderer::GlFrameRenderer(const reference::CacheState& cache,
                                 const std::string& fragmentSource)
    : cache_(cache), program_(virtualTextureVertexSource(), fragmentSource) {
  const TextureDescription& d = cache.description;
  glCreateTextures(GL_TEXTURE_2D, 1, &indirection_);
  const auto finestSide = static_cast<GLsizei>(pagesPerSide(d.finestLevel()));
  glTextureStorage2D(indirection_, 1, GL_RGBA16UI, finestSide + finestSide / 2, finestSide);
  glTextureParameteri(indirection_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(indirection_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glCreateTextures(GL_TEXTURE_2D, 1, &texels_);
  const auto width = static_cast<GLsizei>(cache.widthTexels),
             height = static_cast<GLsizei>(cache.heightTexels);
  glTextureStorage2D(texels_, 1, GL_RGBA8, width, height);
  glTextureParameteri(texels_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texels_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texels_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texels_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  glCreateVertexArrays(1, &vertexArray_);
  glCreateBuffers(1, &vertices_);
  glCreateBuffers(1, &indices_);
  glVertexArrayVertexBuffer(vertexArray_, 0, vertices_, 0, sizeof(ClipVertex));
  glVertexArrayElementBuffer(vertexArray_, indices_);
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vertexArray_, a);
    glVertexArrayAttribBinding(vertexArray_, a, 0);
  }
  glVertexArrayAttribFormat(vertexArray_, 0, 4, GL_FLOAT, GL_FALSE, offsetof(ClipVertex, position));
  glVertexArrayAttribFormat(vertexArray_, 1, 2, GL_FLOAT, GL_FALSE, offsetof(ClipVertex, uv));
  uploadCache();
}

void GlFrameRenderer::uploadCache() {
  const TextureDescription& d = cache_.description;
  // Level m of the table at its origin in the one texture (virtual_texture_program.cpp).
  const auto finestSide = static_cast<GLint>(pagesPerSide(d.finestLevel()));
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    const auto side = static_cast<GLsizei>(pagesPerSide(m));
    const bool finest = m == d.finestLevel();
    glTextureSubImage2D(indirection_, 0, finest ? 0 : finestSide,
                        finest ? 0 : finestSide - 2 * side, side, side, GL_RGBA_INTEGER,
                        GL_UNSIGNED_SHORT, cache_.indirection[m].data());
  }
  glTextureSubImage2D(texels_, 0, 0, 0, static_cast<GLsizei>(cache_.widthTexels),
                      static_cast<GLsizei>(cache_.heightTexels), GL_RGBA, GL_UNSIGNED_BYTE,
                      cache_.texels.data());
}

GlFrameRenderer::~GlFrameRenderer() {
  if (readbackFence_) glDeleteSync(readbackFence_);
  glDeleteBuffers(2, readbackBuffers_);
  glDeleteBuffers(1, &vertices_);
  glDeleteBuffers(1, &indices_);
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(3, targets_);
  glDeleteTextures(1, &texels_);
  glDeleteTextures(1, &indirection_);
}

void GlFrameRenderer::prepareTargets(Viewport viewport, bool need8) {
  if (framebuffer_ && viewport.width == viewport_.width && viewport.height == viewport_.height &&
      need8 == need8_)
    return;
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(3, targets_);
  viewport_ = viewport;
  need8_ = need8;
  glCreateTextures(GL_TEXTURE_2D, 3, targets_);
  glTextureStorage2D(targets_[0], 1, GL_RGBA8, viewport.width, viewport.height);
  glTextureStorage2D(targets_[1], 1, need8 ? GL_RGBA8UI : GL_RGBA32UI, viewport.width,
                     viewport.height);
  glTextureStorage2D(targets_[2], 1, GL_DEPTH_COMPONENT32F, viewport.width, viewport.height);
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, targets_[0], 0);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT1, targets_[1], 0);
  glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, targets_[2], 0);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_, 2, buffers);
}

void GlFrameRenderer::uploadMesh(const ClipSpaceMesh& mesh) {
  glNamedBufferData(vertices_, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(ClipVertex)),
                    mesh.vertices.data(), GL_STATIC_DRAW);
  glNamedBufferData(indices_, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                    mesh.indices.data(), GL_STATIC_DRAW);
}

void GlFrameRenderer::draw(const ClipSpaceMesh& mesh, const reference::RenderSettings& settings) {
  submit(mesh, settings);
  glFinish();
}

void GlFrameRenderer::submit(const ClipSpaceMesh& mesh, const reference::RenderSettings& settings) {
  const TextureDescription& d = cache_.description;
  prepareTargets(settings.viewport, settings.need8);
  uploadMesh(mesh);
  const GLfloat clearColor[4] = {0, 0, 0, 0}, one = 1.0f;
  const glm::uvec4 clearNeed = reference::needClearValue(settings.need8);
  glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, clearColor);
  // The integer needbuffer is cleared as a texture: Mesa 22.3's softpipe loses a framebuffer
  // clear of an integer attachment when depth is cleared and drawn after it (README, softpipe).
  if (settings.need8) {
    const glm::u8vec4 narrow(clearNeed);
    glClearTexImage(targets_[1], 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, &narrow.x);
  } else {
    glClearTexImage(targets_[1], 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, &clearNeed.x);
  }
  glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &one);

  glUseProgram(program_.id());
  glUniform1i(program_.uniform("uVt.pageSize"), static_cast<GLint>(d.pageSize));
  glUniform1i(program_.uniform("uVt.border"), static_cast<GLint>(d.border));
  glUniform1i(program_.uniform("uVt.finestLevel"), static_cast<GLint>(d.finestLevel()));
  glUniform1i(program_.uniform("uVt.trilinear"), settings.trilinear ? 1 : 0);
  glUniform1i(program_.uniform("uVt.exactFilter"), settings.exactFilter ? 1 : 0);
  glUniform1i(program_.uniform("uVt.need8"), settings.need8 ? 1 : 0);
  glUniform1i(program_.uniform("uVt.needScaleLog2"), settings.needScaleLog2);
  glUniform2f(program_.uniform("uVt.cacheSize"), static_cast<float>(cache_.widthTexels),
              static_cast<float>(cache_.heightTexels));
  glUniform1i(program_.uniform("uFinestLevel"), static_cast<GLint>(d.finestLevel()));
  glUniform1i(program_.uniform("uIndirection"), 0);
  glUniform1i(program_.uniform("uCache"), 1);
  glBindTextureUnit(0, indirection_);
  glBindTextureUnit(1, texels_);

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, settings.viewport.width, settings.viewport.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(vertexArray_);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
}

GlFrame GlFrameRenderer::render(const ClipSpaceMesh& mesh,
                                const reference::RenderSettings& settings, bool readDepth) {
  draw(mesh, settings);
  const size_t pixels =
      static_cast<size_t>(settings.viewport.width) * static_cast<size_t>(settings.viewport.height);
  GlFrame frame;
  frame.color = readColor();
  frame.need = readNeed(pixels, settings.need8, [&](void* destination, size_t bytes) {
    glGetTextureImage(targets_[1], 0, GL_RGBA_INTEGER,
                      settings.need8 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_INT,
                      static_cast<GLsizei>(bytes), destination);
  });
  if (readDepth) {  // only for the Distance heuristic: a scene pays only for what it uses
    frame.depth.resize(pixels);
    glGetTextureImage(targets_[2], 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(pixels * sizeof(float)), frame.depth.data());
  }
  return frame;
}

void GlFrameRenderer::present(glm::ivec2 window) const {
  glNamedFramebufferReadBuffer(framebuffer_, GL_COLOR_ATTACHMENT0);
  glBlitNamedFramebuffer(framebuffer_, 0, 0, 0, viewport_.width, viewport_.height, 0, 0, window.x,
                         window.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

std::optional<GlFrame> GlFrameRenderer::renderAsync(const ClipSpaceMesh& mesh,
                                                    const reference::RenderSettings& settings,
                                                    bool readDepth) {
  submit(mesh, settings);
  std::optional<GlFrame> previous = collectReadback();  // the GPU works on this frame meanwhile
  const size_t pixels =
      static_cast<size_t>(settings.viewport.width) * static_cast<size_t>(settings.viewport.height);
  const size_t needBytes = pixels * (settings.need8 ? 4 : 16);
  if (!readbackBuffers_[0]) glCreateBuffers(2, readbackBuffers_);
  glNamedBufferData(readbackBuffers_[0], static_cast<GLsizeiptr>(needBytes), nullptr,
                    GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, readbackBuffers_[0]);
  glGetTextureImage(targets_[1], 0, GL_RGBA_INTEGER,
                    settings.need8 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_INT,
                    static_cast<GLsizei>(needBytes), nullptr);
  if (readDepth) {
    glNamedBufferData(readbackBuffers_[1], static_cast<GLsizeiptr>(pixels * sizeof(float)), nullptr,
                      GL_STREAM_READ);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, readbackBuffers_[1]);
    glGetTextureImage(targets_[2], 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(pixels * sizeof(float)), nullptr);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  readbackFence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();
  readbackViewport_ = settings.viewport;
  readbackNeed8_ = settings.need8;
  readbackDepth_ = readDepth;
  return previous;
}

std::optional<GlFrame> GlFrameRenderer::collectReadback() {
  if (!readbackFence_) return std::nullopt;
  while (glClientWaitSync(readbackFence_, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000) ==
         GL_TIMEOUT_EXPIRED) {
  }
  glDeleteSync(readbackFence_);
  readbackFence_ = nullptr;
  const size_t pixels =
      static_cast<size_t>(readbackViewport_.width) * static_cast<size_t>(readbackViewport_.height);
  GlFrame frame;
  frame.need = readNeed(pixels, readbackNeed8_, [&](void* destination, size_t bytes) {
    glGetNamedBufferSubData(readbackBuffers_[0], 0, static_cast<GLsizeiptr>(bytes), destination);
  });
  if (readbackDepth_) {
    frame.depth.resize(pixels);
    glGetNamedBufferSubData(readbackBuffers_[1], 0, static_cast<GLsizeiptr>(pixels * sizeof(float)),
                            frame.depth.data());
  }
  return frame;
}

std::vector<uint8_t> GlFrameRenderer::readColor() const {
  const size_t pixels =
      static_cast<size_t>(viewport_.width) * static_cast<size_t>(viewport_.height);
  std::vector<uint8_t> color(pixels * 4);
  glGetTextureImage(targets_[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels * 4),
                    color.data());
  return color;
}

}  // namespace vt
