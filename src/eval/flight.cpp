#include "eval/flight.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "eval/image_metrics.h"
#include "gl/gl_frame_renderer.h"
#include "runtime/needbuffer_scale.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Draws camera views from the runtime's current cache state with the oracle or the GL path, at
// the screen's resolution or at a reduced needbuffer's (jittered per frame), with asynchronous
// readback as an option: then the main pass returns the previous frame's needbuffer and depth
// (the GL path copies them through pixel-buffer objects behind a fence; the oracle keeps them).
class FrameDrawer {
 public:
  FrameDrawer(const Mesh& mesh, const VirtualTextureRuntime& runtime,
              const reference::RenderSettings& settings, bool gl, int needScaleLog2)
      : mesh_(mesh), runtime_(runtime), settings_(settings), needScaleLog2_(needScaleLog2) {
    if (gl) gl_ = std::make_unique<GlFrameRenderer>(runtime.cacheState());
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
    options.capture(FlightCaptureView{frame, clip, color, need, runtime_});
  }

 private:
  // Returns the clip-space mesh it drew.
  ClipSpaceMesh pass(const Camera& camera, Viewport viewport, int scaleLog2, glm::vec2 jitter,
                     std::vector<uint8_t>* color, std::vector<glm::uvec4>* need,
                     std::vector<float>* depth, bool delayed) {
    reference::RenderSettings settings = settings_;
    settings.viewport = viewport;
    settings.needScaleLog2 = scaleLog2;
    const bool readDepth = depth != nullptr;
    const ClipSpaceMesh clip = toClipSpace(mesh_, camera, viewport, jitter);
    if (gl_) {
      gl_->uploadCache();  // the management step changed it since the last draw
      if (delayed && need) {
        std::optional<GlFrame> previous = gl_->renderAsync(clip, settings, readDepth);
        if (color) *color = gl_->readColor();
        *need = previous ? std::move(previous->need) : std::vector<glm::uvec4>{};
        if (depth) *depth = previous ? std::move(previous->depth) : std::vector<float>{};
        return clip;
      }
      GlFrame frame = gl_->render(clip, settings, readDepth);
      if (color) *color = std::move(frame.color);
      if (need) *need = std::move(frame.need);
      if (depth) *depth = std::move(frame.depth);
      return clip;
    }
    reference::Frame frame = reference::renderFrame(clip, runtime_.cacheState(), settings);
    if (color) *color = std::move(frame.color);
    if (delayed && need) {
      std::swap(frame.need, delayedNeed_);
      if (readDepth) std::swap(frame.depth, delayedDepth_);
    }
    if (need) *need = std::move(frame.need);
    if (depth) *depth = std::move(frame.depth);
    return clip;
  }

  const Mesh& mesh_;
  const VirtualTextureRuntime& runtime_;
  const reference::RenderSettings settings_;
  const int needScaleLog2_;
  std::unique_ptr<GlFrameRenderer> gl_;
  std::vector<glm::uvec4> delayedNeed_;
  std::vector<float> delayedDepth_;
};

RuntimeOptions runtimeOptions(const VirtualTextureReader& reader,
                              const FlightConfiguration& configuration) {
  RuntimeOptions options;
  options.framesX = options.framesY = std::max(1u, configuration.cacheFrames);
  options.lockedLevels = configuration.lockedLevels;
  options.priority.heuristic = configuration.heuristic;
  options.priority.ancestors = configuration.ancestors;
  options.priority.noiseValueSkipping = configuration.noiseSkipping;
  options.trilinearParents = configuration.trilinearParents;
  options.randomSeed = configuration.seed;
  double meanNoise = 0.0;
  for (const float n : reader.noiseValues()) meanNoise += n;
  meanNoise /= static_cast<double>(std::max<size_t>(1, reader.noiseValues().size()));
  options.priority.noiseThreshold = configuration.noiseThreshold >= 0.0f
                                        ? configuration.noiseThreshold
                                        : static_cast<float>(meanNoise);
  return options;
}

// The initial cache state (thesis 4.2.1): levels 0..K-1 and, when asked, every page the first
// frame needs, found by drawing it with every page resident (with trilinear parents, and their
// parents).
std::vector<uint64_t> initialPages(const VirtualTextureReader& reader, const Mesh& mesh,
                                   const CameraPath& path, const FlightConfiguration& c,
                                   const reference::RenderSettings& settings) {
  std::vector<uint64_t> pages;
  const uint32_t levels = std::min(c.initialLevels, reader.description().levelCount);
  for (uint64_t p = 0; levels > 0 && p < pageCount(levels - 1); ++p) pages.push_back(p);
  if (c.preloadVisible) {
    const reference::ResidentTexture everything(reader);
    const reference::Frame first = reference::renderFrame(
        toClipSpace(mesh, path.at(0), settings.viewport), everything, settings);
    const std::vector<uint64_t> visible = neededPages(first.need, settings.need8).pages;
    if (c.trilinearParents) {  // the coarser level of each visible page's blend, first
      std::vector<uint64_t> parents;
      for (const uint64_t page : visible)
        if (levelOfAbsoluteIndex(page) > 0) parents.push_back(parentIndex(page));
      std::sort(parents.begin(), parents.end());
      parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
      pages.insert(pages.end(), parents.begin(), parents.end());
    }
    pages.insert(pages.end(), visible.begin(), visible.end());
  }
  return pages;
}

}  // namespace

