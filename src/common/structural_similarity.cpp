#include "common/structural_similarity.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace vt {

double meanUniformSsim(std::span<const float> a, std::span<const float> b, uint32_t side,
                       uint32_t window) {
  const size_t n = size_t{side};
  if (side == 0 || a.size() != n * n || b.size() != n * n)
    throw std::invalid_argument("meanUniformSsim: grids of " + std::to_string(a.size()) + " and " +
                                std::to_string(b.size()) + " values for side " +
                                std::to_string(side));
  const size_t w = std::clamp<size_t>(window, 1, n);
  // Summed-area tables of x, y, x^2, y^2 and x y, one row and column of zeros first.
  const size_t stride = n + 1;
  std::vector<double> sums(5 * stride * stride, 0.0);
  const auto at = [&](size_t k, size_t x, size_t y) -> double& {
    return sums[(k * stride + y) * stride + x];
  };
  for (size_t y = 0; y < n; ++y)
    for (size_t x = 0; x < n; ++x) {
      const double u = a[y * n + x], v = b[y * n + x];
      const double values[5] = {u, v, u * u, v * v, u * v};
      for (size_t k = 0; k < 5; ++k)
        at(k, x + 1, y + 1) = values[k] + at(k, x, y + 1) + at(k, x + 1, y) - at(k, x, y);
    }
  const double area = static_cast<double>(w * w);
  double total = 0.0;
  for (size_t y = 0; y + w <= n; ++y)
    for (size_t x = 0; x + w <= n; ++x) {
      double m[5];
      for (size_t k = 0; k < 5; ++k)
        m[k] = (at(k, x + w, y + w) - at(k, x, y + w) - at(k, x + w, y) + at(k, x, y)) / area;
      total += windowSsim(m[0], m[1], m[2] - m[0] * m[0], m[3] - m[1] * m[1], m[4] - m[0] * m[1]);
    }
  const size_t windows = (n - w + 1) * (n - w + 1);
  return total / static_cast<double>(windows);
}

}  // namespace vt
