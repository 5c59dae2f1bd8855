#include "build/noise_value.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vt {
namespace {

// Luminance of every texel of a stored page, in [0, 1].
std::vector<float> luminance(const TextureDescription& d, std::span<const std::byte> page) {
  const uint32_t side = d.storedPageSide();
  std::vector<float> y(size_t{side} * side);
  for (size_t i = 0; i < y.size(); ++i) {
    const std::byte* t = page.data() + i * d.channels;
    const auto c = [&](int k) { return std::to_integer<int>(t[k]) / 255.0f; };
    y[i] = d.channels >= 3 ? 0.2126f * c(0) + 0.7152f * c(1) + 0.0722f * c(2) : c(0);
  }
  return y;
}

}  // namespace

float noiseValue(const TextureDescription& d, PageId child, std::span<const std::byte> page,
                 std::span<const std::byte> parentPage) {
  const std::vector<float> childY = luminance(d, page);
  const std::vector<float> parentY = luminance(d, parentPage);
  const int P = static_cast<int>(d.pageSize), B = static_cast<int>(d.border);
  const int side = static_cast<int>(d.storedPageSide());
  // The quarter of the parent this child covers starts at parent texel (qx, qy) * P/2.
  const float originX = static_cast<float>((child.x & 1) * P) * 0.5f;
  const float originY = static_cast<float>((child.y & 1) * P) * 0.5f;
  const auto parentAt = [&](int x, int y) {
    x = std::clamp(x + B, 0, side - 1);
    y = std::clamp(y + B, 0, side - 1);
    return parentY[static_cast<size_t>(y) * side + x];
  };

  double sumSquares = 0.0;
  for (int j = 0; j < P; ++j) {
    for (int i = 0; i < P; ++i) {
      // Child texel centre (i + 0.5) / P of the page is parent texel coordinate
      // origin + (i + 0.5) / 2; bilinear with texel centres at +0.5.
      const float u = originX + (static_cast<float>(i) + 0.5f) * 0.5f - 0.5f;
      const float v = originY + (static_cast<float>(j) + 0.5f) * 0.5f - 0.5f;
      const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
      const float fx = u - static_cast<float>(x0), fy = v - static_cast<float>(y0);
      const float top = parentAt(x0, y0) * (1 - fx) + parentAt(x0 + 1, y0) * fx;
      const float bottom = parentAt(x0, y0 + 1) * (1 - fx) + parentAt(x0 + 1, y0 + 1) * fx;
      const float upsampled = top * (1 - fy) + bottom * fy;
      const float difference = childY[static_cast<size_t>(j + B) * side + (i + B)] - upsampled;
      sumSquares += static_cast<double>(difference) * difference;
    }
  }
  return static_cast<float>(std::sqrt(sumSquares / (static_cast<double>(P) * P)));
}

}  // namespace vt