std::vector<uint8_t> referenceImage(const reference::ResidentTexture& everything, const Mesh& mesh,
                                    const Camera& camera,
                                    const reference::RenderSettings& settings) {
  reference::RenderSettings full = settings;
  full.needScaleLog2 = 0;
  return reference::renderFrame(toClipSpace(mesh, camera, full.viewport), everything, full).color;
}

FlightResult fly(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                 const FlightConfiguration& configuration, const FlightOptions& options) {
  const reference::RenderSettings& settings = options.settings;
  RuntimeOptions runtimeSettings = runtimeOptions(reader, configuration);
  runtimeSettings.keepAnalysis = options.keepAnalysis;
  VirtualTextureRuntime runtime(reader, runtimeSettings);
  runtime.preload(initialPages(reader, mesh, path, configuration, settings));

  // Deterministic budget mode for evaluations, or a thread over a link in real time.
  std::unique_ptr<BudgetStreamer> budget;
  std::unique_ptr<ThreadedStreamer> thread;
  if (options.threadedStreaming)
    thread = std::make_unique<ThreadedStreamer>(reader, options.link);
  else
    budget = std::make_unique<BudgetStreamer>(reader, configuration.budget, configuration.latency);

  FrameDrawer drawer(mesh, runtime, settings, options.gl, configuration.needScaleLog2);
  const Viewport screen = settings.viewport, needViewport = drawer.needViewport();

  FlightResult result;
  result.frames.reserve(static_cast<size_t>(path.frameCount()));
  const auto start = Clock::now();
  uint64_t streamedBefore = 0, evictedBefore = 0;
  for (int frameNumber = 0; frameNumber < path.frameCount(); ++frameNumber) {
    const Camera current = path.at(frameNumber), previous = path.at(std::max(0, frameNumber - 1)),
                 beforePrevious = path.at(std::max(0, frameNumber - 2));
    const auto frameIndex = static_cast<uint64_t>(frameNumber);
    const bool wantsColor =
        options.reference || (options.wantsColor && options.wantsColor(frameNumber));
    std::vector<uint8_t> color;
    std::vector<glm::uvec4> need, lookAheadNeed;
    std::vector<float> depth;
    drawer.draw(current, frameIndex, wantsColor ? &color : nullptr, need,
                runtime.needsDepth() ? &depth : nullptr, configuration.asyncReadback);

    if (options.capture && options.wantsCapture && options.wantsCapture(frameNumber)) {
      const auto captureStart = Clock::now();
      drawer.capture(current, frameNumber, options);
      result.qualitySeconds += secondsSince(captureStart);
    }

    VirtualTextureRuntime::Prediction prediction;
    prediction.hotSpot = hotSpot(previous, current, needViewport, configuration.hotSpot);
    if (configuration.lookAhead != LookAhead::kNone) {
      drawer.draw(lookAheadCamera(beforePrevious, previous, current, configuration.lookAhead),
                  frameIndex, nullptr, lookAheadNeed, nullptr, false);
      prediction.lookAheadNeed = lookAheadNeed;
    }
    FlightFrame frame;
    frame.statistics.streamed = streamedBefore;
    frame.statistics.evicted = evictedBefore;
    // The first frame under asynchronous readback has no needbuffer yet: nothing to ask for.
    const std::vector<StreamRequest> requests =
        need.empty() ? std::vector<StreamRequest>{}
                     : runtime.analyze(need, depth, needViewport.width, needViewport.height,
                                       settings.need8, frameIndex, frame.statistics, prediction);

    std::vector<uint8_t> expected;
    if (options.reference) {
      const auto qualityStart = Clock::now();
      expected = options.reference(frameNumber);
      if (!expected.empty()) {
        const ImageView got{screen.width, screen.height, color},
            want{screen.width, screen.height, expected};
        const SsimAndWssim structure = ssimAndWssim(got, want);
        frame.quality = FrameQuality{rmse(got, want), structure.ssim, structure.wssim};
      }
      result.qualitySeconds += secondsSince(qualityStart);
    }

    // Streaming for the next frame, applied by the management step.
    std::vector<StreamedPage> arrived;
    if (budget) {
      arrived = budget->frame(requests);
    } else {
      thread->request(requests);
      arrived = thread->takeStreamed();
    }
    if (options.observe) {
      const auto observeStart = Clock::now();
      std::vector<uint64_t> streamed;
      for (const StreamedPage& page : arrived) streamed.push_back(page.page);
      options.observe(FlightFrameView{frameNumber, color, need, needViewport, expected, requests,
                                      streamed, runtime, frame});
      result.qualitySeconds += secondsSince(observeStart);
    }
    const auto [applied, evicted] = runtime.apply(std::move(arrived));
    streamedBefore = applied;
    evictedBefore = evicted;

    result.totals.hits += frame.statistics.hits;
    result.totals.misses += frame.statistics.misses;
    result.totals.streamed += frame.statistics.streamed;
    result.totals.evicted += frame.statistics.evicted;
    result.frames.push_back(frame);
  }
  result.seconds = secondsSince(start) - result.qualitySeconds;
  return result;
}

}  // namespace vt
