#include "eval/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vt {
namespace {

std::vector<uint8_t> constant(int width, int height, uint8_t value) {
  std::vector<uint8_t> rgba(static_cast<size_t>(width) * height * 4, value);
  for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  return rgba;
}

TEST(ImageMetrics, IdenticalImagesHaveNoError) {
  std::vector<uint8_t> noise(32 * 24 * 4);
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<uint8_t>((i * 7919) % 251);
  const ImageView a{32, 24, noise};
  EXPECT_EQ(rmse(a, a), 0.0);
  EXPECT_DOUBLE_EQ(ssim(a, a), 1.0);
}

TEST(ImageMetrics, ConstantImagesHaveTheirClosedFormValues) {
  // RMSE of a uniform difference d is d. For constant images the variances vanish and SSIM is
  // (2 a b + C1) / (a^2 + b^2 + C1), with C1 = (0.01 * 255)^2 (Wang et al. 2004).
  const auto a = constant(20, 20, 100), b = constant(20, 20, 110);
  const ImageView va{20, 20, a}, vb{20, 20, b};
  EXPECT_DOUBLE_EQ(rmse(va, vb), 10.0);
  const double c1 = 2.55 * 2.55;
  // The luminance of gray g is (0.2126 + 0.7152 + 0.0722) g = g, up to rounding of the weights.
  EXPECT_NEAR(ssim(va, vb), (2 * 100.0 * 110.0 + c1) / (100.0 * 100.0 + 110.0 * 110.0 + c1), 1e-12);
}

TEST(ImageMetrics, RejectsMismatchedSizes) {
  const auto a = constant(20, 20, 1), b = constant(20, 21, 1);
  EXPECT_THROW(rmse({20, 20, a}, {20, 21, b}), std::invalid_argument);
  const auto tiny = constant(5, 5, 1);
  EXPECT_THROW(ssim({5, 5, tiny}, {5, 5, tiny}), std::invalid_argument);
}

}  // namespace
}  // namespace vt
