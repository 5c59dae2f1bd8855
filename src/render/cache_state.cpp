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

CacheState emptyCache(const TextureDescription& description, uint32_t framesX, uint32_t framesY,
                      BlockDecoding decoding) {
  CacheState state;
  state.description = description;
  const uint32_t side = description.storedPageSide();
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
  state.decoding = decoding;
  if (isBlockCompressed(description.format))
    state.blocks = ZeroedBlocks(uint64_t{framesX} * framesY * description.storedPageBytes());
  return state;
}

CacheState placePages(const VirtualTextureReader& reader, std::span<const PlacedPage> pages,
                      uint32_t framesX, uint32_t framesY, BlockDecoding decoding) {
  requirePageTablesFit(reader.path(), reader.description().levelCount);
  CacheState state = emptyCache(reader.description(), framesX, framesY, decoding);
  const TextureDescription& d = state.description;

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
    storePage(state, placed.frameX, placed.frameY, reader.readStoredPage(page));
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
                          uint32_t framesX, uint32_t framesY, BlockDecoding decoding) {
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
  return placePages(reader, placed, framesX, framesY, decoding);
}

namespace {

// Decodes the blocks of frame (frameX, frameY) into its texels under the cache's decoding.
void decodeFrame(CacheState& cache, uint32_t frameX, uint32_t frameY) {
  const TextureDescription& d = cache.description;
  const uint32_t side = d.storedPageSide(), blocksPerRow = cache.widthTexels / 4;
  const size_t bytes = blockBytes(d.format);
  for (uint32_t by = 0; by < side / 4; ++by)
    for (uint32_t bx = 0; bx < side / 4; ++bx) {
      const size_t block = size_t{frameY * side / 4 + by} * blocksPerRow + frameX * side / 4 + bx;
      const std::array<BlockTexel, 16> texels =
          decodeBlock(d.format, cache.blocks.data() + block * bytes, cache.decoding);
      for (uint32_t t = 0; t < 16; ++t) {
        const size_t x = size_t{frameX} * side + bx * 4 + t % 4,
                     y = size_t{frameY} * side + by * 4 + t / 4;
        std::copy(texels[t].begin(), texels[t].end(),
                  cache.texels.data() + (y * cache.widthTexels + x) * 4);
      }
    }
}

}  // namespace

CacheState withDecoding(const CacheState& cache, BlockDecoding decoding) {
  CacheState copy = cache;
  if (!decodesDifferently(cache, decoding)) return copy;
  copy.decoding = decoding;
  for (const uint64_t page : cache.residentPages) {
    const glm::u16vec4 entry = cache.indirection.entry(fromAbsoluteIndex(page));
    decodeFrame(copy, entry.x, entry.y);
  }
  return copy;
}

void storePage(CacheState& cache, uint32_t frameX, uint32_t frameY,
               std::span<const std::byte> stored) {
  const TextureDescription& d = cache.description;
  const uint32_t side = d.storedPageSide();
  if (stored.size() != d.storedPageBytes() || frameX >= cache.framesX || frameY >= cache.framesY)
    throw std::invalid_argument("storePage: page or frame does not fit the cache");
  if (isBlockCompressed(d.format)) {
    const uint32_t blocksPerRow = cache.widthTexels / 4, pageBlocks = side / 4;
    const size_t bytes = blockBytes(d.format);
    for (uint32_t by = 0; by < pageBlocks; ++by)
      std::copy_n(stored.data() + size_t{by} * pageBlocks * bytes, pageBlocks * bytes,
                  cache.blocks.data() +
                      (size_t{frameY * pageBlocks + by} * blocksPerRow + frameX * pageBlocks) *
                          bytes);
    decodeFrame(cache, frameX, frameY);
    return;
  }
  for (uint32_t y = 0; y < side; ++y)
    for (uint32_t x = 0; x < side; ++x) {
      const glm::u8vec4 rgba =
          expandToRgba(stored.data() + (size_t{y} * side + x) * d.channels, d.channels);
      uint8_t* out = cache.texels.data() +
                     ((size_t{frameY * side + y} * cache.widthTexels) + frameX * side + x) * 4;
      for (int c = 0; c < 4; ++c) out[c] = rgba[c];
    }
}

CacheState cacheOfLevels(const VirtualTextureReader& reader, int maxLevel, uint32_t maxSideTexels,
                         BlockDecoding decoding) {
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
  return makeCacheState(reader, pages, frames, frames, decoding);
}

CacheState rootOnlyCache(const TextureDescription& description) {
  CacheState cache = emptyCache(description, 1, 1);
  cache.residentPages = {0};
  cache.indirection = IndirectionTable(description.levelCount);
  return cache;
}

}  // namespace vt
