#pragma once
// The page cache (thesis 3.1.2, 3.2.2.1): a grid of frames, each holding one page, with least-
// recently-used replacement. Pages of the first `lockedLevels` levels are locked once loaded
// (thesis 4.3.1): they are never evicted. "Used" means needed by a frame: the runtime touches
// every resident page the needbuffer names. The order of operations alone decides every
// placement, so the same sequence gives the same cache.

#include <cstdint>
#include <list>
#include <optional>
#include <unordered_map>
#include <vector>

#include "format/page_address.h"

namespace vt {

struct FrameId {
  uint32_t x = 0, y = 0;
  friend bool operator==(const FrameId&, const FrameId&) = default;
};

struct PageCacheStatistics {
  uint64_t insertions = 0, evictions = 0, refusals = 0;  // refusals: no frame could be freed
};

class PageCache {
 public:
  PageCache(uint32_t framesX, uint32_t framesY, uint32_t lockedLevels = 0);

  uint32_t framesX() const { return framesX_; }
  uint32_t framesY() const { return framesY_; }
  uint64_t capacity() const { return uint64_t{framesX_} * framesY_; }
  uint64_t size() const { return frames_.size(); }
  const PageCacheStatistics& statistics() const { return statistics_; }

  bool contains(uint64_t page) const { return frames_.count(page) != 0; }
  std::optional<FrameId> frameOf(uint64_t page) const;

  // Marks a resident page as used now (most recently used).
  void touch(uint64_t page);

  struct Placement {
    FrameId frame;
    std::optional<uint64_t> evicted;  // the page that had to leave, if any
  };
  // Places a page that is not resident: into a free frame (in row order), else into the frame of
  // the least recently used unlocked page. Nothing when every frame holds a locked page.
  std::optional<Placement> insert(uint64_t page);

  // The resident pages, by absolute index.
  std::vector<uint64_t> residentPages() const;

 private:
  struct Slot {
    FrameId frame;
    bool locked;
    std::list<uint64_t>::iterator lru;  // position in lru_ (unlocked pages only)
  };

  uint32_t framesX_, framesY_, lockedLevels_;
  uint64_t nextFree_ = 0;    // frames never used yet: nextFree_ .. capacity - 1
  std::list<uint64_t> lru_;  // unlocked pages, least recently used first
  std::unordered_map<uint64_t, Slot> frames_;
  PageCacheStatistics statistics_;
};

}  // namespace vt
