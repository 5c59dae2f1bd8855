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

#include "build/layout.h"

namespace vt {

class MipKernel {
 public:
  MipKernel(MipFilter filter, ColorSpace colorSpace, uint32_t channels);

  // Level m rows on each side of 2Y that the filter reads: 0 for box, 1 for tent.
  uint32_t reach() const { return filter_ == MipFilter::kTent ? 1 : 0; }

  // Texels [begin, begin + count) of a row Y of level m - 1, written to out[0 .. count * channels).
  // rows[k] is the level m row 2Y - reach + k, already clamped to the level, k in
  // [0, 2 + 2 reach), from column `firstColumn` on: rows[k][(x - firstColumn) * channels] is
  // column x. It must hold the columns the texels read, 2X - reach .. 2X + 1 + reach clamped to
  // the level; `side` is the level m side.
  using Rows = std::array<const uint8_t*, 4>;
  void downsample(const Rows& rows, uint64_t side, uint64_t begin, uint64_t count, uint8_t* out,
                  uint64_t firstColumn = 0) const;
  // The single texel X of that row, written to out[0 .. channels).
  void texel(const Rows& rows, uint64_t x, uint64_t side, uint8_t* out,
             uint64_t firstColumn = 0) const;

 private:
  template <int Taps>
  void filterTexel(const Rows& rows, uint64_t x, uint64_t side, uint64_t firstColumn,
                   uint8_t* out) const;
  uint8_t encode(float linear) const;

  MipFilter filter_;
  uint32_t channels_;
  uint32_t colorChannels_;           // channels filtered in linear light (0 for linear textures)
  std::array<float, 256> decode_{};  // sRGB code -> linear
  std::array<float, 255> encodeThreshold_{};  // linear value where code k turns into k + 1
  std::array<uint8_t, 4097> encodeStart_{};   // codes whose threshold is <= i / 4096
};

}  // namespace vt
