#include "build/block_encoding.h"

#include <squish.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

namespace vt {
namespace {

size_t blockBytes(PixelFormat format) { return format == PixelFormat::kBc1 ? 8 : 16; }

int squishFlags(PixelFormat format) {
  return (format == PixelFormat::kBc1 ? squish::kDxt1 : squish::kDxt5) | squish::kColourRangeFit;
}

void checkSizes(PixelFormat format, uint32_t side, size_t rgbaBytes, size_t blocksBytes) {
  if (!isBlockCompressed(format) || side % 4 != 0)
    throw std::invalid_argument("block compression: not a block format, or a side of " +
                                std::to_string(side) + " texels");
  const size_t blocks = size_t{side / 4} * (side / 4);
  if (rgbaBytes != size_t{side} * side * 4 || blocksBytes != blocks * blockBytes(format))
    throw std::invalid_argument("block compression: buffers of " + std::to_string(rgbaBytes) +
                                " and " + std::to_string(blocksBytes) + " bytes for a side of " +
                                std::to_string(side));
}

}  // namespace

void encodeBlocks(PixelFormat format, uint32_t side, std::span<const std::byte> rgba,
                  std::span<std::byte> blocks) {
  checkSizes(format, side, rgba.size(), blocks.size());
  const size_t perRow = side / 4, bytes = blockBytes(format);
  std::array<uint8_t, 64> texels;
  for (size_t by = 0; by < perRow; ++by)
    for (size_t bx = 0; bx < perRow; ++bx) {
      for (size_t row = 0; row < 4; ++row)
        std::memcpy(texels.data() + row * 16, rgba.data() + ((by * 4 + row) * side + bx * 4) * 4,
                    16);
      if (format == PixelFormat::kBc1)
        for (size_t k = 3; k < texels.size(); k += 4) texels[k] = 255;
      squish::Compress(texels.data(), blocks.data() + (by * perRow + bx) * bytes,
                       squishFlags(format));
    }
}

}  // namespace vt
