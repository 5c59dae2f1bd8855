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

// Windowed sums of luminance x and y, their squares and product, for one row of window centres:
// the window is separable, so each image row is first summed across (once), and a centre row
// sums the `taps` rows of those sums below its window's first row.
struct WindowMoments {
  std::vector<double> x, y, xx, yy, xy;
  explicit WindowMoments(size_t n) : x(n), y(n), xx(n), yy(n), xy(n) {}
};

}  // namespace

// The reference's share of the work, in the order meanSsims did it in one pass: its luminance,
// its windows' means and mean squares (a row pass, then a column pass), and WSSIM's weights.
struct PreparedReference::Prepared {
  SsimOptions options;
  Window w;
  int width = 0, height = 0;
  size_t columns = 0, rows = 0;      // window positions across and down
  std::vector<double> y;             // luminance
  std::vector<double> my, yy;        // per window: weighted mean of y and of y^2
  std::vector<double> weight;        // per window: WSSIM's weight
  double weights = 0.0;              // their sum, in window order
};

PreparedReference::PreparedReference(const ImageView& reference, const SsimOptions& options) {
  const auto prepared = std::make_shared<Prepared>();
  prepared_ = prepared;
  Prepared& p = *prepared;
  p.options = options;
  p.w = window(options);
  const int taps = static_cast<int>(p.w.taps.size()), W = reference.width, H = reference.height;
  if (reference.rgba.size() != static_cast<size_t>(W) * static_cast<size_t>(H) * 4)
    throw std::invalid_argument("images differ in size");
  if (W < taps || H < taps) throw std::invalid_argument("images smaller than the SSIM window");
  p.width = W;
  p.height = H;
  p.columns = static_cast<size_t>(W - taps + 1);
  p.rows = static_cast<size_t>(H - taps + 1);
  p.y = luminance(reference);
  // Row sums of y and y^2, every image row.
  std::vector<double> acrossY(p.columns * static_cast<size_t>(H)),
      acrossYY(p.columns * static_cast<size_t>(H));
  for (int row = 0; row < H; ++row) {
    const size_t first = static_cast<size_t>(row) * static_cast<size_t>(W);
    for (size_t c = 0; c < p.columns; ++c) {
      double sy = 0, syy = 0;
      for (int i = 0; i < taps; ++i) {
        const double k = p.w.taps[static_cast<size_t>(i)];
        const double py = p.y[first + c + static_cast<size_t>(i)];
        sy += k * py;
        syy += k * py * py;
      }
      acrossY[static_cast<size_t>(row) * p.columns + c] = sy;
      acrossYY[static_cast<size_t>(row) * p.columns + c] = syy;
    }
  }
  // WSSIM's weight (thesis 4.2.3.1): pixel centres at +0.5, as the WeightedPixel heuristic.
  const double centreX = 0.5 * W, centreY = 0.5 * H, radius = std::hypot(centreX, centreY);
  p.my.resize(p.columns * p.rows);
  p.yy.resize(p.columns * p.rows);
  p.weight.resize(p.columns * p.rows);
  for (size_t top = 0; top < p.rows; ++top) {
    const int cy = static_cast<int>(top) - p.w.first;
    for (size_t c = 0; c < p.columns; ++c) {
      double my = 0, yy = 0;
      for (int j = 0; j < taps; ++j) {
        const double k = p.w.taps[static_cast<size_t>(j)];
        const size_t at = (top + static_cast<size_t>(j)) * p.columns + c;
        my += k * acrossY[at];
        yy += k * acrossYY[at];
      }
      const size_t index = top * p.columns + c;
      p.my[index] = my;
      p.yy[index] = yy;
      const int cx = static_cast<int>(c) - p.w.first;
      const double r = std::hypot(cx + 0.5 - centreX, cy + 0.5 - centreY);
      p.weight[index] = std::max(0.0, 1.0 - r / radius);
      p.weights += p.weight[index];
    }
  }
}

