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

}  // namespace
}  // namespace vt::reference
