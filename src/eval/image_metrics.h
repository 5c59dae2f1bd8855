#pragma once
// Full-reference quality metrics (thesis appendix A) between two RGBA8 images of equal size.
//
// RMSE: over the R, G and B channels, in 8-bit units (appendix A.1).
// SSIM (Wang et al. 2004, appendix A.2) on Rec. 709 luminance in [0, 255] (L = 255):
//   Q = ((2 mu_x mu_y + C1)(2 sigma_xy + C2)) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 +
//   C2)), C1 = (0.01 L)^2, C2 = (0.03 L)^2, with local means, variances and covariance under a
//   window (population statistics: weights summing to 1), at every position where the window lies
//   wholly inside the image, averaged. Windows: the thesis's 8 x 8 uniform block (the default; an
//   even window's centre is the pixel right and below the middle) or any odd or even uniform size,
//   or the usual 11 x 11 Gaussian of sigma 1.5. With the Gaussian, or a uniform odd size, this is
//   scikit-image's structural_similarity(data_range=255, use_sample_covariance=False) on the
//   same luminance (a test checks it to 1e-4 on rendered frames).
// WSSIM (thesis 4.2.3.1): each window's Q weighted by its centre's distance r from the screen's
//   centre, w = max(0, 1 - r / R), R the distance from the centre to a corner (the WeightedPixel
//   weight of runtime/needbuffer_analysis.h); the weighted mean sum(w Q) / sum(w).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "common/structural_similarity.h"  // windowSsim

namespace vt {

struct ImageView {
  int width = 0, height = 0;
  std::span<const uint8_t> rgba;  // width * height * 4
};

enum class SsimWindow { kUniform, kGaussian };

struct SsimOptions {
  SsimWindow window = SsimWindow::kUniform;
  int uniformSize = 8;  // side of the uniform window, pixels
};

// Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B of one RGBA8 pixel, in [0, 255], as SSIM
// uses it.
inline double luminanceOf(const uint8_t* rgba) {
  return 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2];
}
// Of each pixel.
std::vector<double> luminance(const ImageView& image);


double rmse(const ImageView& a, const ImageView& b);
// Throws std::invalid_argument for images of different sizes or smaller than the window.
double ssim(const ImageView& a, const ImageView& b, const SsimOptions& options = {});
double wssim(const ImageView& a, const ImageView& b, const SsimOptions& options = {});
// Both at the cost of one: the window statistics are computed once, separably (a row pass, then
// a column pass over a ring of `taps` rows), in O(width * height * taps).
struct SsimAndWssim {
  double ssim = 1.0, wssim = 1.0;
};
SsimAndWssim ssimAndWssim(const ImageView& a, const ImageView& b, const SsimOptions& options = {});

// A reference image `b` prepared once for comparing many images `a` with it (an evaluation
// compares every run's frame with the frame's one reference): its luminance, its windows' means
// and mean squares and WSSIM's weights. compare(a) equals ssimAndWssim(a, b) bit for bit.
class PreparedReference {
 public:
  explicit PreparedReference(const ImageView& b, const SsimOptions& options = {});
  SsimAndWssim compare(const ImageView& a) const;  // thread-safe

 private:
  struct Prepared;
  std::shared_ptr<const Prepared> prepared_;
};

}  // namespace vt
