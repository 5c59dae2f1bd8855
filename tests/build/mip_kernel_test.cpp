#include "build/mip_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vt {
namespace {

// Filters one texel of level m - 1 from a 4x4 neighbourhood given row by row (for the box filter
// only rows 1..2 and columns 1..2 of the 4x4 matter: the texel is at X = 1 of a 4-texel row).
std::vector<uint8_t> filter(MipFilter f, ColorSpace space, uint32_t channels,
                            const std::vector<std::vector<uint8_t>>& rows4) {
  const MipKernel kernel(f, space, channels);
  std::vector<uint8_t> out(channels);
  const uint32_t first = f == MipFilter::kBox ? 1 : 0;
  MipKernel::Rows rows{};
  for (uint32_t k = 0; k < 2 + 2 * kernel.reach(); ++k) rows[k] = rows4[first + k].data();
  kernel.texel(rows, 1, 4, out.data());
  return out;
}

double srgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}
double linearToSrgb(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

TEST(MipKernel, LinearBoxAveragesRoundingHalfUp) {
  // Texel X = 1 averages columns 2 and 3 of rows 2 and 3 (rows4[1], rows4[2] here are 2Y, 2Y+1).
  const std::vector<std::vector<uint8_t>> rows = {
      {0, 0, 0, 0}, {0, 0, 10, 20}, {0, 0, 30, 41}, {0, 0, 0, 0}};
  EXPECT_EQ(filter(MipFilter::kBox, ColorSpace::kLinear, 1, rows)[0], 25);  // 101 / 4 = 25.25
  const std::vector<std::vector<uint8_t>> tie = {
      {0, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 0}};
  EXPECT_EQ(filter(MipFilter::kBox, ColorSpace::kLinear, 1, tie)[0], 1);  // 0.5 rounds up
}

TEST(MipKernel, LinearTentWeighsOneThreeThreeOne) {
  // Columns 1..4 of the 4 rows around X = 1 (clamped: column 4 is column 3 of a 4-wide level).
  // One bright texel at (2, 1): weight 3 (column) * 3 (row) / 64 of 255 = 35.86 -> 36.
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(4, 0));
  rows[1][2] = 255;
  EXPECT_EQ(filter(MipFilter::kTent, ColorSpace::kLinear, 1, rows)[0], 36);
  // A corner texel (1, 0) has weight 1 * 1: 255 / 64 = 3.98 -> 4.
  std::vector<std::vector<uint8_t>> corner(4, std::vector<uint8_t>(4, 0));
  corner[0][1] = 255;
  EXPECT_EQ(filter(MipFilter::kTent, ColorSpace::kLinear, 1, corner)[0], 4);
}

TEST(MipKernel, SrgbFiltersInLinearLightAndKeepsAlphaLinear) {
  // Two black and two white texels, RGBA: colour is encode(0.5) = 187.5 + ... -> 188; the
  // alpha channel 0/255 averages linearly to 128.
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(16, 0));
  for (int c = 0; c < 4; ++c) {
    rows[1][2 * 4 + c] = 255;
    rows[2][3 * 4 + c] = 255;
  }
  const auto out = filter(MipFilter::kBox, ColorSpace::kSrgb, 4, rows);
  const int expected = static_cast<int>(std::lround(255.0 * linearToSrgb(0.5)));
  EXPECT_EQ(expected, 188);
  EXPECT_EQ(out[0], expected);
  EXPECT_EQ(out[1], expected);
  EXPECT_EQ(out[2], expected);
  EXPECT_EQ(out[3], 128);
}

TEST(MipKernel, SrgbMatchesDoublePrecisionReference) {
  // Random 2x2 quads against the transfer functions in double: equal but for values within float
  // rounding of a code boundary, and never more than one code apart.
  std::mt19937 random(7);
  int exact = 0, total = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(4, 0));
    double sum = 0.0;
    for (int j = 1; j <= 2; ++j)
      for (int i = 2; i <= 3; ++i) {
        rows[static_cast<size_t>(j)][static_cast<size_t>(i)] = static_cast<uint8_t>(random() % 256);
        sum += srgbToLinear(rows[static_cast<size_t>(j)][static_cast<size_t>(i)] / 255.0);
      }
    const int reference = static_cast<int>(std::lround(255.0 * linearToSrgb(sum / 4.0)));
    const int got = filter(MipFilter::kBox, ColorSpace::kSrgb, 1, rows)[0];
    ASSERT_LE(std::abs(got - reference), 1) << trial;
    exact += got == reference;
    ++total;
  }
  EXPECT_GE(exact, total - total / 1000);
}

}  // namespace
}  // namespace vt
