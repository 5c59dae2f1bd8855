#include "format/level_image.h"

#include <cstring>

#include "common/error.h"

namespace vt {

LevelImage assembleLevel(const VirtualTextureReader& reader, uint32_t level) {
  const TextureDescription& d = reader.description();
  if (level >= d.levelCount)
    throw InputError(reader.path(), "level " + std::to_string(level) +
                                        " does not exist (levels 0.." +
                                        std::to_string(d.finestLevel()) + ")");
  const uint64_t side = levelSide(d.pageSize, level);
  if (side > kMaxAssembledSide)
    throw InputError(reader.path(), "level " + std::to_string(level) + " is " +
                                        std::to_string(side) + " texels wide, more than the " +
                                        std::to_string(kMaxAssembledSide) + " an image may have");
  LevelImage image;
  image.side = static_cast<uint32_t>(side);
  image.channels = d.channels;
  image.texels.assign(side * side * d.channels, std::byte{0});

  std::vector<std::byte> page(d.pageBytes());
  const size_t rowBytes = size_t{d.pageSize} * d.channels;
  const size_t storedRowBytes = size_t{d.storedPageSide()} * d.channels;
  for (uint32_t py = 0; py < pagesPerSide(level); ++py) {
    for (uint32_t px = 0; px < pagesPerSide(level); ++px) {
      const PageId id{px, py, level};
      if (!reader.contains(id)) continue;
      reader.readPage(id, page);
      for (uint32_t row = 0; row < d.pageSize; ++row) {
        const std::byte* from =
            page.data() + (row + d.border) * storedRowBytes + size_t{d.border} * d.channels;
        std::byte* to =
            image.texels.data() +
            ((uint64_t{py} * d.pageSize + row) * side + uint64_t{px} * d.pageSize) * d.channels;
        std::memcpy(to, from, rowBytes);
      }
    }
  }
  return image;
}

}  // namespace vt
