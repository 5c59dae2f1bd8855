#pragma once
// SSIM (Wang et al. 2004; thesis appendix A.2) on luminance in [0, 255]: one window's Q, and its
// mean over every uniform window of a grid. The evaluations' image metrics (eval/image_metrics.h)
// and `vt build`'s ancestor errors (build/ancestor_error.h) measure with the same constants and
// windows.

#include <cstdint>
#include <span>

namespace vt {

// One window's Q from its means, variances and covariance (population statistics), with
// C1 = (0.01 L)^2 and C2 = (0.03 L)^2 for L = 255.
inline double windowSsim(double mx, double my, double vx, double vy, double cxy) {
  constexpr double kC1 = (0.01 * 255) * (0.01 * 255), kC2 = (0.03 * 255) * (0.03 * 255);
  return ((2 * mx * my + kC1) * (2 * cxy + kC2)) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
}

// The mean Q over every `window` x `window` uniform window that lies wholly inside two grids of
// `side` x `side` values (rows one after another), from summed-area tables in double precision.
// `window` is clamped to `side`, so a grid smaller than the window is one window.
double meanUniformSsim(std::span<const float> a, std::span<const float> b, uint32_t side,
                       uint32_t window);

}  // namespace vt
