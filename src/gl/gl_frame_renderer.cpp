#include "gl/gl_frame_renderer.h"

#include <cstddef>
#include <vector>

#include "gl/virtual_texture_program.h"
#include "shader/needbuffer.h"

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

size_t pixelCount(Viewport viewport) {
  return static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height);
}

// The cache texture's internal format: RGBA8, or the texture's own block format, so that a page
// costs in the cache what it costs on disk (S3TC: EXT_texture_compression_s3tc, in every
// desktop driver; BC1 as RGB, its pages being opaque).
GLenum cacheInternalFormat(PixelFormat format) {
  switch (format) {
    case PixelFormat::kBc1:
      return GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
    case PixelFormat::kBc3:
      return GL_COMPRESSED_RGBA_S3TC_DXT5_EXT;
    case PixelFormat::kUnorm8:
      break;
  }
  return GL_RGBA8;
}

}  // namespace

GlFrameRenderer::GlFrameRenderer(const CacheState& cache)
    : GlFrameRenderer(cache, virtualTextureFragmentSource()) {}

GlFrameRenderer::GlFrameRenderer(const CacheState& cache, const std::string& fragmentSource)
    : cache_(cache),
      program_(virtualTextureVertexSource(), fragmentSource),
      indirection_(createTexture(GL_TEXTURE_2D)),
      texels_(createTexture(GL_TEXTURE_2D)),
      vertexArray_(createVertexArray()),
      vertices_(createBuffer()),
      indices_(createBuffer()) {
  const TextureDescription& d = cache.description;
  const auto finestSide = static_cast<GLsizei>(pagesPerSide(d.finestLevel()));
  glTextureStorage2D(indirection_.get(), 1, GL_RGBA16UI, finestSide + finestSide / 2, finestSide);
  glTextureParameteri(indirection_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(indirection_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const auto width = static_cast<GLsizei>(cache.widthTexels),
             height = static_cast<GLsizei>(cache.heightTexels);
  glTextureStorage2D(texels_.get(), 1, cacheInternalFormat(d.format), width, height);
  glTextureParameteri(texels_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texels_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texels_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texels_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  const GLuint vertexArray = vertexArray_.get();
  glVertexArrayVertexBuffer(vertexArray, 0, vertices_.get(), 0, sizeof(ClipVertex));
  glVertexArrayElementBuffer(vertexArray, indices_.get());
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vertexArray, a);
    glVertexArrayAttribBinding(vertexArray, a, 0);
  }
  glVertexArrayAttribFormat(vertexArray, 0, 4, GL_FLOAT, GL_FALSE, offsetof(ClipVertex, position));
  glVertexArrayAttribFormat(vertexArray, 1, 2, GL_FLOAT, GL_FALSE, offsetof(ClipVertex, uv));
  cacheChanged();
}

void GlFrameRenderer::cacheChanged() {
  const TextureDescription& d = cache_.description;
  // Level m of the table at its origin in the one texture (virtual_texture_program.cpp).
  const auto finestSide = static_cast<GLint>(pagesPerSide(d.finestLevel()));
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    const auto side = static_cast<GLsizei>(pagesPerSide(m));
    const bool finest = m == d.finestLevel();
    glTextureSubImage2D(indirection_.get(), 0, finest ? 0 : finestSide,
                        finest ? 0 : finestSide - 2 * side, side, side, GL_RGBA_INTEGER,
                        GL_UNSIGNED_SHORT, cache_.indirection.level(m).data());
  }
  const auto width = static_cast<GLsizei>(cache_.widthTexels),
             height = static_cast<GLsizei>(cache_.heightTexels);
  if (isBlockCompressed(d.format))
    glCompressedTextureSubImage2D(texels_.get(), 0, 0, 0, width, height,
                                  cacheInternalFormat(d.format),
                                  static_cast<GLsizei>(cache_.blocks.size()), cache_.blocks.data());
  else
    glTextureSubImage2D(texels_.get(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE,
                        cache_.texels.data());
}

void GlFrameRenderer::prepareTargets(Viewport viewport, bool need8) {
  if (framebuffer_ && viewport.width == viewport_.width && viewport.height == viewport_.height &&
      need8 == need8_)
    return;
  framebuffer_.reset();
  for (GlTexture& target : targets_) target.reset();
  viewport_ = viewport;
  need8_ = need8;
  for (GlTexture& target : targets_) target = createTexture(GL_TEXTURE_2D);
  const GLuint color = targets_[0].get(), need = targets_[1].get(), depth = targets_[2].get();
  glTextureStorage2D(color, 1, GL_RGBA8, viewport.width, viewport.height);
  glTextureStorage2D(need, 1, need8 ? GL_RGBA8UI : GL_RGBA32UI, viewport.width, viewport.height);
  glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, viewport.width, viewport.height);
  framebuffer_ = createFramebuffer();
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, color, 0);
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT1, need, 0);
  glNamedFramebufferTexture(framebuffer_.get(), GL_DEPTH_ATTACHMENT, depth, 0);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_.get(), 2, buffers);
}

void GlFrameRenderer::uploadMesh(const ClipSpaceMesh& mesh) {
  glNamedBufferData(vertices_.get(),
                    static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(ClipVertex)),
                    mesh.vertices.data(), GL_STATIC_DRAW);
  glNamedBufferData(indices_.get(), static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                    mesh.indices.data(), GL_STATIC_DRAW);
}

