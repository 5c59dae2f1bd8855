#pragma once
// One level of a virtual texture as an ordinary image: the pages' interiors (borders dropped) put
// side by side, rows of increasing t. Pages a sparse texture does not store stay transparent
// black. For viewing and checking levels that fit in memory.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/virtual_texture_reader.h"

namespace vt {

// The largest level side assembleLevel accepts: 16384^2 RGBA8 texels are 1 GiB.
inline constexpr uint64_t kMaxAssembledSide = 16384;

struct LevelImage {
  uint32_t side = 0;      // texels along each side
  uint32_t channels = 0;  // as in the texture
  std::vector<std::byte> texels;
};

// Throws InputError when the level does not exist or is larger than kMaxAssembledSide.
LevelImage assembleLevel(const VirtualTextureReader& reader, uint32_t level);

}  // namespace vt
