#include "vt/oracle/compare.h"

#include <algorithm>

#include "reference/api/api_internal.h"
#include "render/frame_comparison.h"

namespace vt::oracle {

std::string reasonName(int reason) { return vt::reasonName(reason); }
std::string widthUnit(int reason) { return vt::widthUnit(reason); }

Comparison compare(const Frame& oracle, std::span<const uint8_t> color,
                   std::span<const uint32_t> need) {
  return translatingErrors([&] {
    const size_t pixels =
        static_cast<size_t>(oracle.viewport.width) * static_cast<size_t>(oracle.viewport.height);
    if (oracle.need.size() != pixels * 4 || oracle.color.size() != pixels * 4 ||
        oracle.ambiguous.size() != pixels)
      throw Error("compare: the oracle frame's images do not match its viewport");
    if (color.size() != pixels * 4 || need.size() != pixels * 4)
      throw Error("compare: the frame has " + std::to_string(color.size() / 4) + " colour and " +
                  std::to_string(need.size() / 4) + " needbuffer pixels, the oracle's " +
                  std::to_string(pixels));
    vt::Frame expected;
    expected.viewport = {oracle.viewport.width, oracle.viewport.height};
    expected.color = oracle.color;
    // Not copied into `expected`: tens of megabytes a frame under a bounded model.
    const vt::ResultSets& sets = internalSets(oracle);
    if (!sets.empty() && sets.offsets.size() != pixels + 1)
      throw Error("compare: the oracle frame's result sets do not match its viewport");
    std::vector<glm::uvec4> actualNeed(pixels);
    expected.need.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
      expected.need[i] = glm::uvec4(oracle.need[i * 4], oracle.need[i * 4 + 1],
                                    oracle.need[i * 4 + 2], oracle.need[i * 4 + 3]);
      actualNeed[i] = glm::uvec4(need[i * 4], need[i * 4 + 1], need[i * 4 + 2], need[i * 4 + 3]);
    }
    vt::FrameComparison c = vt::compareFrames(
        expected, sets, color, actualNeed, oracle.needEncoding == NeedEncoding::k8Bit);
    Comparison result;
    result.pixels = c.pixels;
    result.identical = c.identical;
    result.explained = c.explained;
    result.unexplained = c.unexplained;
    result.ambiguous = c.ambiguous;
    result.explainedBy = c.explainedBy;
    result.unexplainedBy = c.unexplainedBy;
    result.widenBy = c.widenBy;
    result.model = oracle.model;
    result.judged = oracle.judged;
    result.needMismatched = c.needMismatched;
    result.maxColorDifference = c.maxColorDifference;
    result.meanColorDifference = c.meanColorDifference;
    result.colorDifferenceImage = std::move(c.colorDifferenceImage);
    result.classificationImage = std::move(c.classificationImage);
    const auto width = static_cast<size_t>(oracle.viewport.width);
    for (const vt::UnexplainedPixel& u : c.unexplainedPixels) {
      const uint64_t i = u.index;
      PixelDifference d;
      d.reason = u.reason;
      d.widenBy = u.widenBy;
      d.x = static_cast<int>(i % width);
      d.y = static_cast<int>(i / width);
      std::copy_n(oracle.need.begin() + static_cast<std::ptrdiff_t>(i * 4), 4, d.expectedNeed);
      std::copy_n(need.begin() + static_cast<std::ptrdiff_t>(i * 4), 4, d.actualNeed);
      std::copy_n(oracle.color.begin() + static_cast<std::ptrdiff_t>(i * 4), 4, d.expectedColor);
      std::copy_n(color.begin() + static_cast<std::ptrdiff_t>(i * 4), 4, d.actualColor);
      result.mismatches.push_back(d);
    }
    return result;
  });
}

}  // namespace vt::oracle