void GlFrameRenderer::draw(const ClipSpaceMesh& mesh, const RenderSettings& settings) {
  submit(mesh, settings);
  glFinish();
}

void GlFrameRenderer::warmUp(const ClipSpaceMesh& mesh, const RenderSettings& settings) {
  draw(mesh, settings);
}

void GlFrameRenderer::submit(const ClipSpaceMesh& mesh, const RenderSettings& settings) {
  const TextureDescription& d = cache_.description;
  prepareTargets(settings.viewport, settings.need8);
  uploadMesh(mesh);
  const GLfloat clearColor[4] = {0, 0, 0, 0}, one = 1.0f;
  const glm::uvec4 clearNeed = needClearValue(settings.need8);
  glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0, clearColor);
  // The integer needbuffer is cleared as a texture: Mesa 22.3's softpipe loses a framebuffer
  // clear of an integer attachment when depth is cleared and drawn after it
  // (docs/precision-models.md, softpipe).
  if (settings.need8) {
    const glm::u8vec4 narrow(clearNeed);
    glClearTexImage(targets_[1].get(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE, &narrow.x);
  } else {
    glClearTexImage(targets_[1].get(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, &clearNeed.x);
  }
  glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &one);

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
  glBindTextureUnit(0, indirection_.get());
  glBindTextureUnit(1, texels_.get());

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, settings.viewport.width, settings.viewport.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(vertexArray_.get());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
}

Frame GlFrameRenderer::render(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                              bool readDepth) {
  draw(mesh, settings);
  const size_t pixels = pixelCount(settings.viewport);
  Frame frame;
  frame.viewport = settings.viewport;
  if (!settings.needOnly) frame.color = readColor();
  frame.need = readNeed(pixels, settings.need8, [&](void* destination, size_t bytes) {
    glGetTextureImage(targets_[1].get(), 0, GL_RGBA_INTEGER,
                      settings.need8 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_INT,
                      static_cast<GLsizei>(bytes), destination);
  });
  if (readDepth) {
    frame.depth.resize(pixels);
    glGetTextureImage(targets_[2].get(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(pixels * sizeof(float)), frame.depth.data());
  }
  return frame;
}

void GlFrameRenderer::present(glm::ivec2 window) const {
  glNamedFramebufferReadBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT0);
  glBlitNamedFramebuffer(framebuffer_.get(), 0, 0, 0, viewport_.width, viewport_.height, 0, 0,
                         window.x, window.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Frame GlFrameRenderer::renderDelayed(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                                     bool readDepth) {
  submit(mesh, settings);
  Frame frame = collectReadback();  // the GPU works on this frame meanwhile
  startReadback(settings, readDepth);
  frame.viewport = settings.viewport;
  if (!settings.needOnly) frame.color = readColor();
  return frame;
}

void GlFrameRenderer::startReadback(const RenderSettings& settings, bool readDepth) {
  const size_t pixels = pixelCount(settings.viewport);
  const size_t needBytes = pixels * (settings.need8 ? 4 : 16);
  if (!readback_.buffers[0])
    for (GlBuffer& buffer : readback_.buffers) buffer = createBuffer();
  const GLuint need = readback_.buffers[0].get(), depth = readback_.buffers[1].get();
  glNamedBufferData(need, static_cast<GLsizeiptr>(needBytes), nullptr, GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, need);
  glGetTextureImage(targets_[1].get(), 0, GL_RGBA_INTEGER,
                    settings.need8 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_INT,
                    static_cast<GLsizei>(needBytes), nullptr);
  if (readDepth) {
    glNamedBufferData(depth, static_cast<GLsizeiptr>(pixels * sizeof(float)), nullptr,
                      GL_STREAM_READ);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, depth);
    glGetTextureImage(targets_[2].get(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(pixels * sizeof(float)), nullptr);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  readback_.fence = insertFence();
  glFlush();
  readback_.viewport = settings.viewport;
  readback_.need8 = settings.need8;
  readback_.depth = readDepth;
}

Frame GlFrameRenderer::collectReadback() {
  Frame frame;
  if (!readback_.fence) return frame;
  while (glClientWaitSync(readback_.fence.get(), GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000) ==
         GL_TIMEOUT_EXPIRED) {
  }
  readback_.fence.reset();
  const size_t pixels = pixelCount(readback_.viewport);
  frame.need = readNeed(pixels, readback_.need8, [&](void* destination, size_t bytes) {
    glGetNamedBufferSubData(readback_.buffers[0].get(), 0, static_cast<GLsizeiptr>(bytes),
                            destination);
  });
  if (readback_.depth) {
    frame.depth.resize(pixels);
    glGetNamedBufferSubData(readback_.buffers[1].get(), 0,
                            static_cast<GLsizeiptr>(pixels * sizeof(float)), frame.depth.data());
  }
  return frame;
}

std::vector<uint8_t> GlFrameRenderer::readColor() const {
  std::vector<uint8_t> color(pixelCount(viewport_) * 4);
  glGetTextureImage(targets_[0].get(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                    static_cast<GLsizei>(color.size()), color.data());
  return color;
}

std::string GlFrameRenderer::describe(const RenderSettings&) const {
  return "gl: " + std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}

}  // namespace vt