SsimAndWssim PreparedReference::compare(const ImageView& image) const {
  const Prepared& p = *prepared_;
  if (image.width != p.width || image.height != p.height ||
      image.rgba.size() != static_cast<size_t>(p.width) * static_cast<size_t>(p.height) * 4)
    throw std::invalid_argument("images differ in size");
  constexpr double kC1 = (0.01 * 255) * (0.01 * 255), kC2 = (0.03 * 255) * (0.03 * 255);
  const Window& w = p.w;
  const int taps = static_cast<int>(w.taps.size()), W = p.width;
  const std::vector<double> x = luminance(image);
  const std::vector<double>& y = p.y;
  const size_t columns = p.columns;

  // Horizontal sums of the last `taps` image rows, in a ring: row r in slot r mod taps. Each
  // window's sums add their taps in the same order as a loop per window would (first tap first),
  // but the loops run across the windows innermost, where they vectorise.
  std::vector<WindowMoments> across(static_cast<size_t>(taps), WindowMoments(columns));
  const auto sumAcross = [&](int row) {
    WindowMoments& m = across[static_cast<size_t>(row % taps)];
    const size_t first = static_cast<size_t>(row) * static_cast<size_t>(W);
    std::fill(m.x.begin(), m.x.end(), 0.0);
    std::fill(m.xx.begin(), m.xx.end(), 0.0);
    std::fill(m.xy.begin(), m.xy.end(), 0.0);
    for (int i = 0; i < taps; ++i) {
      const double k = w.taps[static_cast<size_t>(i)];
      const double* px = x.data() + first + static_cast<size_t>(i);
      const double* py = y.data() + first + static_cast<size_t>(i);
      for (size_t c = 0; c < columns; ++c) {
        m.x[c] += k * px[c];
        m.xx[c] += k * px[c] * px[c];
        m.xy[c] += k * px[c] * py[c];
      }
    }
  };

  // Per row of windows: the column sums (same order: first tap first), then each window's Q,
  // then the means, summed in window order.
  std::vector<double> mx(columns), xx(columns), xy(columns), q(columns);
  double sum = 0.0, weightedSum = 0.0;
  for (int row = 0; row < taps - 1; ++row) sumAcross(row);
  for (size_t top = 0; top < p.rows; ++top) {
    sumAcross(static_cast<int>(top) + taps - 1);
    std::fill(mx.begin(), mx.end(), 0.0);
    std::fill(xx.begin(), xx.end(), 0.0);
    std::fill(xy.begin(), xy.end(), 0.0);
    for (int j = 0; j < taps; ++j) {
      const double k = w.taps[static_cast<size_t>(j)];
      const WindowMoments& m = across[(top + static_cast<size_t>(j)) % static_cast<size_t>(taps)];
      for (size_t c = 0; c < columns; ++c) {
        mx[c] += k * m.x[c];
        xx[c] += k * m.xx[c];
        xy[c] += k * m.xy[c];
      }
    }
    const double* my = p.my.data() + top * columns;
    const double* yy = p.yy.data() + top * columns;
    for (size_t c = 0; c < columns; ++c) {
      const double vx = xx[c] - mx[c] * mx[c], vy = yy[c] - my[c] * my[c],
                   cxy = xy[c] - mx[c] * my[c];
      q[c] = ((2 * mx[c] * my[c] + kC1) * (2 * cxy + kC2)) /
             ((mx[c] * mx[c] + my[c] * my[c] + kC1) * (vx + vy + kC2));
    }
    const double* weight = p.weight.data() + top * columns;
    for (size_t c = 0; c < columns; ++c) {
      sum += q[c];
      weightedSum += weight[c] * q[c];
    }
  }
  const size_t windows = columns * p.rows;
  return {windows > 0 ? sum / static_cast<double>(windows) : 1.0,
          p.weights > 0.0 ? weightedSum / p.weights : 1.0};
}

namespace {

SsimAndWssim meanSsims(const ImageView& a, const ImageView& b, const SsimOptions& options) {
  requireSameSize(a, b);
  return PreparedReference(b, options).compare(a);
}

}  // namespace

SsimAndWssim ssimAndWssim(const ImageView& a, const ImageView& b, const SsimOptions& options) {
  return meanSsims(a, b, options);
}

double ssim(const ImageView& a, const ImageView& b, const SsimOptions& options) {
  return meanSsims(a, b, options).ssim;
}

double wssim(const ImageView& a, const ImageView& b, const SsimOptions& options) {
  return meanSsims(a, b, options).wssim;
}

}  // namespace vt
