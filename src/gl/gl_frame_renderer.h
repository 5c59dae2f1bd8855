#pragma once
// The GL renderer of one frame: the virtual-texture program (the shared shader logic) over a cache
// state uploaded as textures, drawing clip-space meshes into a colour target (RGBA8), a needbuffer
// (RGBA32UI, or RGBA8UI for the 8-bit encoding) and a 32F depth buffer with GL_LESS, then reading
// them back. Needs a current HeadlessContext. Rows of the readback run bottom to top, like the
// oracle's frames.

#include <epoxy/gl.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gl/gl_program.h"
#include "reference/cache_state.h"
#include "reference/renderer.h"

namespace vt {

struct GlFrame {
  std::vector<uint8_t> color;    // RGBA8
  std::vector<glm::uvec4> need;  // widened to 32 bits per channel
  std::vector<float> depth;      // window depth (32-bit float target), 1.0 where no geometry;
                                 // read back only when asked
};

class GlFrameRenderer {
 public:
  // Uploads the cache state: the page cache as an RGBA8 texture with GL_LINEAR filtering and the
  // indirection table as one RGBA16UI texture holding every level side by side
  // (virtual_texture_program.cpp).
  explicit GlFrameRenderer(const reference::CacheState& cache);
  // The same with another fragment shader: the planted-bug tests' variants of the real one.
  GlFrameRenderer(const reference::CacheState& cache, const std::string& fragmentSource);
  ~GlFrameRenderer();
  GlFrameRenderer(const GlFrameRenderer&) = delete;
  GlFrameRenderer& operator=(const GlFrameRenderer&) = delete;

  // Uploads the cache state's texels and indirection table again, after the runtime changed them
  // (the textures keep their size: the cache's layout is fixed).
  void uploadCache();

  // Uploads the mesh, draws and waits for the GPU (glFinish) without reading back: for timing.
  void draw(const ClipSpaceMesh& mesh, const reference::RenderSettings& settings);
  // Draws and reads back colour and needbuffer.
  GlFrame render(const ClipSpaceMesh& mesh, const reference::RenderSettings& settings,
                 bool readDepth = false);
  // Asynchronous readback (thesis 3.2.4: the needbuffer's transfer need not stall the frame):
  // draws without waiting, then returns the needbuffer (and depth, if it was asked for) of the
  // frame drawn by the previous call, whose copy into pixel-buffer objects was fenced when it was
  // drawn, and starts this frame's copy. The first call returns nothing. Colour stays in the
  // target (present(), readColor()).
  std::optional<GlFrame> renderAsync(const ClipSpaceMesh& mesh,
                                     const reference::RenderSettings& settings,
                                     bool readDepth = false);
  // The colour of the frame drawn last (a synchronous read).
  std::vector<uint8_t> readColor() const;
  // Copies the last frame's colour to the current context's window (framebuffer 0), scaled to
  // `window` pixels.
  void present(glm::ivec2 window) const;

 private:
  void prepareTargets(Viewport viewport, bool need8);
  void submit(const ClipSpaceMesh& mesh, const reference::RenderSettings& settings);
  std::optional<GlFrame> collectReadback();
  void uploadMesh(const ClipSpaceMesh& mesh);

  const reference::CacheState& cache_;
  GlProgram program_;
  GLuint indirection_ = 0, texels_ = 0;
  GLuint targets_[3] = {0, 0, 0};
  GLuint framebuffer_ = 0, vertexArray_ = 0, vertices_ = 0, indices_ = 0;
  Viewport viewport_{0, 0};
  bool need8_ = false;
  // The readback in flight: its buffers, fence and what they hold.
  GLuint readbackBuffers_[2] = {0, 0};  // needbuffer, depth
  GLsync readbackFence_ = nullptr;
  Viewport readbackViewport_{0, 0};
  bool readbackNeed8_ = false, readbackDepth_ = false;
};

}  // namespace vt
