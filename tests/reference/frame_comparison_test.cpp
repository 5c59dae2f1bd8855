#include "reference/frame_comparison.h"

#include <gtest/gtest.h>

namespace vt::reference {
namespace {

// Eight pixels of page (1, 2) of level 3, colour 100 everywhere.
Frame smallFrame() {
  Frame frame;
  frame.viewport = {4, 2};
  frame.color.assign(8 * 4, 100);
  frame.need.assign(8, glm::uvec4(1, 2, 3, 1));
  frame.triangle.assign(8, 0);
  return frame;
}

// The one-value set of smallFrame's pixels, widened as a test asks.
Alternative pointOf(const Frame& frame) {
  Alternative a;
  a.triangle = 0;
  a.levelLo = a.levelHi = 3;
  a.uvLo = a.uvHi = glm::vec2(1.5f / 8.0f, 2.5f / 8.0f);
  a.colorLo = a.colorHi = a.filterLo = a.filterHi = glm::u8vec4(frame.color[0]);
  return a;
}

ResultSets setsOf(std::vector<std::vector<Alternative>> perPixel) {
  ResultSets sets;
  sets.offsets.push_back(0);
  for (const auto& alternatives : perPixel) {
    sets.alternatives.insert(sets.alternatives.end(), alternatives.begin(), alternatives.end());
    sets.offsets.push_back(static_cast<uint32_t>(sets.alternatives.size()));
  }
  return sets;
}

TEST(FrameComparison, UnderAPinnedModelEveryDifferenceIsUnexplainedAndAttributed) {
  const Frame oracle = smallFrame();
  std::vector<uint8_t> color = oracle.color;
  std::vector<glm::uvec4> need = oracle.need;
  color[0] = 102;                    // pixel 0: colour off by 2
  need[1] = glm::uvec4(1, 2, 4, 1);  // pixel 1: a finer level
  need[2] = glm::uvec4(3, 2, 3, 1);  // pixel 2: two pages to the right
  need[3] = glm::uvec4(0);           // pixel 3: no geometry

  const FrameComparison c = compareFrames(oracle, color, need, false);
  EXPECT_EQ(c.pixels, 8u);
  EXPECT_EQ(c.identical, 4u);
  EXPECT_EQ(c.explained, 0u);
  EXPECT_EQ(c.unexplained, 4u);
  EXPECT_EQ(c.ambiguous, 0u);
  EXPECT_EQ(c.needMismatched, 3u);
  EXPECT_EQ(c.maxColorDifference, 2);
  EXPECT_EQ(c.unexplainedBy[3], 1u);  // lod, by one level
  EXPECT_EQ(c.widenBy[3], 1.0);
  EXPECT_EQ(c.unexplainedBy[2], 1u);  // attributes, by two pages
  EXPECT_EQ(c.widenBy[2], 2.0);
  EXPECT_EQ(c.unexplainedBy[4], 1u);  // filter, by 2 units
  EXPECT_EQ(c.widenBy[4], 2.0);
  EXPECT_EQ(c.unexplainedBy[0], 1u);  // coverage
  ASSERT_EQ(c.unexplainedPixels.size(), 4u);
  EXPECT_EQ(c.unexplainedPixels[1].index, 1u);
  EXPECT_EQ(c.unexplainedPixels[1].reason, 3);
  // Top-down classification image: pixel 1 (row 0, bottom) is red in the image's last row.
  EXPECT_EQ(c.classificationImage[(4 + 1) * 4 + 0], 255);
  EXPECT_EQ(c.classificationImage[(4 + 1) * 4 + 1], 0);
}

TEST(FrameComparison, AnAmbiguousPixelPassesOnlyValuesItsSetHolds) {
  Frame oracle = smallFrame();
  const Alternative point = pointOf(oracle);
  Alternative wideColour = point;  // colour 96..104 reachable
  wideColour.colorLo = glm::u8vec4(96);
  wideColour.colorHi = glm::u8vec4(104);
  wideColour.filterLo = glm::u8vec4(99);
  wideColour.filterHi = glm::u8vec4(101);
  Alternative twoLevels = point;  // level 3 or 4, pages of (s, t) in one page of level 3
  twoLevels.levelHi = 4;
  Alternative neighbour = point;  // another triangle may own the pixel: page (2, 2)
  neighbour.triangle = 7;
  neighbour.reasons = kReasonCoverage;
  neighbour.uvLo = neighbour.uvHi = glm::vec2(2.5f / 8.0f, 2.5f / 8.0f);
  Alternative empty;  // or nothing
  empty.triangle = -1;
  oracle.sets = setsOf({{wideColour},
                        {wideColour},
                        {wideColour},
                        {twoLevels},
                        {twoLevels},
                        {point, neighbour},
                        {point, neighbour},
                        {point, empty}});

  std::vector<uint8_t> color = oracle.color;
  std::vector<glm::uvec4> need = oracle.need;
  color[0 * 4 + 1] = 101;            // within the filter's share: filter
  color[1 * 4 + 1] = 104;            // within the set, beyond the filter's share: attributes
  color[2 * 4 + 1] = 200;            // ambiguous, but 96 units beyond its set: unexplained
  need[3] = glm::uvec4(3, 5, 4, 1);  // level 4 and its page under (s, t): lod
  need[4] = glm::uvec4(1, 2, 5, 1);  // level 5: unexplained, one level beyond
  need[5] = glm::uvec4(2, 2, 3, 1);  // the neighbour's page: coverage
  need[6] = glm::uvec4(4, 2, 3, 1);  // no alternative names page (4, 2)
  need[7] = glm::uvec4(0);           // empty, and the colour cleared
  for (int k = 0; k < 4; ++k) color[7 * 4 + k] = 0;

  const FrameComparison c = compareFrames(oracle, color, need, false);
  EXPECT_EQ(c.identical, 0u);
  EXPECT_EQ(c.ambiguous, 8u);
  EXPECT_EQ(c.explained, 5u);
  EXPECT_EQ(c.unexplained, 3u);
  EXPECT_EQ(c.explainedBy[4], 1u);  // filter
  EXPECT_EQ(c.explainedBy[2], 1u);  // attributes
  EXPECT_EQ(c.explainedBy[3], 1u);  // lod
  EXPECT_EQ(c.explainedBy[0], 2u);  // coverage: the neighbour, and the empty pixel
  EXPECT_EQ(c.unexplainedBy[4], 1u);
  EXPECT_EQ(c.widenBy[4], 96.0);
  EXPECT_EQ(c.unexplainedBy[3], 1u);
  EXPECT_EQ(c.widenBy[3], 1.0);
  EXPECT_EQ(c.unexplainedBy[2], 1u);
  EXPECT_EQ(c.widenBy[2], 2.0);  // two pages beyond (2, 2), the nearest alternative
}

TEST(FrameComparison, RejectsFramesOfDifferentSizes) {
  const Frame oracle = smallFrame();
  const std::vector<uint8_t> color(4);
  const std::vector<glm::uvec4> need(1);
  EXPECT_THROW(compareFrames(oracle, color, need, false), std::invalid_argument);
}

}  // namespace
}  // namespace vt::reference
