#include "eval/image_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// SSIM and WSSIM by their definition: every window summed in two dimensions, tap by tap.
struct Definition {
  double ssim, wssim;
};

// SSIM's Q of one window from its weighted means and mean squares (the constants and the order of
// operations of image_metrics.cpp), and the means of Q over the windows in window order: plain,
// and weighted by WSSIM's weight (falling from the image's centre; pixel centres at +0.5).
class WindowAverages {
 public:
  WindowAverages(const ImageView& image, int taps)
      : first_(-(taps / 2)),
        centreX_(0.5 * image.width),
        centreY_(0.5 * image.height),
        radius_(std::hypot(centreX_, centreY_)) {}

  void add(int left, int top, double mx, double my, double xx, double yy, double xy) {
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    const double vx = xx - mx * mx, vy = yy - my * my, cxy = xy - mx * my;
    const double q =
        ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
    const double r = std::hypot(left - first_ + 0.5 - centreX_, top - first_ + 0.5 - centreY_);
    const double w = std::max(0.0, 1.0 - r / radius_);
    sum_ += q;
    count_ += 1;
    weighted_ += w * q;
    weights_ += w;
  }

  Definition result() const { return {sum_ / count_, weighted_ / weights_}; }

 private:
  int first_;
  double centreX_, centreY_, radius_;
  double sum_ = 0, count_ = 0, weighted_ = 0, weights_ = 0;
};
Definition byDefinition(const ImageView& a, const ImageView& b, const std::vector<double>& taps) {
  const std::vector<double> x = luminance(a), y = luminance(b);
  const int n = static_cast<int>(taps.size());
  WindowAverages averages(a, n);
  for (int top = 0; top + n <= a.height; ++top)
    for (int left = 0; left + n <= a.width; ++left) {
      double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double k = taps[static_cast<size_t>(i)] * taps[static_cast<size_t>(j)];
          const size_t p = static_cast<size_t>(top + j) * static_cast<size_t>(a.width) +
                           static_cast<size_t>(left + i);
          mx += k * x[p];
          my += k * y[p];
          xx += k * x[p] * x[p];
          yy += k * y[p] * y[p];
          xy += k * x[p] * y[p];
        }
      averages.add(left, top, mx, my, xx, yy, xy);
    }
  return averages.result();
}

TEST(ImageMetrics, SeparableWindowsAgreeWithTheDefinition) {
  // Two unlike images with detail at every scale; the one-pass separable computation against
  // the two-dimensional sums, for the thesis's 8 x 8 block and the 11 x 11 Gaussian. They differ
  // only by the order of the additions: within 1e-12 relative (a few hundred ulps of terms that
  // reach 255^2).
  const int width = 61, height = 37;
  std::vector<uint8_t> first(static_cast<size_t>(width) * height * 4),
      second(first.size());
  uint32_t state = 12345;
  for (size_t i = 0; i < first.size(); ++i) {
    state = state * 1664525u + 1013904223u;
    first[i] = static_cast<uint8_t>((i * 37 / 4) % 256);
    second[i] = static_cast<uint8_t>(first[i] / 2 + (state >> 25));
  }
  const ImageView a{width, height, first}, b{width, height, second};
  std::vector<double> gaussian;
  double total = 0;
  for (int k = -5; k <= 5; ++k) total += gaussian.emplace_back(std::exp(-k * k / (2 * 1.5 * 1.5)));
  for (double& t : gaussian) t /= total;
  const std::vector<double> block(8, 1.0 / 8);
  for (const auto& [options, taps] :
       {std::pair{SsimOptions{}, block},
        std::pair{SsimOptions{.window = SsimWindow::kGaussian}, gaussian}}) {
    const Definition expected = byDefinition(a, b, taps);
    const SsimAndWssim both = ssimAndWssim(a, b, options);
    EXPECT_LT(expected.ssim, 0.9);
    EXPECT_NEAR(both.ssim, expected.ssim, 1e-12);
    EXPECT_NEAR(both.wssim, expected.wssim, 1e-12);
    EXPECT_NE(both.ssim, both.wssim);
    EXPECT_EQ(ssim(a, b, options), both.ssim);
    EXPECT_EQ(wssim(a, b, options), both.wssim);
  }
}

// One reference prepared once serves several images (the runs of an evaluation): each comparison
// gives the bits of comparing afresh, SSIM and WSSIM.
TEST(ImageMetrics, APreparedReferenceComparesLikeAFreshOne) {
  const int width = 45, height = 29;
  std::vector<uint8_t> reference(static_cast<size_t>(width) * height * 4);
  for (size_t i = 0; i < reference.size(); ++i)
    reference[i] = static_cast<uint8_t>((i * 53 / 3) % 256);
  const ImageView want{width, height, reference};
  const PreparedReference prepared(want);
  for (const int shift : {1, 17, 90}) {
    std::vector<uint8_t> image = reference;
    for (size_t i = 0; i < image.size(); i += 3) image[i] = static_cast<uint8_t>(image[i] + shift);
    const ImageView got{width, height, image};
    const SsimAndWssim fresh = ssimAndWssim(got, want), reused = prepared.compare(got);
    EXPECT_LT(fresh.ssim, 1.0);
    EXPECT_EQ(reused.ssim, fresh.ssim);
    EXPECT_EQ(reused.wssim, fresh.wssim);
  }
  const std::vector<uint8_t> small(16 * 16 * 4, 0);
  EXPECT_THROW(prepared.compare(ImageView{16, 16, small}), std::invalid_argument);
}

