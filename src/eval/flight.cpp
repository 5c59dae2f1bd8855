#include "eval/flight.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "common/elapsed_time.h"
#include "eval/flight_run.h"
#include "runtime/needbuffer_scale.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

using Clock = std::chrono::steady_clock;

// Draws camera views from the runtime's current cache state, at the screen's resolution or at a
// reduced needbuffer's (jittered per frame), with delayed readback as an option: then the main
// pass returns the previous frame's needbuffer and depth (FrameRenderer::renderDelayed).
class FrameDrawer {
 public:
  FrameDrawer(const Mesh& mesh, const RenderSettings& settings, Backend backend, int needScaleLog2)
      : mesh_(mesh), settings_(settings), backend_(backend), needScaleLog2_(needScaleLog2) {}

  // The runtime whose cache state the frames are drawn from.
  void attach(const VirtualTextureRuntime& runtime) {
    runtime_ = &runtime;
    renderer_ = makeFrameRenderer(backend_, runtime.cacheState());
  }

  Viewport needViewport() const { return reducedViewport(settings_.viewport, needScaleLog2_); }

  // `color` at the screen's resolution when asked (with the main pass when the needbuffer is
  // full-size, else in a pass of its own); `delayed`: the main pass under asynchronous readback.
  void draw(const Camera& camera, uint64_t frame, std::vector<uint8_t>* color,
            std::vector<glm::uvec4>& need, std::vector<float>* depth, bool delayed) {
    if (needScaleLog2_ == 0) {
      pass(camera, settings_.viewport, 0, glm::vec2(0.0f), color, &need, depth, delayed);
      return;
    }
    pass(camera, needViewport(), needScaleLog2_, needJitter(frame, needScaleLog2_), nullptr, &need,
         depth, delayed);
    if (color) pass(camera, settings_.viewport, 0, glm::vec2(0.0f), color, nullptr, nullptr, false);
  }

  // The camera at the screen's resolution with a full-size needbuffer, synchronously: what a
  // capture records. Leaves the delayed readback of the main pass alone.
  void capture(const Camera& camera, int frame, const FlightOptions& options) {
    std::vector<uint8_t> color;
    std::vector<glm::uvec4> need;
    const ClipSpaceMesh clip =
        pass(camera, settings_.viewport, 0, glm::vec2(0.0f), &color, &need, nullptr, false);
    options.capture(FlightCaptureView{frame, clip, color, need, *runtime_});
  }

 private:
  // Returns the clip-space mesh it drew.
  ClipSpaceMesh pass(const Camera& camera, Viewport viewport, int scaleLog2, glm::vec2 jitter,
                     std::vector<uint8_t>* color, std::vector<glm::uvec4>* need,
                     std::vector<float>* depth, bool delayed) {
    RenderSettings settings = settings_;
    settings.viewport = viewport;
    settings.needScaleLog2 = scaleLog2;
    // Nobody looks at the colour: the oracle reads no texel, the GL path reads no colour back.
    settings.needOnly = color == nullptr;
    const bool readDepth = depth != nullptr;
    const ClipSpaceMesh clip = toClipSpace(mesh_, camera, viewport, jitter);
    renderer_->cacheChanged();  // the management step changed it since the last draw
    Frame frame = delayed && need ? renderer_->renderDelayed(clip, settings, readDepth)
                                  : renderer_->render(clip, settings, readDepth);
    if (color) *color = std::move(frame.color);
    if (need) *need = std::move(frame.need);
    if (depth) *depth = std::move(frame.depth);
    return clip;
  }

  const Mesh& mesh_;
  const VirtualTextureRuntime* runtime_ = nullptr;
  const RenderSettings settings_;
  const Backend backend_;
  const int needScaleLog2_;
  std::unique_ptr<FrameRenderer> renderer_;
};

}  // namespace

std::vector<uint8_t> referenceImage(const ResidentRenderer& everything, const Mesh& mesh,
                                    const Camera& camera, const RenderSettings& settings) {
  RenderSettings full = settings;
  full.needScaleLog2 = 0;
  return everything.draw(toClipSpace(mesh, camera, full.viewport), full).color;
}

FlightResult fly(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                 const FlightConfiguration& configuration, const FlightOptions& options) {
  const RenderSettings& settings = options.settings;
  // The first frame's needbuffer with every page resident, for the initial cache state.
  std::vector<glm::uvec4> firstNeed;
  if (configuration.preloadVisible)
    firstNeed =
        makeResidentRenderer(reader)->draw(toClipSpace(mesh, path.at(0), settings.viewport), settings)
            .need;
  const std::vector<uint64_t> initial =
      initialPages(reader, configuration, firstNeed, settings.need8);
  FrameDrawer drawer(mesh, settings, options.backend, configuration.needScaleLog2);
  FlightRun run(reader, configuration, options, drawer.needViewport(), initial);
  drawer.attach(run.runtime());

  for (int frameNumber = 0; frameNumber < path.frameCount(); ++frameNumber) {
    const Camera current = path.at(frameNumber), previous = path.at(std::max(0, frameNumber - 1)),
                 beforePrevious = path.at(std::max(0, frameNumber - 2));
    const auto frameIndex = static_cast<uint64_t>(frameNumber);
    const bool wantsColor =
        options.reference || (options.wantsColor && options.wantsColor(frameNumber));
    const auto drawStart = Clock::now();
    std::vector<uint8_t> color;
    std::vector<glm::uvec4> need, lookAheadNeed;
    std::vector<float> depth;
    drawer.draw(current, frameIndex, wantsColor ? &color : nullptr, need,
                run.runtime().needsDepth() ? &depth : nullptr, configuration.asyncReadback);
    if (configuration.lookAhead != LookAhead::kNone)
      drawer.draw(lookAheadCamera(beforePrevious, previous, current, configuration.lookAhead),
                  frameIndex, nullptr, lookAheadNeed, nullptr, false);
    const double drawSeconds = secondsSince(drawStart);

    if (options.capture && options.wantsCapture && options.wantsCapture(frameNumber)) {
      const auto captureStart = Clock::now();
      drawer.capture(current, frameNumber, options);
      run.times().other += secondsSince(captureStart);
    }
    std::vector<uint8_t> expected;
    if (options.reference) {
      const auto referenceStart = Clock::now();
      expected = options.reference(frameNumber);
      run.times().reference += secondsSince(referenceStart);
    }
    run.frame(frameNumber, previous, current,
              DrawnFrame{.color = color,
                         .need = need,
                         .depth = depth,
                         .lookAheadNeed = lookAheadNeed,
                         .reference = expected},
              drawSeconds);
  }
  return run.finish();
}

}  // namespace vt
