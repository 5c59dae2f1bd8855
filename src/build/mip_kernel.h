#pragma once
// The mip filter: how a texel of level m - 1 is made from texels of level m (layout.h, MipFilter).
//
// Level m - 1 texel (X, Y) is centred on the corner shared by level m texels (2X, 2Y) and
// (2X + 1, 2Y + 1). The box filter averages those 2x2 texels; the tent filter weighs the 4x4
// texels 2X-1 .. 2X+2 by [1 3 3 1] / 8 per axis. Texel indices outside the level are clamped to
// its edge, as at the texture's edge everywhere in this project.
//
// Colour handling: with sRGB textures the colour channels are decoded to linear light, filtered,
// and encoded again (rounded to the nearest 8-bit code); alpha, and every channel of linear
// textures, is filtered on its stored value with integer arithmetic, rounding half up. Each result
// depends only on the source texels, never on thread count or evaluation order.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "build/layout.h"

namespace vt {

class MipKernel {
 public:
  MipKernel(MipFilter filter, ColorSpace colorSpace, uint32_t channels);

  // Level m rows on each side of 2Y that the filter reads: 0 for box, 1 for tent.
  uint32_t reach() const { return filter_ == MipFilter::kTent ? 1 : 0; }

  // One texel of level m - 1 at column X; `row(k)` gives the level m row 2Y - reach + k (already
  // clamped to the level), k in [0, 2 + 2 reach); `side` is the level m side.
  void texel(const std::function<const uint8_t*(uint32_t)>& row, uint64_t x, uint64_t side,
             uint8_t* out) const;

  // A whole row of level m - 1 (side / 2 texels) from the same rows.
  void downsampleRow(const std::array<const uint8_t*, 4>& rows, uint64_t side, uint8_t* out) const;

 private:
  template <int Taps>
  void filterTexel(const std::array<const uint8_t*, 4>& rows, uint64_t x, uint64_t side,
                   uint8_t* out) const;

  MipFilter filter_;
  uint32_t channels_;
  uint32_t colorChannels_;  // channels filtered in linear light (0 for linear textures)
  std::array<float, 256> decode_{};           // sRGB code -> linear
  std::array<float, 255> encodeThreshold_{};  // linear value where code k turns into k + 1
};

}  // namespace vt
