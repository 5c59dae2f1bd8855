#pragma once
// Needbuffer analysis (thesis 3.2.4.1): one pass over the needbuffer (and, when a heuristic needs
// it, the depth buffer) gathers per needed page what the page priority heuristics of chapter 4.2
// use, and the frame's global cache hits and misses.
//
// Per page: the pixels that need it (PixelSum), their summed depth (Distance: mean = sum / pixels),
// their summed centre weight (WeightedPixel) and their summed hot-spot weight (HotSpot). A pixel's
// weight at distance r from the weighting centre is max(0, 1 - r / R), R the distance from the
// screen centre to a corner: 1 at the centre, 0 at the corners. Rows run bottom to top, as
// rendered. A scene pays only for what it asks: depth and weights are summed only when requested.

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <unordered_map>

#include "format/page_address.h"
#include "shader/needbuffer.h"

namespace vt {

struct PageStatistics {
  uint64_t pixels = 0;
  double depthSum = 0.0;
  double centreWeight = 0.0;
  double hotSpotWeight = 0.0;

  double meanDepth() const { return pixels ? depthSum / static_cast<double>(pixels) : 0.0; }

  // The statistics of both sets of pixels.
  PageStatistics& operator+=(const PageStatistics& other) {
    pixels += other.pixels;
    depthSum += other.depthSum;
    centreWeight += other.centreWeight;
    hotSpotWeight += other.hotSpotWeight;
    return *this;
  }
};

struct AnalysisOptions {
  bool need8 = false;                // the needbuffer's encoding
  bool depth = false;                // sum depths (Distance)
  bool centreWeight = false;         // WeightedPixel
  std::optional<glm::vec2> hotSpot;  // HotSpot: the weighting centre in pixels
};

struct NeedBufferAnalysis {
  std::unordered_map<uint64_t, PageStatistics> pages;  // by absolute index
  uint64_t coveredPixels = 0;
};

// `need` holds width * height values; `depth` (same size) only when options.depth.
NeedBufferAnalysis analyzeNeedBuffer(std::span<const glm::uvec4> need, std::span<const float> depth,
                                     int width, int height, const AnalysisOptions& options);

}  // namespace vt
