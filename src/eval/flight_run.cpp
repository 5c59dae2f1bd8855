#include "eval/flight_run.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "common/elapsed_time.h"
#include "runtime/needbuffer_scale.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

using Clock = std::chrono::steady_clock;

RuntimeOptions runtimeOptions(const VirtualTextureReader& reader,
                              const FlightConfiguration& configuration) {
  RuntimeOptions options;
  options.framesX = options.framesY = cacheFramesFor(configuration, reader.description());
  options.lockedLevels = configuration.lockedLevels;
  options.priority.heuristic = configuration.heuristic;
  options.priority.ancestors = configuration.ancestors;
  options.priority.noiseValueSkipping = configuration.noiseSkipping;
  options.trilinearParents = configuration.trilinearParents;
  options.lookAheadPrefetch = configuration.lookAheadPrefetch;
  options.lookAheadWeight = configuration.lookAheadWeight;
  options.lodBiasBacklog = configuration.lodBiasBacklog;
  options.randomSeed = configuration.seed;
  double meanNoise = 0.0;
  for (const float n : reader.noiseValues()) meanNoise += n;
  meanNoise /= static_cast<double>(std::max<size_t>(1, reader.noiseValues().size()));
  options.priority.noiseThreshold = configuration.noiseThreshold >= 0.0f
                                        ? configuration.noiseThreshold
                                        : static_cast<float>(meanNoise);
  return options;
}

}  // namespace

std::vector<uint64_t> initialPages(const VirtualTextureReader& reader,
                                   const FlightConfiguration& c,
                                   std::span<const glm::uvec4> firstNeed, bool need8) {
  std::vector<uint64_t> pages;
  const uint32_t levels = std::min(c.initialLevels, reader.description().levelCount);
  for (uint64_t p = 0; levels > 0 && p < pageCount(levels - 1); ++p) pages.push_back(p);
  if (c.preloadVisible) {
    const std::vector<uint64_t> visible = neededPages(firstNeed, need8).pages;
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

FlightRun::FlightRun(const VirtualTextureReader& reader, const FlightConfiguration& configuration,
                     const FlightOptions& options, Viewport needViewport,
                     std::span<const uint64_t> initialPages)
    : configuration_(configuration),
      options_(options),
      needViewport_(needViewport) {
  if (configuration.selection != PageSelection::kHeuristic && !options.drawsNextView)
    throw std::invalid_argument("configuration '" + configuration.label() +
                                "': selection ceiling picks pages with the next frame's view, "
                                "which only vt eval draws");
  RuntimeOptions settings = runtimeOptions(reader, configuration);
  settings.keepAnalysis = options.keepAnalysis;
  // The cache's texels decoded as the oracle's arithmetic decodes: its frames need no second
  // decoding (the GL path uploads the blocks and decodes them itself).
  settings.decoding = options.settings.arithmetic.blockDecoding;
  runtime_ = std::make_unique<VirtualTextureRuntime>(reader, settings);
  runtime_->preload(std::vector<uint64_t>(initialPages.begin(), initialPages.end()));
  // Deterministic budget mode for evaluations, or a thread over a link in real time.
  if (options.threadedStreaming)
    streamer_ = std::make_unique<ThreadedStreamer>(reader, options.link);
  else
    streamer_ = std::make_unique<BudgetStreamer>(
        reader, FrameBudget{configuration.budget, configuration.budgetBytes},
        configuration.latency);
}

FlightRun::~FlightRun() = default;

void FlightRun::frame(int frameNumber, const Camera& previous, const Camera& current,
                      const DrawnFrame& drawn, double drawSeconds) {
  FlightTimes& times = result_.times;
  times.draw += drawSeconds;
  const RenderSettings& settings = options_.settings;
  const auto frameIndex = static_cast<uint64_t>(frameNumber);

  // Analysis: the needbuffer, with the configuration's prediction of the next views.
  const auto analysisStart = Clock::now();
  const Viewport needViewport = drawn.needViewport.width > 0 ? drawn.needViewport : needViewport_;
  VirtualTextureRuntime::Prediction prediction;
  prediction.hotSpot = hotSpot(previous, current, needViewport, configuration_.hotSpot);
  if (configuration_.lookAhead != LookAhead::kNone) prediction.lookAheadNeed = drawn.lookAheadNeed;
  FlightFrame frame;
  frame.statistics.streamed = streamedBefore_;
  frame.statistics.evicted = evictedBefore_;
  // The first frame under asynchronous readback has no needbuffer yet: nothing to ask for.
  std::vector<StreamRequest> requests =
      drawn.need.empty()
          ? std::vector<StreamRequest>{}
          : runtime_->analyze(drawn.need, drawn.depth, needViewport.width, needViewport.height,
                              settings.need8, frameIndex, frame.statistics, prediction);
  if (drawn.select) requests = drawn.select(requests, *runtime_);
  times.analysis += secondsSince(analysisStart);

  if (!drawn.reference.empty()) {
    const auto metricsStart = Clock::now();
    const Viewport screen = settings.viewport;
    const ImageView got{screen.width, screen.height, drawn.color},
        want{screen.width, screen.height, drawn.reference};
    const SsimAndWssim structure = drawn.preparedReference
                                       ? drawn.preparedReference->compare(got)
                                       : PreparedReference(want).compare(got);
    frame.quality = FrameQuality{rmse(got, want), structure.ssim, structure.wssim};
    times.metrics += secondsSince(metricsStart);
  }

  // Streaming for the next frame, applied by the management step.
  const auto streamingStart = Clock::now();
  std::vector<StreamedPage> arrived = streamer_->exchange(requests);
  double streamingSeconds = secondsSince(streamingStart);
  if (options_.observe) {
    const auto observeStart = Clock::now();
    std::vector<uint64_t> streamed;
    for (const StreamedPage& page : arrived) streamed.push_back(page.page);
    options_.observe(FlightFrameView{frameNumber, drawn.color, drawn.need, needViewport,
                                     drawn.reference, requests, streamed, *runtime_, frame});
    times.other += secondsSince(observeStart);
  }
  const auto applyStart = Clock::now();
  const auto [applied, evicted] = runtime_->apply(std::move(arrived));
  streamingSeconds += secondsSince(applyStart);
  times.streaming += streamingSeconds;
  streamedBefore_ = applied;
  evictedBefore_ = evicted;

  result_.totals.hits += frame.statistics.hits;
  result_.totals.misses += frame.statistics.misses;
  result_.totals.streamed += frame.statistics.streamed;
  result_.totals.evicted += frame.statistics.evicted;
  result_.frames.push_back(frame);
}

FlightResult FlightRun::finish() {
  const FlightTimes& t = result_.times;
  result_.seconds = t.draw + t.analysis + t.streaming;
  result_.qualitySeconds = t.reference + t.metrics + t.other;
  return std::move(result_);
}

}  // namespace vt