// SSIM and WSSIM with each window's sums in the separable order (across each row of the window,
// tap by tap, then down those sums), every window computed: what compare() must give bit for bit
// although it computes only the windows that see a difference.
Definition inSeparableOrder(const ImageView& a, const ImageView& b,
                            const std::vector<double>& taps) {
  const std::vector<double> x = luminance(a), y = luminance(b);
  const int n = static_cast<int>(taps.size());
  WindowAverages averages(a, n);
  for (int top = 0; top + n <= a.height; ++top)
    for (int left = 0; left + n <= a.width; ++left) {
      double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
      for (int j = 0; j < n; ++j) {
        double rx = 0, ry = 0, rxx = 0, ryy = 0, rxy = 0;
        for (int i = 0; i < n; ++i) {
          const double k = taps[static_cast<size_t>(i)];
          const size_t p = static_cast<size_t>(top + j) * static_cast<size_t>(a.width) +
                           static_cast<size_t>(left + i);
          rx += k * x[p];
          ry += k * y[p];
          rxx += k * x[p] * x[p];
          ryy += k * y[p] * y[p];
          rxy += k * x[p] * y[p];
        }
        const double k = taps[static_cast<size_t>(j)];
        mx += k * rx;
        my += k * ry;
        xx += k * rxx;
        yy += k * ryy;
        xy += k * rxy;
      }
      averages.add(left, top, mx, my, xx, yy, xy);
    }
  return averages.result();
}

// Frames of an evaluation mostly equal their reference but in patches: compare() skips the
// windows without a difference (their SSIM is 1 exactly) and must still give every bit of the
// full computation, whether the patches sit in the middle, at the edges or are single pixels.
TEST(ImageMetrics, WindowsWithoutADifferenceChangeNoBit) {
  const int width = 53, height = 41;
  std::vector<uint8_t> reference(static_cast<size_t>(width) * height * 4);
  for (size_t i = 0; i < reference.size(); ++i)
    reference[i] = static_cast<uint8_t>((i * 53 / 3 + i * i % 7) % 256);
  const ImageView want{width, height, reference};
  struct Patch {
    int x, y, w, h;
  };
  const std::vector<std::vector<Patch>> layouts = {
      {{20, 15, 6, 4}},
      {{0, 0, 3, 2}, {width - 2, height - 1, 2, 1}},
      {{30, 0, 1, 1}, {0, 30, 1, 1}, {12, 20, 1, 1}},
      {{0, 10, width, 1}},
      {{7, 0, 2, height}}};
  std::vector<double> gaussian;
  double total = 0;
  for (int k = -5; k <= 5; ++k) total += gaussian.emplace_back(std::exp(-k * k / (2 * 1.5 * 1.5)));
  for (double& t : gaussian) t /= total;
  for (const auto& [options, taps] :
       {std::pair{SsimOptions{}, std::vector<double>(8, 1.0 / 8)},
        std::pair{SsimOptions{.window = SsimWindow::kGaussian}, gaussian}}) {
    const PreparedReference prepared(want, options);
    for (const std::vector<Patch>& patches : layouts) {
      std::vector<uint8_t> image = reference;
      for (const Patch& patch : patches)
        for (int y = patch.y; y < patch.y + patch.h; ++y)
          for (int x = patch.x; x < patch.x + patch.w; ++x)
            image[(static_cast<size_t>(y) * width + static_cast<size_t>(x)) * 4 + 1] ^= 0x5a;
      const ImageView got{width, height, image};
      const Definition expected = inSeparableOrder(got, want, taps);
      const SsimAndWssim measured = prepared.compare(got);
      EXPECT_LT(measured.ssim, 1.0);
      EXPECT_EQ(measured.ssim, expected.ssim);
      EXPECT_EQ(measured.wssim, expected.wssim);
    }
    EXPECT_EQ(prepared.compare(want).ssim, 1.0);
    EXPECT_EQ(prepared.compare(want).wssim, 1.0);
  }
}

TEST(ImageMetrics, RejectsMismatchedSizes) {
  const auto a = constant(20, 20, 1), b = constant(20, 21, 1);
  EXPECT_THROW(rmse({20, 20, a}, {20, 21, b}), std::invalid_argument);
  const auto tiny = constant(5, 5, 1);
  EXPECT_THROW(ssim({5, 5, tiny}, {5, 5, tiny}), std::invalid_argument);
}

}  // namespace
}  // namespace vt
