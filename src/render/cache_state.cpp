#include "render/cache_state.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/resource_limits.h"

namespace vt {

glm::u8vec4 expandToRgba(const std::byte* t, uint32_t channels) {
  const auto c = [&](uint32_t k) { return std::to_integer<uint8_t>(t[k]); };
  switch (channels) {
    case 1:
      return {c(0), c(0), c(0), 255};
    case 2:
      return {c(0), c(0), c(0), c(1)};
    case 3:
      return {c(0), c(1), c(2), 255};
    default:
      return {c(0), c(1), c(2), c(3)};
  }
}

CacheState placePages(const VirtualTextureReader& reader, std::span<const PlacedPage> pages,
                      uint32_t framesX, uint32_t framesY) {
  CacheState state;
  state.description = reader.description();
  const TextureDescription& d = state.description;
  requirePageTablesFit(reader.path(), d.levelCount);
  const uint32_t side = d.storedPageSide();
  if (framesX == 0 || framesY == 0 || uint64_t{framesX} * side > kMaxCacheSideTexels ||
      uint64_t{framesY} * side > kMaxCacheSideTexels)
    throw std::invalid_argument(std::to_string(framesX) + " x " + std::to_string(framesY) +
                                " frames of " + std::to_string(side) +
                                " texels: the cache texture must have 1 to " +
                                std::to_string(kMaxCacheSideTexels) + " texels per side");
  state.framesX = framesX;
  state.framesY = framesY;
  state.widthTexels = framesX * side;
  state.heightTexels = framesY * side;
  state.texels = ZeroedBytes(size_t{state.widthTexels} * state.heightTexels * 4);

  // Frames: the page's own entry; everything else inherits its parent's, level by level.
  std::vector<std::vector<glm::ivec2>> frameOf(d.levelCount);
  for (uint32_t m = 0; m < d.levelCount; ++m) frameOf[m].assign(pagesInLevel(m), glm::ivec2(-1));
  std::vector<bool> frameTaken(size_t{framesX} * framesY, false);
  for (const PlacedPage& placed : pages) {
    const std::string name = "page " + std::to_string(placed.page);
    if (placed.page >= pageCount(d.levelCount - 1) ||
        !reader.contains(fromAbsoluteIndex(placed.page)))
      throw std::invalid_argument(name + " is not stored in the texture");
    if (placed.frameX >= framesX || placed.frameY >= framesY)
      throw std::invalid_argument(name + ": frame (" + std::to_string(placed.frameX) + ", " +
                                  std::to_string(placed.frameY) + ") lies outside the " +
                                  std::to_string(framesX) + " x " + std::to_string(framesY) +
                                  " frames");
    const size_t frame = size_t{placed.frameY} * framesX + placed.frameX;
    const PageId page = fromAbsoluteIndex(placed.page);
    if (frameTaken[frame])
      throw std::invalid_argument(name + ": frame (" + std::to_string(placed.frameX) + ", " +
                                  std::to_string(placed.frameY) + ") already holds a page");
    if (frameOf[page.level][relativeIndex(page)].x >= 0)
      throw std::invalid_argument(name + " is resident twice");
    frameTaken[frame] = true;
    frameOf[page.level][relativeIndex(page)] =
        glm::ivec2(static_cast<int>(placed.frameX), static_cast<int>(placed.frameY));
    storePage(state, placed.frameX, placed.frameY, reader.readPage(page));
    state.residentPages.push_back(placed.page);
  }
  if (frameOf[0][0].x < 0)
    throw std::invalid_argument("the root page (0) is not resident: every lookup falls back to it");
  state.indirection = IndirectionTable(d.levelCount);
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    for (uint64_t p = 0; p < pagesInLevel(m); ++p) {
      const PageId page = fromRelativeIndex(p, m);
      const glm::ivec2 frame = frameOf[m][p];
      state.indirection.set(page, frame.x >= 0 ? glm::u16vec4(frame.x, frame.y, m, 0)
                                               : state.indirection.entry(parent(page)));
    }
  }
  return state;
}

CacheState makeCacheState(const VirtualTextureReader& reader, std::span<const uint64_t> pages,
                          uint32_t framesX, uint32_t framesY) {
  std::vector<uint64_t> resident(pages.begin(), pages.end());
  if (std::find(resident.begin(), resident.end(), uint64_t{0}) == resident.end())
    resident.insert(resident.begin(), 0);
  if (resident.size() > uint64_t{framesX} * framesY)
    throw std::invalid_argument(std::to_string(resident.size()) + " pages do not fit into " +
                                std::to_string(framesX) + " x " + std::to_string(framesY) +
                                " frames");
  std::vector<PlacedPage> placed;
  placed.reserve(resident.size());
  for (size_t k = 0; k < resident.size(); ++k)
    placed.push_back(
        {resident[k], static_cast<uint32_t>(k % framesX), static_cast<uint32_t>(k / framesX)});
  return placePages(reader, placed, framesX, framesY);
}

void storePage(CacheState& cache, uint32_t frameX, uint32_t frameY,
               std::span<const std::byte> texels) {
  const TextureDescription& d = cache.description;
  const uint32_t side = d.storedPageSide();
  if (texels.size() != d.pageBytes() || frameX >= cache.framesX || frameY >= cache.framesY)
    throw std::invalid_argument("storePage: page or frame does not fit the cache");
  for (uint32_t y = 0; y < side; ++y)
    for (uint32_t x = 0; x < side; ++x) {
      const glm::u8vec4 rgba =
          expandToRgba(texels.data() + (size_t{y} * side + x) * d.channels, d.channels);
      uint8_t* out = cache.texels.data() +
                     ((size_t{frameY * side + y} * cache.widthTexels) + frameX * side + x) * 4;
      for (int c = 0; c < 4; ++c) out[c] = rgba[c];
    }
}

CacheState cacheOfLevels(const VirtualTextureReader& reader, int maxLevel, uint32_t maxSideTexels) {
  const uint32_t maxFrames =
      std::max<uint32_t>(1, maxSideTexels / reader.description().storedPageSide());
  std::vector<uint64_t> pages;
  for (uint64_t slot = 0; slot < reader.storedPageCount(); ++slot) {
    const uint64_t page = reader.storedPage(slot);
    if (maxLevel < 0 || levelOfAbsoluteIndex(page) <= static_cast<uint32_t>(maxLevel))
      pages.push_back(page);
  }
  while (pages.size() > uint64_t{maxFrames} * maxFrames) {
    const uint32_t finest = levelOfAbsoluteIndex(pages.back());
    std::erase_if(pages, [finest](uint64_t p) { return levelOfAbsoluteIndex(p) == finest; });
  }
  const auto frames = std::max<uint32_t>(
      1, static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(pages.size())))));
  return makeCacheState(reader, pages, frames, frames);
}

CacheState rootOnlyCache(const TextureDescription& description) {
  CacheState cache;
  cache.description = description;
  cache.framesX = cache.framesY = 1;
  cache.widthTexels = cache.heightTexels = description.storedPageSide();
  cache.residentPages = {0};
  cache.texels = ZeroedBytes(uint64_t{cache.widthTexels} * cache.heightTexels * 4);
  cache.indirection = IndirectionTable(description.levelCount);
  return cache;
}

}  // namespace vt
