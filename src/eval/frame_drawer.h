#pragma once
// Draws what a FramePlan (frame_plan.h) asks for with one FrameRenderer, from the cache state the
// renderer reads: the LookAhead pass, then the needbuffer pass (with the view's colour when the
// needbuffer is the view's own, else the colour in a pass of its own, last), the needbuffer pass
// under delayed readback when the plan asks for it (FrameRenderer::renderDelayed).

#include <memory>
#include <span>
#include <vector>

#include "eval/frame_plan.h"
#include "render/frame_renderer.h"
#include "render/render_settings.h"
#include "scene/mesh.h"

namespace vt {

struct DrawnPasses {
  std::vector<uint8_t> color;  // the view, RGBA8 rows bottom to top, when asked
  std::vector<glm::uvec4> need, lookAheadNeed;
  std::vector<float> depth;  // the needbuffer pass's, when asked
  ClipSpaceMesh view;        // the view's clip-space mesh (the needbuffer's when it is the view)
};

// What becomes of the view's colour: not drawn where the needbuffer pass is not the view, drawn
// for a window to show (the last pass), or drawn and read back.
enum class ViewColor { kNone, kShown, kReadBack };

class FrameDrawer {
 public:
  // `settings`: everything but the viewport, which each pass takes from the plan. `renderer`
  // draws from a cache state the caller changes between frames; both must outlive the drawer.
  FrameDrawer(const Mesh& mesh, const RenderSettings& settings, FrameRenderer& renderer)
      : mesh_(mesh), settings_(settings), renderer_(renderer) {}

  // Fills `out` (reused from frame to frame) with what the plan draws: what it does not draw
  // (the colour unless read back, depth unless asked, the LookAhead needbuffer without a
  // LookAhead pass) is left empty.
  void draw(const FramePlan& plan, ViewColor color, bool wantsDepth, DrawnPasses& out);

  // The plan's view at the screen's resolution with a full-size needbuffer, synchronously: what a
  // capture records. Leaves the delayed readback of the main pass alone.
  void capture(const FramePlan& plan, DrawnPasses& out);

 private:
  // Returns the clip-space mesh it drew.
  ClipSpaceMesh pass(const Camera& camera, Viewport viewport, int scaleLog2, glm::vec2 jitter,
                     std::vector<uint8_t>* color, std::vector<glm::uvec4>* need,
                     std::vector<float>* depth, bool delayed);

  const Mesh& mesh_;
  const RenderSettings settings_;
  FrameRenderer& renderer_;
};

}  // namespace vt
