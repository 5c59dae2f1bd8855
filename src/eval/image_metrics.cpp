#include "eval/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
  for (size_t i = 0; i < y.size(); ++i) y[i] = luminanceOf(image.rgba.data() + 4 * i);
  return y;
}

double rmse(const ImageView& a, const ImageView& b) {
  requireSameSize(a, b);
  // Squared differences of 8-bit values are integers: summed exactly in 64 bits (2^64 / 255^2 is
  // far beyond any image), in any order, hence fast and the same as a sum in doubles.
  uint64_t sum = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const int d = static_cast<int>(a.rgba[i + c]) - static_cast<int>(b.rgba[i + c]);
      sum += static_cast<uint64_t>(d * d);
    }
  const double count = static_cast<double>(a.width) * a.height * 3;
  return count > 0 ? std::sqrt(static_cast<double>(sum) / count) : 0.0;
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

// A run of columns [first, last); empty when first >= last.
struct Span {
  size_t first = SIZE_MAX, last = 0;
  bool empty() const { return first >= last; }
  void add(Span other) {
    first = std::min(first, other.first);
    last = std::max(last, other.last);
  }
};

// The windows of each row of windows whose support holds a pixel where the luminances differ,
// as one span of window columns per row (it may include windows without one), and the columns
// of each image row's sums across that those windows read. A window whose support has equal
// luminances in both images has SSIM 1 exactly: its two means, two variances and covariance
// are computed by the same operations in the same order from the same values, so each factor of
// Q's numerator equals its factor in the denominator bit for bit ((2 mx) my = mx mx + my my,
// 2 cxy = vx + vy), and neither is zero (C1, C2 > 0).
struct DifferingWindows {
  std::vector<Span> windows;  // per row of windows
  std::vector<Span> across;   // per image row
};

DifferingWindows differingWindows(const std::vector<double>& x, const std::vector<double>& y,
                                  int width, int height, int taps) {
  const size_t columns = static_cast<size_t>(width - taps + 1),
               rows = static_cast<size_t>(height - taps + 1), t = static_cast<size_t>(taps);
  std::vector<Span> differ(static_cast<size_t>(height));  // per image row: differing pixels
  for (size_t row = 0; row < differ.size(); ++row) {
    const double* a = x.data() + row * static_cast<size_t>(width);
    const double* b = y.data() + row * static_cast<size_t>(width);
    size_t first = 0, last = static_cast<size_t>(width);
    while (first < last && a[first] == b[first]) ++first;
    while (last > first && a[last - 1] == b[last - 1]) --last;
    if (first < last) differ[row] = {first, last};
  }
  DifferingWindows d{std::vector<Span>(rows), std::vector<Span>(static_cast<size_t>(height))};
  for (size_t top = 0; top < rows; ++top) {
    Span pixels;
    for (size_t j = 0; j < t; ++j) pixels.add(differ[top + j]);
    if (pixels.empty()) continue;
    // Windows c .. c + taps - 1 that reach a differing column.
    const Span windows{pixels.first >= t - 1 ? pixels.first - (t - 1) : 0,
                       std::min(columns, pixels.last)};
    d.windows[top] = windows;
    for (size_t j = 0; j < t; ++j) d.across[top + j].add(windows);
  }
  return d;
}

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
  const Window& w = p.w;
  const int taps = static_cast<int>(w.taps.size()), W = p.width;
  const std::vector<double> x = luminance(image);
  const std::vector<double>& y = p.y;
  const size_t columns = p.columns;

  // Horizontal sums of the last `taps` image rows, in a ring: row r in slot r mod taps. Each
  // window's sums add their taps in the same order as a loop per window would (first tap first),
  // but the loops run across the windows innermost, where they vectorise.
  std::vector<WindowMoments> across(static_cast<size_t>(taps), WindowMoments(columns));
  // Only the windows that see a difference are computed (differingWindows: the others are 1).
  const DifferingWindows differing = differingWindows(x, y, W, p.height, taps);
  const auto sumAcross = [&](int row) {
    const Span span = differing.across[static_cast<size_t>(row)];
    if (span.empty()) return;
    WindowMoments& m = across[static_cast<size_t>(row % taps)];
    const size_t first = static_cast<size_t>(row) * static_cast<size_t>(W);
    std::fill(m.x.begin() + span.first, m.x.begin() + span.last, 0.0);
    std::fill(m.xx.begin() + span.first, m.xx.begin() + span.last, 0.0);
    std::fill(m.xy.begin() + span.first, m.xy.begin() + span.last, 0.0);
    for (int i = 0; i < taps; ++i) {
      const double k = w.taps[static_cast<size_t>(i)];
      const double* px = x.data() + first + static_cast<size_t>(i);
      const double* py = y.data() + first + static_cast<size_t>(i);
      for (size_t c = span.first; c < span.last; ++c) {
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
    const Span span = differing.windows[top];
    std::fill(q.begin(), q.end(), 1.0);
    std::fill(mx.begin(), mx.end(), 0.0);
    std::fill(xx.begin(), xx.end(), 0.0);
    std::fill(xy.begin(), xy.end(), 0.0);
    for (int j = 0; j < taps && !span.empty(); ++j) {
      const double k = w.taps[static_cast<size_t>(j)];
      const WindowMoments& m = across[(top + static_cast<size_t>(j)) % static_cast<size_t>(taps)];
      for (size_t c = span.first; c < span.last; ++c) {
        mx[c] += k * m.x[c];
        xx[c] += k * m.xx[c];
        xy[c] += k * m.xy[c];
      }
    }
    const double* my = p.my.data() + top * columns;
    const double* yy = p.yy.data() + top * columns;
    for (size_t c = span.first; c < span.last; ++c) {
      const double vx = xx[c] - mx[c] * mx[c], vy = yy[c] - my[c] * my[c],
                   cxy = xy[c] - mx[c] * my[c];
      q[c] = windowSsim(mx[c], my[c], vx, vy, cxy);
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
