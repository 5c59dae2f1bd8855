#include "reference/frame_comparison.h"

#include <gtest/gtest.h>

namespace vt::reference {
namespace {

Frame smallFrame() {
  Frame frame;
  frame.viewport = {4, 2};
  frame.color.assign(8 * 4, 100);
  frame.need.assign(8, glm::uvec4(1, 2, 3, 1));
  frame.ambiguity.assign(8, 0);
  return frame;
}

TEST(FrameComparison, ClassifiesEveryPixel) {
  const Frame oracle = smallFrame();
  std::vector<uint8_t> color = oracle.color;
  std::vector<glm::uvec4> need = oracle.need;
  color[0] = 102;                    // pixel 0: colour off by 2
  need[1] = glm::uvec4(1, 2, 4, 1);  // pixel 1: another page
  color[2 * 4 + 1] = 200;            // pixel 2: colour off by 100
  Frame flagged = oracle;
  flagged.ambiguity[2] = kPageBoundary;  // ... but the oracle flagged pixel 2

  const FrameComparison exact = compareFrames(oracle, color, need, PrecisionProfile::kExact);
  EXPECT_EQ(exact.pixels, 8u);
  EXPECT_EQ(exact.identical, 5u);
  EXPECT_EQ(exact.withinBound, 1u);  // 2 <= 4
  EXPECT_EQ(exact.mismatched, 2u);   // the page, and the unflagged 100
  EXPECT_EQ(exact.needMismatched, 1u);
  EXPECT_EQ(exact.maxColorDifference, 100);

  const FrameComparison withFlag = compareFrames(flagged, color, need, PrecisionProfile::kExact);
  EXPECT_EQ(withFlag.flagged, 1u);
  EXPECT_EQ(withFlag.mismatched, 1u);

  // llvmpipe has no colour bound: a difference of 2 is a mismatch.
  const FrameComparison llvmpipe = compareFrames(oracle, color, need, PrecisionProfile::kLlvmpipe);
  EXPECT_EQ(llvmpipe.withinBound, 0u);
  EXPECT_EQ(llvmpipe.mismatched, 3u);
  // Top-down classification image: pixel 1 (row 0, bottom) is red in the image's last row.
  EXPECT_EQ(llvmpipe.classificationImage[(4 + 1) * 4 + 0], 255);
  EXPECT_EQ(llvmpipe.classificationImage[(4 + 1) * 4 + 1], 0);
}

TEST(FrameComparison, RejectsFramesOfDifferentSizes) {
  const Frame oracle = smallFrame();
  const std::vector<uint8_t> color(4);
  const std::vector<glm::uvec4> need(1);
  EXPECT_THROW(compareFrames(oracle, color, need, PrecisionProfile::kExact), std::invalid_argument);
}

}  // namespace
}  // namespace vt::reference
