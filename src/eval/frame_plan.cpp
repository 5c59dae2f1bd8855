#include "eval/frame_plan.h"

#include <algorithm>

#include "runtime/needbuffer_scale.h"
#include "scene/camera_motion.h"

namespace vt {

FramePlan planFrame(const FlightConfiguration& configuration, Viewport screen, uint64_t frame,
                    const Camera& beforePrevious, const Camera& previous, const Camera& current) {
  FramePlan plan;
  plan.frame = frame;
  plan.screen = screen;
  plan.camera = current;
  plan.previous = previous;
  const int scale = configuration.needScaleLog2;
  const auto pass = [&](LookAhead camera, const Camera& view) {
    return NeedPass{.camera = camera,
                    .scaleLog2 = scale,
                    .view = view,
                    .viewport = reducedViewport(screen, scale),
                    .jitter = needJitter(frame, scale)};
  };
  plan.need = pass(LookAhead::kNone, current);
  if (configuration.lookAhead != LookAhead::kNone)
    plan.lookAhead =
        pass(configuration.lookAhead,
             lookAheadCamera(beforePrevious, previous, current, configuration.lookAhead));
  plan.delayedReadback = configuration.asyncReadback;
  return plan;
}

FramePlan planFrame(const FlightConfiguration& configuration, Viewport screen,
                    const CameraPath& path, int frame) {
  return planFrame(configuration, screen, static_cast<uint64_t>(frame),
                   path.at(std::max(0, frame - 2)), path.at(std::max(0, frame - 1)),
                   path.at(frame));
}

}  // namespace vt
