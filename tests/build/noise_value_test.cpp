#include "build/noise_value.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace vt {
namespace {

const TextureDescription kGray{.pageSize = 8, .border = 1, .levelCount = 3, .channels = 1};

// A stored page whose texel (i, j) (border included, so i, j in [0, P + 2B)) has `value(i, j)`.
std::vector<std::byte> grayPage(const std::function<int(int, int)>& value) {
  const int side = static_cast<int>(kGray.storedPageSide());
  std::vector<std::byte> page(kGray.pageBytes());
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) page[static_cast<size_t>(j * side + i)] = std::byte(value(i, j));
  return page;
}

TEST(NoiseValue, ChildThatAddsNothingScoresZero) {
  const auto flat = grayPage([](int, int) { return 77; });
  EXPECT_EQ(noiseValue(kGray, PageId{1, 0, 1}, flat, flat), 0.0f);
}

TEST(NoiseValue, UniformDifferenceIsTheRmse) {
  // Luminance 1 against an upsampled parent of luminance 0: every texel differs by 1.
  const auto white = grayPage([](int, int) { return 255; });
  const auto black = grayPage([](int, int) { return 0; });
  EXPECT_FLOAT_EQ(noiseValue(kGray, PageId{0, 1, 1}, white, black), 1.0f);
  // Half of the texels differ by 1: RMSE = sqrt(1/2).
  const auto halfWhite = grayPage([](int, int j) { return j - 1 < 4 ? 255 : 0; });
  EXPECT_FLOAT_EQ(noiseValue(kGray, PageId{0, 1, 1}, halfWhite, black), std::sqrt(0.5f));
}

TEST(NoiseValue, LinearRampUpsamplesExactlyFromTheRightQuarter) {
  // The parent holds a ramp in x; bilinear upsampling of a ramp is exact, so a child that holds
  // the same ramp at twice the resolution, for the quarter it covers, has NoiseValue 0 and one
  // that holds the other quarter's ramp does not. Parent texel i (border included) has value
  // 8 * i, at parent coordinate i - B + 0.5; the child's texel i covers (i - B + 0.5) / 2 + origin.
  const auto parentPage = grayPage([](int i, int) { return 8 * i; });
  const auto childOf = [](double originX) {
    return grayPage([originX](int i, int) {
      const double parentX = originX + (i - 1 + 0.5) / 2.0;  // parent texel coordinate
      return static_cast<int>(std::lround(8.0 * (parentX - 0.5 + 1)));
    });
  };
  EXPECT_NEAR(noiseValue(kGray, PageId{0, 0, 1}, childOf(0.0), parentPage), 0.0f, 1e-6f);
  EXPECT_NEAR(noiseValue(kGray, PageId{1, 0, 1}, childOf(4.0), parentPage), 0.0f, 1e-6f);
  // The left child measured against the right quarter differs by 4 parent texels = 32 / 255.
  EXPECT_NEAR(noiseValue(kGray, PageId{1, 0, 1}, childOf(0.0), parentPage), 32.0f / 255.0f, 1e-6f);
}

TEST(NoiseValue, UsesRec709LuminanceForColor) {
  const TextureDescription rgb{.pageSize = 4, .border = 1, .levelCount = 2, .channels = 3};
  std::vector<std::byte> green(rgb.pageBytes(), std::byte{0}), black(rgb.pageBytes(), std::byte{0});
  for (size_t t = 0; t < green.size(); t += 3) green[t + 1] = std::byte{255};
  EXPECT_FLOAT_EQ(noiseValue(rgb, PageId{0, 0, 1}, green, black), 0.7152f);
}

}  // namespace
}  // namespace vt
