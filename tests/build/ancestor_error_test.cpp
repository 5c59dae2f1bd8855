// Ancestor errors (build/ancestor_error.h): the evaluations' SSIM on the evaluations' windows, and
// each page resampled from the right place of every ancestor.

#include "build/ancestor_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "common/structural_similarity.h"
#include "eval/image_metrics.h"

namespace vt {
namespace {

// Grey RGBA8 images (R = G = B, so their luminance is the value) and the same values as grids:
// the build's mean over 8 x 8 windows is the evaluations' SSIM of the images.
TEST(AncestorError, MeanUniformSsimIsTheEvaluationsSsim) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> value(0, 255);
  for (const uint32_t side : {8u, 13u, 24u}) {
    std::vector<float> a(size_t{side} * side), b(a.size());
    std::vector<uint8_t> rgbaA(4 * a.size()), rgbaB(4 * a.size());
    for (size_t k = 0; k < a.size(); ++k) {
      const int u = value(random), v = std::clamp(u + value(random) / 4 - 32, 0, 255);
      a[k] = static_cast<float>(u);
      b[k] = static_cast<float>(v);
      for (int c = 0; c < 3; ++c) {
        rgbaA[4 * k + c] = static_cast<uint8_t>(u);
        rgbaB[4 * k + c] = static_cast<uint8_t>(v);
      }
    }
    const ImageView imageA{static_cast<int>(side), static_cast<int>(side), rgbaA};
    const ImageView imageB{static_cast<int>(side), static_cast<int>(side), rgbaB};
    EXPECT_NEAR(meanUniformSsim(a, b, side, 8), ssim(imageA, imageB), 1e-9) << side;
    EXPECT_DOUBLE_EQ(meanUniformSsim(a, a, side, 8), 1.0);
  }
  // A grid smaller than the window is one window.
  const std::vector<float> small = {10, 20, 30, 40}, other = {40, 30, 20, 10};
  EXPECT_LT(meanUniformSsim(small, other, 2, 8), 0.0);  // anticorrelated
}

// The luminance of a stored page of a linear function of texture coordinates (no rounding).
// Bilinear filtering reproduces a linear function, so every page resampled from the right place
// of any ancestor shows it exactly; a neighbour's ancestor does not.
TEST(AncestorError, LinearFunctionsResampleExactlyFromTheRightPlaceOfEveryAncestor) {
  const TextureDescription d{.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4};
  const auto linear = [&](PageId page) {
    const uint32_t side = d.storedPageSide();
    const double texels = static_cast<double>(levelSide(d.pageSize, page.level));
    std::vector<float> y(size_t{side} * side);
    for (uint32_t j = 0; j < side; ++j)
      for (uint32_t i = 0; i < side; ++i) {
        const double s = (static_cast<double>(page.x) * d.pageSize - d.border + i + 0.5) / texels;
        const double t = (static_cast<double>(page.y) * d.pageSize - d.border + j + 0.5) / texels;
        y[size_t{j} * side + i] = static_cast<float>(40.0 + 150.0 * s + 60.0 * t);
      }
    return y;
  };
  for (uint32_t level = 1; level < d.levelCount; ++level)
    for (uint32_t y = 0; y < (1u << level); ++y)
      for (uint32_t x = 0; x < (1u << level); ++x) {
        const PageId page{x, y, level};
        for (uint32_t l = 0; l < level; ++l) {
          SCOPED_TRACE(testing::Message() << "page " << x << ", " << y << " on " << level
                                          << " through level " << l);
          EXPECT_LT(ancestorError(d, page, linear(page), l, linear(ancestorAt(page, l))), 1e-6f);
          if (l > 0) {  // the ancestor's neighbour along s, wrapped
            PageId wrong = ancestorAt(page, l);
            wrong.x = (wrong.x + 1) % (1u << l);
            EXPECT_GT(ancestorError(d, page, linear(page), l, linear(wrong)), 1e-3f);
          }
        }
      }
}

TEST(AncestorError, FlatPagesAndPagesSmallerThanTheWindow) {
  const TextureDescription d{.pageSize = 4, .border = 0, .levelCount = 3, .channels = 1};
  const std::vector<std::byte> flat(d.pageBytes(), std::byte{90});
  const std::vector<float> y = pageLuminance(d, flat);
  EXPECT_EQ(y, std::vector<float>(16, 90.0f));
  EXPECT_EQ(ancestorError(d, PageId{3, 1, 2}, y, 0, y), 0.0f);
  std::vector<std::byte> striped(d.pageBytes());
  for (size_t k = 0; k < striped.size(); ++k) striped[k] = std::byte((k % 2) ? 255 : 0);
  const float error = ancestorError(d, PageId{3, 1, 2}, pageLuminance(d, striped), 1, y);
  EXPECT_GT(error, 0.5f);
  EXPECT_LE(error, 2.0f);
  EXPECT_THROW(ancestorError(d, PageId{3, 1, 2}, y, 2, y), std::invalid_argument);
}

}  // namespace
}  // namespace vt
