#include "eval/flight.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "common/elapsed_time.h"
#include "eval/flight_run.h"
#include "eval/frame_drawer.h"
#include "eval/frame_plan.h"
#include "runtime/needbuffer_scale.h"
#include "shader/needbuffer.h"

namespace vt {

std::vector<uint8_t> referenceImage(const ResidentRenderer& everything, const Mesh& mesh,
                                    const Camera& camera, const RenderSettings& settings) {
  RenderSettings full = settings;
  full.needScaleLog2 = 0;
  return everything.draw(toClipSpace(mesh, camera, full.viewport), full).color;
}

FlightResult fly(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                 const FlightConfiguration& configuration, const FlightOptions& options) {
  using Clock = std::chrono::steady_clock;
  const RenderSettings& settings = options.settings;
  // The first frame's needbuffer with every page resident, for the initial cache state.
  std::vector<glm::uvec4> firstNeed;
  if (configuration.preloadVisible)
    firstNeed = makeResidentRenderer(reader)
                    ->draw(toClipSpace(mesh, path.at(0), settings.viewport), settings)
                    .need;
  const std::vector<uint64_t> initial =
      initialPages(reader, configuration, firstNeed, settings.need8);
  FlightRun run(reader, configuration, options,
                reducedViewport(settings.viewport, configuration.needScaleLog2), initial);
  const std::unique_ptr<FrameRenderer> renderer =
      makeFrameRenderer(options.backend, run.runtime().cacheState());
  FrameDrawer drawer(mesh, settings, *renderer);

  DrawnPasses drawn;
  const int frames = options.lastFrame < 0 ? path.frameCount()
                                           : std::min(path.frameCount(), options.lastFrame + 1);
  for (int frameNumber = 0; frameNumber < frames; ++frameNumber) {
    const FramePlan plan = planFrame(configuration, settings.viewport, path, frameNumber);
    const bool wantsColor =
        options.reference || (options.wantsColor && options.wantsColor(frameNumber));
    const auto drawStart = Clock::now();
    drawer.draw(plan, wantsColor ? ViewColor::kReadBack : ViewColor::kNone,
                run.runtime().needsDepth(), drawn);
    const double drawSeconds = secondsSince(drawStart);

    if (options.capture && options.wantsCapture && options.wantsCapture(frameNumber)) {
      const auto captureStart = Clock::now();
      DrawnPasses captured;
      drawer.capture(plan, captured);
      options.capture(FlightCaptureView{frameNumber, captured.view, captured.color, captured.need,
                                        run.runtime()});
      run.times().other += secondsSince(captureStart);
    }
    std::vector<uint8_t> expected;
    if (options.reference) {
      const auto referenceStart = Clock::now();
      expected = options.reference(frameNumber);
      run.times().reference += secondsSince(referenceStart);
    }
    run.frame(frameNumber, plan.previous, plan.camera,
              DrawnFrame{.color = drawn.color,
                         .need = drawn.need,
                         .depth = drawn.depth,
                         .lookAheadNeed = drawn.lookAheadNeed,
                         .reference = expected},
              drawSeconds);
  }
  return run.finish();
}

}  // namespace vt
