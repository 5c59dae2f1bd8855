#include "render/frame_comparison.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "shader/needbuffer.h"

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

// A triangle's alternative of levels lo..hi over (s, t) in [uvLo, uvHi], every channel in
// [colour, colour].
Alternative drawn(int lo, int hi, glm::vec2 uvLo, glm::vec2 uvHi, uint8_t colour) {
  Alternative a;
  a.triangle = 0;
  a.levelLo = static_cast<uint8_t>(lo);
  a.levelHi = static_cast<uint8_t>(hi);
  a.uvLo = uvLo;
  a.uvHi = uvHi;
  a.colorLo = a.colorHi = a.filterLo = a.filterHi = glm::u8vec4(colour);
  return a;
}

// The widths worked out by hand, one pixel at a time (SetWidths' definition in
// frame_comparison.h).
TEST(FrameComparison, SetWidthsOfHandBuiltSetsAreExact) {
  // Pixel 0: red in [100, 103], the other channels one value; one page of level 3.
  Alternative single = drawn(3, 3, {0.55f, 0.55f}, {0.56f, 0.56f}, 100);
  single.colorHi.r = 103;
  // Pixel 1: three triangles. Red [10, 20] u [15, 30] = 21 values, green 0 and 5 apart: 2 values;
  // levels {3, 4} u {4, 5} u {3}. Level 3: pages x 0..2 of row 0 (a) and x 2..3 of rows 0..1 (c),
  // 3 + 4 - 1 shared = 6; level 4: x 1..4 of row 1 (a) holds b's (4, 1): 4; level 5: b's (8, 3).
  Alternative a = drawn(3, 4, {0.1f, 0.1f}, {0.3f, 0.1f}, 0);
  a.colorLo.r = 10;
  a.colorHi.r = 20;
  Alternative b = drawn(4, 5, {0.25f, 0.1f}, {0.25f, 0.1f}, 0);
  b.colorLo.r = 15;
  b.colorHi.r = 30;
  b.colorLo.g = b.colorHi.g = 5;
  Alternative c = drawn(3, 3, {0.3f, 0.1f}, {0.4f, 0.2f}, 0);
  c.colorLo.r = c.colorHi.r = 12;  // inside a's reds
  // Pixel 2: only the clear alternative: not covered. Pixel 3: a triangle of colour 50 or the
  // clear values: two values per channel, one level, one page.
  const Alternative empty;
  const ResultSets sets =
      setsOf({{single}, {a, b, c}, {empty}, {drawn(2, 2, {0.3f, 0.3f}, {0.3f, 0.3f}, 50), empty}});

  const SetWidths p0 = pixelSetWidths(sets, 0);
  EXPECT_EQ(p0.covered, 1u);
  EXPECT_EQ(p0.colorWidthSum, 0.75);  // (3 + 0 + 0 + 0) / 4
  EXPECT_EQ(p0.levelSum, 1u);
  EXPECT_EQ(p0.pageSum, 1u);
  const SetWidths p1 = pixelSetWidths(sets, 1);
  EXPECT_EQ(p1.colorWidthSum, 5.25);  // (20 + 1 + 0 + 0) / 4
  EXPECT_EQ(p1.levelSum, 3u);
  EXPECT_EQ(p1.pageSum, 11u);  // 6 + 4 + 1
  EXPECT_EQ(pixelSetWidths(sets, 2).covered, 0u);
  const SetWidths p3 = pixelSetWidths(sets, 3);
  EXPECT_EQ(p3.colorWidthSum, 1.0);
  EXPECT_EQ(p3.pageSum, 1u);

  const SetWidths frame = setWidths(sets, {}, false);
  EXPECT_EQ(frame.covered, 3u);
  EXPECT_DOUBLE_EQ(frame.meanColorWidth(), 7.0 / 3.0);  // (0.75 + 5.25 + 1) / 3 covered pixels
  EXPECT_DOUBLE_EQ(frame.meanLevels(), 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(frame.meanPages(), 13.0 / 3.0);
}

// Under a pinned model (no sets) every pixel the oracle covers admits its one value.
TEST(FrameComparison, SetWidthsOfAPinnedFrameAreZeroWidthOneLevelOnePage) {
  Frame oracle = smallFrame();
  oracle.need[5] = needClearValue(false);
  const SetWidths widths = setWidths(oracle.sets, oracle.need, false);
  EXPECT_EQ(widths.covered, 7u);
  EXPECT_EQ(widths.meanColorWidth(), 0.0);
  EXPECT_EQ(widths.meanLevels(), 1.0);
  EXPECT_EQ(widths.meanPages(), 1.0);
}

TEST(FrameComparison, RejectsFramesOfDifferentSizes) {
  const Frame oracle = smallFrame();
  const std::vector<uint8_t> color(4);
  const std::vector<glm::uvec4> need(1);
  EXPECT_THAT([&] { compareFrames(oracle, color, need, false); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("compareFrames: frames of different sizes")));
}

}  // namespace
}  // namespace vt::reference
