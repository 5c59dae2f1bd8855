#include "eval/image_metrics.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace vt {
namespace {

void requireSameSize(const ImageView& a, const ImageView& b) {
  if (a.width != b.width || a.height != b.height ||
      a.rgba.size() != static_cast<size_t>(a.width) * a.height * 4 ||
      b.rgba.size() != a.rgba.size())
    throw std::invalid_argument("images differ in size");
}

std::vector<double> luminance(const ImageView& image) {
  std::vector<double> y(static_cast<size_t>(image.width) * image.height);
  for (size_t i = 0; i < y.size(); ++i)
    y[i] = 0.2126 * image.rgba[4 * i] + 0.7152 * image.rgba[4 * i + 1] +
           0.0722 * image.rgba[4 * i + 2];
  return y;
}

}  // namespace

double rmse(const ImageView& a, const ImageView& b) {
  requireSameSize(a, b);
  double sum = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = static_cast<double>(a.rgba[i]) - b.rgba[i];
    sum += d * d;
  }
  const double count = static_cast<double>(a.width) * a.height * 3;
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

double ssim(const ImageView& a, const ImageView& b) {
  requireSameSize(a, b);
  constexpr int kRadius = 5;
  constexpr double kSigma = 1.5, kC1 = (0.01 * 255) * (0.01 * 255),
                   kC2 = (0.03 * 255) * (0.03 * 255);
  std::array<double, 2 * kRadius + 1> weight{};
  double total = 0.0;
  for (int k = -kRadius; k <= kRadius; ++k)
    total += weight[k + kRadius] = std::exp(-k * k / (2 * kSigma * kSigma));
  for (double& w : weight) w /= total;
  const std::vector<double> x = luminance(a), y = luminance(b);
  const int W = a.width, H = a.height;
  if (W < 2 * kRadius + 1 || H < 2 * kRadius + 1)
    throw std::invalid_argument("images smaller than the SSIM window");
  double sum = 0.0;
  long windows = 0;
  for (int cy = kRadius; cy < H - kRadius; ++cy)
    for (int cx = kRadius; cx < W - kRadius; ++cx) {
      double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
      for (int j = -kRadius; j <= kRadius; ++j)
        for (int i = -kRadius; i <= kRadius; ++i) {
          const double w = weight[i + kRadius] * weight[j + kRadius];
          const size_t p = static_cast<size_t>(cy + j) * W + static_cast<size_t>(cx + i);
          mx += w * x[p];
          my += w * y[p];
          xx += w * x[p] * x[p];
          yy += w * y[p] * y[p];
          xy += w * x[p] * y[p];
        }
      const double vx = xx - mx * mx, vy = yy - my * my, cxy = xy - mx * my;
      sum +=
          ((2 * mx * my + kC1) * (2 * cxy + kC2)) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
      ++windows;
    }
  return sum / static_cast<double>(windows);
}

}  // namespace vt
