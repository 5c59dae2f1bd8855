#pragma once
// A page cache state as the GL renderer holds it (thesis 3.1.2, 3.2.2): a cache texture of
// frames of (P + 2B)^2 texels and an indirection table whose entry for page (px, py, m) names the
// frame of that page or of its best resident ancestor, and that page's level (3.2.2.2-3.2.2.3).
// Both renderers read the same state: the GL path uploads it, the oracle samples it.
//
// Layout: frame (fx, fy) starts at texel (fx, fy) * (P + 2B), rows of increasing t. Texels are
// RGBA8 whatever the texture's channels (gray spreads to RGB, missing alpha is opaque). The
// indirection table is render/indirection_table.h.

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "common/zeroed_buffer.h"
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
                      uint32_t framesX, uint32_t framesY);

// Places `pages` (absolute indices; the root is added when missing) into frames in the order
// given, row by row, reads them from `reader` and builds the indirection table. Throws
// std::invalid_argument when they do not fit into framesX x framesY frames or a page is not
// stored in the texture.
CacheState makeCacheState(const VirtualTextureReader& reader, std::span<const uint64_t> pages,
                          uint32_t framesX, uint32_t framesY);

// A cache state of the stored pages of levels 0..maxLevel (all levels when maxLevel is negative),
// dropping the finest levels until the pages fit into a square cache texture of at most
// `maxSideTexels` texels per side; frames are laid out in a square grid.
CacheState cacheOfLevels(const VirtualTextureReader& reader, int maxLevel, uint32_t maxSideTexels);

// A cache state of `description` with only the root page resident (its texels zero): enough to
// draw needbuffers, which do not depend on what is resident.
CacheState rootOnlyCache(const TextureDescription& description);

// Copies a stored page's texels (borders included) into frame `frameX, frameY` of the cache.
void storePage(CacheState& cache, uint32_t frameX, uint32_t frameY,
               std::span<const std::byte> texels);

// RGBA8 of one stored texel of `channels` components.
glm::u8vec4 expandToRgba(const std::byte* texel, uint32_t channels);

}  // namespace vt
