#pragma once
// The management step of the renderer (thesis 3.2.2): streamed pages go into the page cache (LRU
// frames, locked levels), the page table follows incrementally, and the cache state the renderers
// read (cache texture and indirection table, render/cache_state.h) is updated where it changed.
// Then, after a frame is drawn, the analysis step (3.2.4) turns its needbuffer into the requests
// for the streaming step, and the frame's statistics.

#include <cstdint>
#include <span>
#include <vector>

#include "format/virtual_texture_reader.h"
#include "render/cache_state.h"
#include "runtime/needbuffer_analysis.h"
#include "runtime/page_cache.h"
#include "runtime/page_priority.h"
#include "runtime/page_streamer.h"
#include "runtime/page_table.h"

namespace vt {

struct RuntimeOptions {
  uint32_t framesX = 16, framesY = 16;  // the cache: framesX x framesY frames of (P + 2B)^2
  uint32_t lockedLevels = 0;  // levels 0 .. lockedLevels - 1 never leave the cache; the root
                              // (level 0) never does in any case: every lookup falls back to it
  PriorityOptions priority;
  // Trilinear filtering blends the needed level with the next coarser one, so a pixel that needs
  // page p (level m > 0) also reads p's parent. The needbuffer names p only (thesis 3.2.3.2);
  // with this option the analysis counts the parent as needed by the same pixels: a resident
  // parent is kept fresh in the LRU order, a missing one is requested. Off: the thesis's runtime.
  bool trilinearParents = false;
  // The LookAhead camera's pages: merged with the drawn frame's and ranked with them (the thesis,
  // 4.2.4), or requested after every request of the drawn frame, so that they fill only the slots
  // present demand leaves (prefetch: beyond the thesis).
  bool lookAheadPrefetch = false;
  // Merged LookAhead pages: each of the LookAhead camera's pixels counts this many times against
  // one of the drawn frame's (what the next frame will show over what this one showed).
  uint32_t lookAheadWeight = 1;
  // A residency LOD bias: when more than this many of the drawn frame's needed pages are missing
  // (0: never), every missing page is first requested one level coarser (its parent, with its
  // pixels), then as it is: the budget goes to coarse pages that cover much while the backlog is
  // large, and demand is never dropped. Beyond the thesis.
  uint32_t lodBiasBacklog = 0;
  bool keepAnalysis = false;  // keep each frame's analysis for priorityTerms (inspection)
  // The run's seed of the `random` factor, mixed with the frame number: runs with different seeds
  // draw independent random priorities (0: the frame number alone).
  uint64_t randomSeed = 0;
  // Block formats: how the cache's RGBA8 texels (the oracle's view) are decoded from its blocks
  // (the GL path's); the oracle decodes again where its arithmetic chooses another member.
  BlockDecoding decoding;
};

struct FrameStatistics {
  uint64_t coveredPixels = 0;
  uint64_t neededPages = 0;       // distinct pages the needbuffer names
  uint64_t hits = 0, misses = 0;  // needed pages resident / not resident
  uint64_t hitPixels = 0;         // pixels whose needed page is resident
  uint64_t requested = 0;         // pages requested for streaming (ancestors included)
  uint64_t streamed = 0;          // pages applied to the cache before this frame
  uint64_t evicted = 0;
  uint64_t resident = 0;  // pages in the cache
};

class VirtualTextureRuntime {
 public:
  VirtualTextureRuntime(const VirtualTextureReader& reader, const RuntimeOptions& options);

  const CacheState& cacheState() const { return cache_; }
  const PageTable& pageTable() const { return table_; }
  const PageCache& pageCache() const { return pageCache_; }

  // Loads pages at once (an initial cache state); the root always comes first.
  void preload(std::span<const uint64_t> pages);
  // Applies streamed pages; returns how many were applied and evicted.
  std::pair<uint64_t, uint64_t> apply(std::vector<StreamedPage> pages);

  // What a frame's analysis may add: the hot spot (HotSpot; default the screen centre), and the
  // needbuffer of the LookAhead camera's second pass, whose pages are requested as well.
  struct Prediction {
    std::optional<glm::vec2> hotSpot;
    std::span<const glm::uvec4> lookAheadNeed;
  };

  // Analyzes a drawn frame (needbuffer, and depth when the heuristic needs it), touches the
  // resident needed pages (LRU; with trilinearParents their resident parents too), and returns
  // the requests, most important first. Statistics describe the drawn frame's needbuffer only.
  std::vector<StreamRequest> analyze(std::span<const glm::uvec4> need, std::span<const float> depth,
                                     int width, int height, bool need8, uint64_t frameNumber,
                                     FrameStatistics& statistics,
                                     const Prediction& prediction = {});

  // Whether the configured heuristic reads depth (only then need the renderer deliver it).
  bool needsDepth() const;

  // With keepAnalysis: the factors that ranked `page` in the last analysed frame (the drawn and
  // the LookAhead needbuffer together), runtime/page_priority.h's priorityTerms.
  std::vector<std::pair<std::string, double>> priorityTerms(uint64_t page) const;

 private:
  // E_q(l) from the file's ancestor errors (none without them).
  AncestorErrors fileAncestorErrors() const;
  // The `random` factor's seed of a frame: the frame number, shifted by the run's seed times the
  // golden-ratio constant, so that seeds s and s + 1 share no frame's sequence.
  uint64_t frameSeed(uint64_t frameNumber) const {
    return frameNumber + options_.randomSeed * 0x9e3779b97f4a7c15ull;
  }
  void insert(uint64_t page, std::span<const std::byte> stored, uint64_t& evicted);
  void syncIndirection();

  const VirtualTextureReader& reader_;
  RuntimeOptions options_;
  PageCache pageCache_;
  PageTable table_;
  CacheState cache_;
  NeedBufferAnalysis lastAnalysis_;  // with keepAnalysis only
  uint64_t lastFrame_ = 0;
};

}  // namespace vt
