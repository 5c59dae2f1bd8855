// Reduced needbuffers: their viewport and the per-frame jitter that moves their samples across
// the screen's pixels.

#include "runtime/needbuffer_scale.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(NeedbufferScale, ViewportShrinksByPowersOfTwoAndNeverToNothing) {
  EXPECT_EQ(reducedViewport({640, 360}, 0).width, 640);
  EXPECT_EQ(reducedViewport({640, 360}, 2).width, 160);
  EXPECT_EQ(reducedViewport({640, 360}, 2).height, 90);
  EXPECT_EQ(reducedViewport({5, 3}, 3).width, 1);
  EXPECT_EQ(reducedViewport({5, 3}, 3).height, 1);
  EXPECT_EQ(parseNeedScale("4"), 2);
  // The refusal names the value of --need-scale it could not read.
  EXPECT_THAT([] { parseNeedScale("3"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("needbuffer scale '3' is not ")));
}

TEST(NeedbufferScale, JitterVisitsEveryScreenPixelOfAReducedPixel) {
  EXPECT_EQ(needJitter(17, 0), glm::vec2(0.0f));
  for (int k = 1; k <= 3; ++k) {
    const int n = 1 << k;
    // Over 4^k frames the jittered sample lands in each of the n x n screen pixels at least once
    // for k = 1 (Halton points are spread evenly) and in most of them for larger k.
    std::set<std::pair<int, int>> pixels;
    for (uint64_t frame = 0; frame < static_cast<uint64_t>(n * n * 4); ++frame) {
      const glm::vec2 j = needJitter(frame, k);
      ASSERT_GT(j.x, -0.5f);
      ASSERT_LT(j.x, 0.5f);
      ASSERT_GT(j.y, -0.5f);
      ASSERT_LT(j.y, 0.5f);
      pixels.emplace(static_cast<int>((j.x + 0.5f) * n), static_cast<int>((j.y + 0.5f) * n));
    }
    EXPECT_EQ(pixels.size(), static_cast<size_t>(n * n)) << "k " << k;
  }
  EXPECT_NE(needJitter(0, 2), needJitter(1, 2));
}

}  // namespace
}  // namespace vt
