#pragma once
// The GL renderer of one frame: the virtual-texture program (the shared shader logic) over a cache
// state uploaded as textures, drawing clip-space meshes into a colour target (RGBA8), a needbuffer
// (RGBA32UI, or RGBA8UI for the 8-bit encoding) and a 32F depth buffer with GL_LESS, then reading
// them back. Needs a current OpenGL 4.5 context (HeadlessContext or a window's) for its whole
// life. Rows of the readback run bottom to top, like the oracle's frames.

#include <epoxy/gl.h>

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "gl/gl_objects.h"
#include "gl/gl_program.h"
#include "render/frame_renderer.h"

namespace vt {

class GlFrameRenderer : public FrameRenderer {
 public:
  // Uploads the cache state: the page cache as an RGBA8 texture with GL_LINEAR filtering and the
  // indirection table as one RGBA16UI texture holding every level side by side
  // (virtual_texture_program.cpp). Reads `cache` again at cacheChanged(): it must outlive the
  // renderer.
  explicit GlFrameRenderer(const CacheState& cache);
  // The same with another fragment shader: the planted-bug tests' variants of the real one.
  GlFrameRenderer(const CacheState& cache, const std::string& fragmentSource);

  // Draws and reads back colour (unless settings.needOnly), needbuffer and, when asked, depth.
  Frame render(const ClipSpaceMesh& mesh, const RenderSettings& settings,
               bool readDepth = false) override;
  // Draws without waiting, then collects the needbuffer (and depth, if it was asked for) of the
  // frame drawn by the previous call, whose copy into pixel-buffer objects was fenced when it was
  // drawn, and starts this frame's copy; reads this frame's colour synchronously.
  Frame renderDelayed(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                      bool readDepth = false) override;
  // Uploads the cache state's texels and indirection table again (the textures keep their size:
  // the cache's layout is fixed).
  void cacheChanged() override;
  void warmUp(const ClipSpaceMesh& mesh, const RenderSettings& settings) override;
  const CacheState* cache() const override { return &cache_; }
  std::string describe(const RenderSettings& settings) const override;

  // Uploads the mesh, draws and waits for the GPU (glFinish) without reading back: for timing.
  void draw(const ClipSpaceMesh& mesh, const RenderSettings& settings);
  // Copies the last frame's colour to the current context's window (framebuffer 0), scaled to
  // `window` pixels.
  void present(glm::ivec2 window) const;

 private:
  // The needbuffer and depth copied into pixel-buffer objects, behind a fence.
  struct Readback {
    std::array<GlBuffer, 2> buffers;  // needbuffer, depth
    GlFence fence;
    Viewport viewport{0, 0};
    bool need8 = false, depth = false;
  };

  void prepareTargets(Viewport viewport, bool need8);
  void submit(const ClipSpaceMesh& mesh, const RenderSettings& settings);
  void startReadback(const RenderSettings& settings, bool readDepth);
  // The readback in flight, waited for; an empty frame when there is none.
  Frame collectReadback();
  std::vector<uint8_t> readColor() const;
  void uploadMesh(const ClipSpaceMesh& mesh);

  const CacheState& cache_;
  GlProgram program_;
  GlTexture indirection_, texels_;
  std::array<GlTexture, 3> targets_;  // colour, needbuffer, depth
  GlFramebuffer framebuffer_;
  GlVertexArray vertexArray_;
  GlBuffer vertices_, indices_;
  Viewport viewport_{0, 0};
  bool need8_ = false;
  Readback readback_;
};

}  // namespace vt
