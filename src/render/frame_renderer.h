#pragma once
// The rendering box of the thesis's figure 3.5 as the loop sees it: draw a clip-space mesh from
// the current cache state into a Frame (colour, needbuffer, depth). The CPU oracle
// (reference/oracle_frame_renderer.h) and the GL path (gl/gl_frame_renderer.h) implement it;
// backends/backend.h makes one by name, the only place that chooses between them.

#include <string>

#include "render/cache_state.h"
#include "render/frame.h"
#include "render/render_settings.h"
#include "scene/clip_space_mesh.h"

namespace vt {

class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;

  // Draws `mesh` and waits for it. The frame holds the colour (unless settings.needOnly), the
  // needbuffer, and the depth exactly when `readDepth` (the Distance heuristic's input: a scene
  // pays only for what it uses); the oracle also fills the channels render_settings.h asks for.
  virtual Frame render(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                       bool readDepth = false) = 0;

  // Delayed readback (thesis 3.2.4: the needbuffer's transfer need not stall the frame): draws
  // `mesh` as render() does and returns its colour, but the needbuffer and depth of the frame the
  // previous call of renderDelayed drew (the GL path copies them behind a fence meanwhile). The
  // first call returns them empty.
  virtual Frame renderDelayed(const ClipSpaceMesh& mesh, const RenderSettings& settings,
                              bool readDepth = false) = 0;

  // The cache state it draws from has changed since the last draw (the runtime's management
  // step): the GL path uploads it again.
  virtual void cacheChanged() = 0;

  // Pays what only a first draw costs (the GL path compiles its shaders then), so that a timed
  // draw after it measures the frame alone.
  virtual void warmUp(const ClipSpaceMesh& mesh, const RenderSettings& settings) = 0;

  // The cache state it draws from; none when it draws every page resident.
  virtual const CacheState* cache() const = 0;

  // What draws under `settings`, for reports: "oracle, profile exact" or "gl: " and GL_RENDERER.
  virtual std::string describe(const RenderSettings& settings) const = 0;
};

}  // namespace vt
