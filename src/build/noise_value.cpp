#include "build/noise_value.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vt {
namespace {

// Luminance of one stored texel, in [0, 1].
float luminance(const TextureDescription& d, std::span<const std::byte> page, size_t texel) {
  return texelLuminance(page.data() + texel * d.channels, d.channels, 255.0f);
}

}  // namespace

float noiseValue(const TextureDescription& d, PageId child, std::span<const std::byte> page,
                 std::span<const std::byte> parentPage) {
  const int P = static_cast<int>(d.pageSize), B = static_cast<int>(d.border);
  const int side = static_cast<int>(d.storedPageSide());
  const int half = std::max(P / 2, 1);
  // The quarter of the parent this child covers starts at parent texel (qx, qy) * P/2.
  const int qx = static_cast<int>(child.x & 1) * P / 2, qy = static_cast<int>(child.y & 1) * P / 2;

  // Luminance of the parent texels bilinear filtering reads: the quarter and one texel around it,
  // indices clamped to the stored page.
  const int window = half + 2;
  std::vector<float> parentY(static_cast<size_t>(window) * window);
  for (int j = 0; j < window; ++j) {
    const int y = std::clamp(qy + j - 1 + B, 0, side - 1);
    for (int i = 0; i < window; ++i) {
      const int x = std::clamp(qx + i - 1 + B, 0, side - 1);
      parentY[static_cast<size_t>(j * window + i)] =
          luminance(d, parentPage, static_cast<size_t>(y) * side + x);
    }
  }
  const auto parentAt = [&](int i, int j) {  // relative to the quarter's first texel
    return parentY[static_cast<size_t>((j + 1) * window + (i + 1))];
  };

  double sumSquares = 0.0;
  for (int j = 0; j < P; ++j) {
    // Child texel centre (j + 0.5) / P of the page is parent texel coordinate (j + 0.5) / 2 of the
    // quarter; bilinear with texel centres at +0.5.
    const float v = (static_cast<float>(j) + 0.5f) * 0.5f - 0.5f;
    const int y0 = static_cast<int>(std::floor(v));
    const float fy = v - static_cast<float>(y0);
    for (int i = 0; i < P; ++i) {
      const float u = (static_cast<float>(i) + 0.5f) * 0.5f - 0.5f;
      const int x0 = static_cast<int>(std::floor(u));
      const float fx = u - static_cast<float>(x0);
      const float top = parentAt(x0, y0) * (1 - fx) + parentAt(x0 + 1, y0) * fx;
      const float bottom = parentAt(x0, y0 + 1) * (1 - fx) + parentAt(x0 + 1, y0 + 1) * fx;
      const float upsampled = top * (1 - fy) + bottom * fy;
      const float difference =
          luminance(d, page, static_cast<size_t>(j + B) * side + (i + B)) - upsampled;
      sumSquares += static_cast<double>(difference) * difference;
    }
  }
  return static_cast<float>(std::sqrt(sumSquares / (static_cast<double>(P) * P)));
}

}  // namespace vt
