#include "eval/frame_drawer.h"

namespace vt {

void FrameDrawer::draw(const FramePlan& plan, ViewColor viewColor, bool wantsDepth,
                       DrawnPasses& out) {
  out.color.clear();
  out.depth.clear();
  out.lookAheadNeed.clear();
  std::vector<uint8_t>* color = viewColor == ViewColor::kReadBack ? &out.color : nullptr;
  std::vector<float>* depth = wantsDepth ? &out.depth : nullptr;
  const NeedPass& need = plan.need;
  // The LookAhead pass first, so that the last pass drawn is the view whenever its colour is asked
  // (a window shows the last pass: vt view).
  if (plan.lookAhead) {
    const NeedPass& ahead = *plan.lookAhead;
    pass(ahead.view, ahead.viewport, ahead.scaleLog2, ahead.jitter, nullptr, &out.lookAheadNeed,
         nullptr, false);
  }
  if (plan.needPassIsTheView()) {
    out.view = pass(plan.camera, plan.screen, 0, need.jitter, color, &out.need, depth,
                    plan.delayedReadback);
  } else {
    pass(need.view, need.viewport, need.scaleLog2, need.jitter, nullptr, &out.need, depth,
         plan.delayedReadback);
    if (viewColor != ViewColor::kNone)
      out.view = pass(plan.camera, plan.screen, 0, glm::vec2(0.0f), color, nullptr, nullptr, false);
  }
}

void FrameDrawer::capture(const FramePlan& plan, DrawnPasses& out) {
  out.view =
      pass(plan.camera, plan.screen, 0, glm::vec2(0.0f), &out.color, &out.need, nullptr, false);
}

ClipSpaceMesh FrameDrawer::pass(const Camera& camera, Viewport viewport, int scaleLog2,
                                glm::vec2 jitter, std::vector<uint8_t>* color,
                                std::vector<glm::uvec4>* need, std::vector<float>* depth,
                                bool delayed) {
  RenderSettings settings = settings_;
  settings.viewport = viewport;
  settings.needScaleLog2 = scaleLog2;
  // Nobody looks at the colour: the oracle reads no texel, the GL path reads no colour back.
  settings.needOnly = color == nullptr;
  const bool readDepth = depth != nullptr;
  ClipSpaceMesh clip = toClipSpace(mesh_, camera, viewport, jitter);
  renderer_.cacheChanged();  // the management step changed it since the last draw
  Frame frame = delayed && need ? renderer_.renderDelayed(clip, settings, readDepth)
                                : renderer_.render(clip, settings, readDepth);
  if (color) *color = std::move(frame.color);
  if (need) *need = std::move(frame.need);
  if (depth) *depth = std::move(frame.depth);
  return clip;
}

}  // namespace vt
