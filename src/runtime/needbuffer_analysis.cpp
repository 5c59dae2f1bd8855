#include "runtime/needbuffer_analysis.h"

#include <cmath>
#include <stdexcept>

namespace vt {

NeedBufferAnalysis analyzeNeedBuffer(std::span<const glm::uvec4> need, std::span<const float> depth,
                                     int width, int height, const AnalysisOptions& options) {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (need.size() != pixels || (options.depth && depth.size() != pixels))
    throw std::invalid_argument("analyzeNeedBuffer: buffers do not match the size");
  const bool weights = options.centreWeight || options.hotSpot.has_value();
  const glm::vec2 centre(static_cast<float>(width) * 0.5f, static_cast<float>(height) * 0.5f);
  const float radius = glm::length(centre);
  const auto weightAround = [&](glm::vec2 at, glm::vec2 pixel) {
    return std::max(0.0f, 1.0f - glm::length(pixel - at) / radius);
  };

  NeedBufferAnalysis analysis;
  // Neighbouring pixels mostly need the same page: accumulate a run, then touch the map once.
  glm::uvec4 runValue(0);
  PageStatistics run;
  const auto flush = [&] {
    if (run.pixels == 0) return;
    if (const auto page = decodeNeed(runValue, options.need8)) {
      analysis.pages[absoluteIndex(*page)] += run;
      analysis.coveredPixels += run.pixels;
    }
    run = PageStatistics{};
  };
  for (size_t i = 0; i < pixels; ++i) {
    if (need[i] != runValue) {
      flush();
      runValue = need[i];
    }
    ++run.pixels;
    if (options.depth) run.depthSum += depth[i];
    if (weights) {
      const glm::vec2 pixel(static_cast<float>(i % static_cast<size_t>(width)) + 0.5f,
                            static_cast<float>(i / static_cast<size_t>(width)) + 0.5f);
      if (options.centreWeight) run.centreWeight += weightAround(centre, pixel);
      if (options.hotSpot) run.hotSpotWeight += weightAround(*options.hotSpot, pixel);
    }
  }
  flush();
  return analysis;
}

}  // namespace vt
