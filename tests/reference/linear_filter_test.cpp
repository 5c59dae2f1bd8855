// The GL_LINEAR family's fixed-point members (render/arithmetic.h, reference/linear_filter.h):
// 8-bit weights, and the lerp's product rounded to nearest or floored, checked on values worked
// out by hand.

#include "reference/linear_filter.h"

#include <gtest/gtest.h>

#include <array>

namespace vt::reference {
namespace {

// Channel 0 of a 2 x 1 texture sampled between its texels with 8-bit weight `weight`.
int sampledUnits(std::array<uint8_t, 2> texels, int weight, LerpRounding rounding) {
  const auto fetch8 = [&](shader::ivec2 t) { return glm::u8vec4(texels[t.x], 0, 0, 255); };
  // s = u * (2 * 256) - 128 is the weight on texel 0's side: u = (weight + 128) / 512, exact.
  const float u = static_cast<float>(weight + 128) / 512.0f;
  const Filter filter{.weights = FilterWeights::kFixedPoint8, .lerpRounding = rounding};
  const shader::vec4 c =
      sampleLinearAt(fetch8, shader::vec2(u, 0.25f), shader::ivec2(2, 1), filter);
  return static_cast<int>(std::lround(c.x * 255.0f));
}

TEST(LinearFilter, FixedPointLerpsRoundTheirProductToNearestOrFloorIt) {
  // 10 + 85 * 3 / 256 = 10.996: nearest 11, floored 10.
  EXPECT_EQ(sampledUnits({10, 13}, 85, LerpRounding::kNearest), 11);
  EXPECT_EQ(sampledUnits({10, 13}, 85, LerpRounding::kFloor), 10);
  // 13 - 200 * 3 / 256 = 10.66: nearest 11, floored 10 (a truncation towards zero would give 11).
  EXPECT_EQ(sampledUnits({13, 10}, 200, LerpRounding::kNearest), 11);
  EXPECT_EQ(sampledUnits({13, 10}, 200, LerpRounding::kFloor), 10);
  // On a texel centre both are the texel.
  EXPECT_EQ(sampledUnits({13, 10}, 0, LerpRounding::kFloor), 13);
}

// The corner-weight member (Filter::kFixedPointCorners) with the parameters a GPU was measured
// with: coordinates on 21 bits, positions half up to 1/256 texel, w11 rounded to nearest, a unorm16
// result. A 2 x 2 texture; the red channel's texels are given.
float cornerSample(std::array<uint8_t, 4> red, glm::vec2 u, FilterOutput output,
                   LerpRounding corner = LerpRounding::kNearest) {
  const auto fetch8 = [&](shader::ivec2 t) {
    return glm::u8vec4(red[static_cast<size_t>(t.y * 2 + t.x)], 0, 0, 255);
  };
  const Filter filter{.weights = FilterWeights::kFixedPointCorners,
                      .lerpRounding = corner,
                      .coordinateBits = 21,
                      .weightBits = 8,
                      .positionRounding = PositionRounding::kHalfUp,
                      .output = output};
  return sampleLinearAt(fetch8, shader::vec2(u), shader::ivec2(2, 2), filter).x;
}

TEST(LinearFilter, CornerWeightsOnFixedPointPositionsReturnAUnorm16Value) {
  // u = 0.5 on a side of 2: P = 0.5, q = 128, so fx = fy = 128 and w11 = (128 128 + 128) >> 8 =
  // 16512 >> 8 = 64, w10 = w01 = 64, w00 = 64. Texels 0, 255, 0, 255: S = 64 255 2 = 32640;
  // K = (257 S + 128) >> 8 = 32768; 32768 / 65535, not a whole number of 1/255.
  EXPECT_EQ(cornerSample({0, 255, 0, 255}, {0.5f, 0.5f}, FilterOutput::kUnorm16),
            32768.0f / 65535.0f);
  // Texels 10, 20, 30, 100: S = 64 160 = 10240, K = (2631680 + 128) >> 8 = 10280.
  EXPECT_EQ(cornerSample({10, 20, 30, 100}, {0.5f, 0.5f}, FilterOutput::kUnorm16),
            10280.0f / 65535.0f);
  // As unorm8: (S + 128) >> 8 = 40 (10368 / 256 = 40.5 floored).
  EXPECT_EQ(cornerSample({10, 20, 30, 100}, {0.5f, 0.5f}, FilterOutput::kUnorm8), 40.0f / 255.0f);
  // u = 0.3: U = floor(0.3 2^21) = 629145 (0.3f is 0.300000011920929), P = 629145 / 2^20 - 0.5 =
  // 0.09999942..., q = floor(25.5998... + 0.5) = 26; fx = fy = 26, w11 = (676 + 128) >> 8 = 3
  // (floored: 676 >> 8 = 2). Texels 0, 0, 0, 255: S = 3 255 = 765 (floored 510);
  // K = (257 765 + 128) >> 8 = 768 (196733 / 256 = 768.49), floored K = (131070 + 128) >> 8 = 512.
  EXPECT_EQ(cornerSample({0, 0, 0, 255}, {0.3f, 0.3f}, FilterOutput::kUnorm16), 768.0f / 65535.0f);
  EXPECT_EQ(
      cornerSample({0, 0, 0, 255}, {0.3f, 0.3f}, FilterOutput::kUnorm16, LerpRounding::kFloor),
      512.0f / 65535.0f);
}

TEST(LinearFilter, TheFixedPointPositionTruncatesTheCoordinateThenRounds) {
  const Filter filter{.weights = FilterWeights::kFixedPointCorners};  // 21 bits, 1/256, half up
  // On a side of 16: u = 1/32 is texel position 0, q = 0.
  EXPECT_EQ(fixedPointPosition(1.0f / 32.0f, 16, filter), 0);
  // u = 1/32 + 2^-13: P = 2^-9, q = floor(0.5 + 0.5) = 1 (half up), floored 0.
  EXPECT_EQ(fixedPointPosition(1.0f / 32.0f + 0x1p-13f, 16, filter), 1);
  Filter floored = filter;
  floored.positionRounding = PositionRounding::kFloor;
  EXPECT_EQ(fixedPointPosition(1.0f / 32.0f + 0x1p-13f, 16, floored), 0);
  // u just below 1/32 + 2^-13 by 2^-22 truncates to 2^-21 below it: q = floor(0.5 - 2^-4 + 0.5) =
  // 0.
  EXPECT_EQ(fixedPointPosition(1.0f / 32.0f + 0x1p-13f - 0x1p-22f, 16, filter), 0);
  // Left of the first texel centre: u = 0 is P = -1/2, q = -128 (texel -1, fraction 128).
  EXPECT_EQ(fixedPointPosition(0.0f, 16, filter), -128);
}

}  // namespace
}  // namespace vt::reference
