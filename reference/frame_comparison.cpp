#include "reference/frame_comparison.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>

namespace vt::reference {

int colorBound(PrecisionProfile profile) { return profile == PrecisionProfile::kLlvmpipe ? 0 : 4; }

FrameComparison compareFrames(const Frame& oracle, std::span<const uint8_t> color,
                              std::span<const glm::uvec4> need, PrecisionProfile profile) {
  const size_t pixels = oracle.need.size();
  if (color.size() != pixels * 4 || need.size() != pixels)
    throw std::invalid_argument("compareFrames: frames of different sizes");
  FrameComparison result;
  result.pixels = pixels;
  result.colorDifferenceImage.assign(pixels * 4, 255);
  result.classificationImage.assign(pixels * 4, 255);
  const int bound = colorBound(profile);
  const int width = oracle.viewport.width, height = oracle.viewport.height;
  uint64_t differenceSum = 0;
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      const size_t i =
          static_cast<size_t>(py) * static_cast<size_t>(width) + static_cast<size_t>(px);
      const size_t out = (static_cast<size_t>(height - 1 - py) * static_cast<size_t>(width) +
                          static_cast<size_t>(px)) *
                         4;
      int largest = 0;
      for (size_t c = 0; c < 4; ++c) {
        const int difference = std::abs(int{color[i * 4 + c]} - int{oracle.color[i * 4 + c]});
        largest = std::max(largest, difference);
        differenceSum += static_cast<uint64_t>(difference);
        if (c < 3)
          result.colorDifferenceImage[out + c] =
              static_cast<uint8_t>(std::min(255, difference * 16));
      }
      result.maxColorDifference = std::max(result.maxColorDifference, largest);
      const bool needSame = need[i] == oracle.need[i];
      std::array<uint8_t, 3> shade{0, 0, 0};
      if (needSame && largest == 0) {
        ++result.identical;
      } else if (oracle.ambiguity[i] != 0) {
        ++result.flagged;
        shade = {255, 220, 0};
      } else if (needSame && largest <= bound) {
        ++result.withinBound;
        shade = {0, 200, 0};
      } else {
        ++result.mismatched;
        result.needMismatched += !needSame;
        if (result.mismatchedPixels.size() < kListedMismatches)
          result.mismatchedPixels.push_back(i);
        shade = {255, 0, 0};
      }
      for (size_t c = 0; c < 3; ++c) result.classificationImage[out + c] = shade[c];
    }
  result.meanColorDifference =
      pixels ? static_cast<double>(differenceSum) / static_cast<double>(pixels * 4) : 0.0;
  return result;
}

}  // namespace vt::reference
