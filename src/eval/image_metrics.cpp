#include "eval/image_metrics.h"

#include <algorithm>
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

}  // namespace

std::vector<double> luminance(const ImageView& image) {
  std::vector<double> y(static_cast<size_t>(image.width) * image.height);
  for (size_t i = 0; i < y.size(); ++i)
    y[i] = 0.2126 * image.rgba[4 * i] + 0.7152 * image.rgba[4 * i + 1] +
           0.0722 * image.rgba[4 * i + 2];
  return y;
}

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

namespace {

// Separable window weights, summing to 1: `first` is the offset of the window's first tap from
// its centre pixel.
struct Window {
  std::vector<double> taps;
  int first = 0;
};

Window window(const SsimOptions& options) {
  Window w;
  if (options.window == SsimWindow::kGaussian) {
    constexpr int kRadius = 5;  // 11 taps: scipy's truncate = 3.5 at sigma 1.5
    constexpr double kSigma = 1.5;
    double total = 0.0;
    for (int k = -kRadius; k <= kRadius; ++k)
      total += w.taps.emplace_back(std::exp(-k * k / (2 * kSigma * kSigma)));
    for (double& t : w.taps) t /= total;
    w.first = -kRadius;
  } else {
    if (options.uniformSize < 1) throw std::invalid_argument("SSIM window of no pixels");
    w.taps.assign(static_cast<size_t>(options.uniformSize), 1.0 / options.uniformSize);
    w.first = -(options.uniformSize / 2);
  }
  return w;
}

// Mean of SSIM over the windows, each weighted by weight(centre x, centre y).
template <class Weight>
double meanSsim(const ImageView& a, const ImageView& b, const SsimOptions& options, Weight weight) {
  requireSameSize(a, b);
  constexpr double kC1 = (0.01 * 255) * (0.01 * 255), kC2 = (0.03 * 255) * (0.03 * 255);
  const Window w = window(options);
  const int taps = static_cast<int>(w.taps.size()), W = a.width, H = a.height;
  if (W < taps || H < taps) throw std::invalid_argument("images smaller than the SSIM window");
  const std::vector<double> x = luminance(a), y = luminance(b);
  double sum = 0.0, weights = 0.0;
  for (int cy = -w.first; cy + w.first + taps <= H; ++cy)
    for (int cx = -w.first; cx + w.first + taps <= W; ++cx) {
      double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
      for (int j = 0; j < taps; ++j)
        for (int i = 0; i < taps; ++i) {
          const double k = w.taps[static_cast<size_t>(i)] * w.taps[static_cast<size_t>(j)];
          const size_t p =
              static_cast<size_t>(cy + w.first + j) * W + static_cast<size_t>(cx + w.first + i);
          mx += k * x[p];
          my += k * y[p];
          xx += k * x[p] * x[p];
          yy += k * y[p] * y[p];
          xy += k * x[p] * y[p];
        }
      const double vx = xx - mx * mx, vy = yy - my * my, cxy = xy - mx * my;
      const double q =
          ((2 * mx * my + kC1) * (2 * cxy + kC2)) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
      const double k = weight(cx, cy);
      sum += k * q;
      weights += k;
    }
  return weights > 0.0 ? sum / weights : 1.0;
}

}  // namespace

double ssim(const ImageView& a, const ImageView& b, const SsimOptions& options) {
  return meanSsim(a, b, options, [](int, int) { return 1.0; });
}

double wssim(const ImageView& a, const ImageView& b, const SsimOptions& options) {
  // Pixel centres at +0.5, as the WeightedPixel heuristic weighs pixels.
  const double centreX = 0.5 * a.width, centreY = 0.5 * a.height;
  const double radius = std::hypot(centreX, centreY);
  return meanSsim(a, b, options, [&](int x, int y) {
    const double r = std::hypot(x + 0.5 - centreX, y + 0.5 - centreY);
    return std::max(0.0, 1.0 - r / radius);
  });
}

}  // namespace vt
