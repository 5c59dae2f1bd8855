#pragma once
// Full-reference quality metrics (thesis appendix A) between two RGBA8 images of equal size.
//
// RMSE: over the R, G and B channels, in 8-bit units (appendix A.1).
// SSIM (Wang et al. 2004, appendix A.2): on Rec. 709 luminance in [0, 255], local means,
// variances and covariance under an 11 x 11 Gaussian window of sigma 1.5 (normalized, population
// statistics), C1 = (0.01 * 255)^2, C2 = (0.03 * 255)^2, averaged over the windows that lie
// wholly inside the image.

#include <cstdint>
#include <span>

namespace vt {

struct ImageView {
  int width = 0, height = 0;
  std::span<const uint8_t> rgba;  // width * height * 4
};

double rmse(const ImageView& a, const ImageView& b);
double ssim(const ImageView& a, const ImageView& b);

}  // namespace vt
