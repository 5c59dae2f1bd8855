#pragma once
// A page cache state as the GL renderer holds it (thesis 3.1.2, 3.2.2): a cache texture of
// frames of (P + 2B)^2 texels and an indirection table whose entry for page (px, py, m) names the
// frame of that page or of its best resident ancestor, and that page's level (3.2.2.2-3.2.2.3).
// Both renderers read the same state: the GL path uploads it, the oracle samples it.
//
// Layout: frame (fx, fy) starts at texel (fx, fy) * (P + 2B), rows of increasing t. Texels are
// RGBA8 whatever the texture's channels (gray spreads to RGB, missing alpha is opaque). A block
// format's cache is its blocks, as the GL path uploads them into a texture of the same compressed
// format, and their RGBA8 decoding under one member of the block-decoding family
// (format/block_decoding.h), which the oracle samples. The indirection table is
// render/indirection_table.h.

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "common/zeroed_buffer.h"
#include "format/block_decoding.h"
#include "format/virtual_texture_reader.h"
#include "render/indirection_table.h"

namespace vt {

struct CacheState {
  TextureDescription description;
  uint32_t framesX = 0, framesY = 0;
  uint32_t widthTexels = 0, heightTexels = 0;
  std::vector<uint64_t> residentPages;  // absolute indices, frame by frame
  ZeroedBytes texels;  // RGBA8, widthTexels x heightTexels; frames no page filled cost no memory
  IndirectionTable indirection;
  // Block formats only: rows of widthTexels / 4 blocks of increasing t, and the decoding that
  // made `texels` from them.
  ZeroedBlocks blocks;
  BlockDecoding decoding;
};

// A page and the frame that holds it.
struct PlacedPage {
  uint64_t page = 0;  // absolute index
  uint32_t frameX = 0, frameY = 0;
};

// The cache state that holds `pages` in the frames given (an engine's cache, or the runtime's),
// read from `reader`, with the indirection table derived from them: every entry names the frame
// of its page or of the page's nearest resident ancestor. Throws std::invalid_argument when a
// frame lies outside framesX x framesY, two pages share a frame or a page, a page is not stored,
// or the root is missing (every lookup falls back to it).
CacheState placePages(const VirtualTextureReader& reader, std::span<const PlacedPage> pages,
                      uint32_t framesX, uint32_t framesY, BlockDecoding decoding = {});

// Places `pages` (absolute indices; the root is added when missing) into frames in the order
// given, row by row, reads them from `reader` and builds the indirection table. Throws
// std::invalid_argument when they do not fit into framesX x framesY frames or a page is not
// stored in the texture.
CacheState makeCacheState(const VirtualTextureReader& reader, std::span<const uint64_t> pages,
                          uint32_t framesX, uint32_t framesY, BlockDecoding decoding = {});

// A cache state of the stored pages of levels 0..maxLevel (all levels when maxLevel is negative),
// dropping the finest levels until the pages fit into a square cache texture of at most
// `maxSideTexels` texels per side; frames are laid out in a square grid.
CacheState cacheOfLevels(const VirtualTextureReader& reader, int maxLevel, uint32_t maxSideTexels,
                         BlockDecoding decoding = {});

// A cache state of `description` with only the root page resident (its texels zero): enough to
// draw needbuffers, which do not depend on what is resident.
CacheState rootOnlyCache(const TextureDescription& description);

// An empty cache texture of framesX x framesY frames for `description` (no page, no indirection).
CacheState emptyCache(const TextureDescription& description, uint32_t framesX, uint32_t framesY,
                      BlockDecoding decoding = {});

// Copies a stored page as the file holds it (VirtualTextureReader::readStoredPage: texels,
// borders included, or blocks) into frame `frameX, frameY` of the cache, decoding blocks with
// the cache's decoding.
void storePage(CacheState& cache, uint32_t frameX, uint32_t frameY,
               std::span<const std::byte> stored);

// The same cache with its blocks decoded under `decoding` (a copy of `cache` where that is its
// decoding already, or the format has no blocks).
CacheState withDecoding(const CacheState& cache, BlockDecoding decoding);

// Whether the oracle must decode `cache` again to sample it under `decoding`.
inline bool decodesDifferently(const CacheState& cache, BlockDecoding decoding) {
  return isBlockCompressed(cache.description.format) && cache.decoding != decoding;
}

// RGBA8 of one stored texel of `channels` components.
glm::u8vec4 expandToRgba(const std::byte* texel, uint32_t channels);

}  // namespace vt
