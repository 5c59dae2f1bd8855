#include "format/block_decoding.h"

#include <array>
#include <stdexcept>
#include <string>

namespace vt {
namespace {

uint32_t divideRounded(uint32_t numerator, uint32_t denominator) {
  return (2 * numerator + denominator) / (2 * denominator);
}

// RGB565 widened to 8 bits per channel by replicating the top bits.
std::array<uint32_t, 3> widen565(uint32_t c) {
  const uint32_t r = (c >> 11) & 31, g = (c >> 5) & 63, b = c & 31;
  return {(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)};
}

uint32_t loadLittle(const std::byte* p, int bytes) {
  uint32_t value = 0;
  for (int k = bytes - 1; k >= 0; --k) value = (value << 8) | static_cast<uint32_t>(p[k]);
  return value;
}

// The colour block at `block` into the RGB of 16 texels (alpha left alone).
void decodeColour(const std::byte* block, bool fourColoursAlways, std::byte* texels,
                  size_t rowStride) {
  const uint32_t raw0 = loadLittle(block, 2), raw1 = loadLittle(block + 2, 2);
  const std::array<uint32_t, 3> c0 = widen565(raw0), c1 = widen565(raw1);
  std::array<std::array<uint32_t, 3>, 4> palette{c0, c1, {}, {}};
  const bool four = fourColoursAlways || raw0 > raw1;
  for (size_t c = 0; c < 3; ++c) {
    if (four) {
      palette[2][c] = divideRounded(2 * c0[c] + c1[c], 3);
      palette[3][c] = divideRounded(c0[c] + 2 * c1[c], 3);
    } else {
      palette[2][c] = divideRounded(c0[c] + c1[c], 2);
      palette[3][c] = 0;
    }
  }
  const uint32_t indices = loadLittle(block + 4, 4);
  for (size_t t = 0; t < 16; ++t) {
    const std::array<uint32_t, 3>& colour = palette[(indices >> (2 * t)) & 3];
    std::byte* texel = texels + (t / 4) * rowStride + (t % 4) * 4;
    for (size_t c = 0; c < 3; ++c) texel[c] = static_cast<std::byte>(colour[c]);
  }
}

// The BC3 alpha block at `block` into the alpha of 16 texels.
void decodeAlpha(const std::byte* block, std::byte* texels, size_t rowStride) {
  const uint32_t a0 = static_cast<uint32_t>(block[0]), a1 = static_cast<uint32_t>(block[1]);
  std::array<uint32_t, 8> palette{a0, a1};
  if (a0 > a1) {
    for (uint32_t i = 2; i < 8; ++i) palette[i] = divideRounded((8 - i) * a0 + (i - 1) * a1, 7);
  } else {
    for (uint32_t i = 2; i < 6; ++i) palette[i] = divideRounded((6 - i) * a0 + (i - 1) * a1, 5);
    palette[6] = 0;
    palette[7] = 255;
  }
  const uint64_t indices = loadLittle(block + 2, 3) | (uint64_t{loadLittle(block + 5, 3)} << 24);
  for (size_t t = 0; t < 16; ++t)
    texels[(t / 4) * rowStride + (t % 4) * 4 + 3] =
        static_cast<std::byte>(palette[(indices >> (3 * t)) & 7]);
}

}  // namespace

void decodeBlocks(PixelFormat format, uint32_t side, std::span<const std::byte> blocks,
                  std::span<std::byte> rgba) {
  if (!isBlockCompressed(format) || side % 4 != 0)
    throw std::invalid_argument("decodeBlocks: not a block format, or a side of " +
                                std::to_string(side) + " texels");
  const size_t perRow = side / 4, bytes = format == PixelFormat::kBc1 ? 8 : 16;
  const size_t rowStride = size_t{side} * 4;
  if (rgba.size() != rowStride * side || blocks.size() != perRow * perRow * bytes)
    throw std::invalid_argument("decodeBlocks: buffers of " + std::to_string(rgba.size()) +
                                " and " + std::to_string(blocks.size()) + " bytes for a side of " +
                                std::to_string(side));
  for (size_t by = 0; by < perRow; ++by)
    for (size_t bx = 0; bx < perRow; ++bx) {
      const std::byte* block = blocks.data() + (by * perRow + bx) * bytes;
      std::byte* texels = rgba.data() + by * 4 * rowStride + bx * 16;
      if (format == PixelFormat::kBc1) {
        decodeColour(block, false, texels, rowStride);
        for (size_t t = 0; t < 16; ++t)
          texels[(t / 4) * rowStride + (t % 4) * 4 + 3] = std::byte{255};
      } else {
        decodeAlpha(block, texels, rowStride);
        decodeColour(block + 8, true, texels, rowStride);
      }
    }
}

}  // namespace vt
