#include "build/synthetic_texture.h"

#include <algorithm>
#include <array>

#include "build/ancestor_error.h"
#include "build/block_encoding.h"
#include "build/noise_value.h"
#include "common/level_hues.h"
#include "format/virtual_texture_writer.h"

namespace vt {
namespace {

std::array<uint8_t, 4> texel(const TextureDescription& d, uint32_t level, int64_t x, int64_t y) {
  const int64_t side = static_cast<int64_t>(levelSide(d.pageSize, level));
  // Clamp at the texture's edge: the border of an edge page repeats the edge texels.
  const uint64_t cx = static_cast<uint64_t>(std::clamp<int64_t>(x, 0, side - 1));
  const uint64_t cy = static_cast<uint64_t>(std::clamp<int64_t>(y, 0, side - 1));
  if (cx % d.pageSize == 0 || cy % d.pageSize == 0) return {255, 255, 255, 255};
  const uint64_t square = std::max<uint32_t>(d.pageSize / 8, 1);
  const uint32_t shade = ((cx / square + cy / square) & 1) ? 256 : 160;
  const auto& hue = levelHue(level);
  // Gradient: 3/4 of the hue at s = 0 rising to all of it at s = 1 (t for green).
  const uint64_t rampS = 192 + (64 * cx) / static_cast<uint64_t>(side);
  const uint64_t rampT = 192 + (64 * cy) / static_cast<uint64_t>(side);
  const auto channel = [&](uint32_t h, uint64_t ramp) {
    return static_cast<uint8_t>(std::min<uint64_t>(255, (h * shade / 256) * ramp / 256));
  };
  return {channel(hue[0], rampS), channel(hue[1], rampT), channel(hue[2], 256), 255};
}

bool intersectsDisc(PageId page, double radius) {
  const double size = 1.0 / static_cast<double>(pagesPerSide(page.level));
  const double x0 = page.x * size, y0 = page.y * size;
  const double nearestX = std::clamp(0.5, x0, x0 + size);
  const double nearestY = std::clamp(0.5, y0, y0 + size);
  const double dx = nearestX - 0.5, dy = nearestY - 0.5;
  return dx * dx + dy * dy <= radius * radius;
}

}  // namespace

std::vector<std::byte> syntheticPage(const TextureDescription& d, PageId page) {
  const uint32_t side = d.storedPageSide();
  std::vector<std::byte> texels(d.pageBytes());
  const int64_t originX = int64_t{page.x} * d.pageSize - d.border;
  const int64_t originY = int64_t{page.y} * d.pageSize - d.border;
  for (uint32_t j = 0; j < side; ++j) {
    for (uint32_t i = 0; i < side; ++i) {
      const auto rgba = texel(d, page.level, originX + i, originY + j);
      std::byte* out = texels.data() + (size_t{j} * side + i) * d.channels;
      for (uint32_t c = 0; c < d.channels; ++c) out[c] = std::byte(rgba[c]);
    }
  }
  return texels;
}

std::vector<uint64_t> syntheticStoredPages(const SyntheticTexture& texture) {
  std::vector<uint64_t> pages;
  const uint64_t total = texture.description.totalPages();
  for (uint64_t p = 0; p < total; ++p)
    if (!texture.discRadius || intersectsDisc(fromAbsoluteIndex(p), *texture.discRadius))
      pages.push_back(p);
  return pages;
}

void writeSyntheticTexture(const std::filesystem::path& path, const SyntheticTexture& texture) {
  const TextureDescription& d = texture.description;
  const std::vector<uint64_t> pages = syntheticStoredPages(texture);
  VirtualTextureWriter writer =
      texture.discRadius ? VirtualTextureWriter(path, d, pages, BlockEncoder(encodeBlocks))
                         : VirtualTextureWriter(path, d, BlockEncoder(encodeBlocks));
  for (const uint64_t p : pages) {
    const PageId page = fromAbsoluteIndex(p);
    const std::vector<std::byte> texels = syntheticPage(d, page);
    // The root has no parent to improve on: its NoiseValue is 0.
    const float noise =
        page.level == 0 ? 0.0f : noiseValue(d, page, texels, syntheticPage(d, parent(page)));
    writer.writePage(page, texels, noise);
  }
  if (texture.ancestorErrors) writer.setAncestorErrors(ancestorErrorsOfWrittenPages(writer));
  writer.commit();
}

}  // namespace vt
