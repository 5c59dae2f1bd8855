#include "runtime/page_cache.h"

#include <algorithm>
#include <stdexcept>

namespace vt {

PageCache::PageCache(uint32_t framesX, uint32_t framesY, uint32_t lockedLevels)
    : framesX_(framesX), framesY_(framesY), lockedLevels_(lockedLevels) {
  if (framesX == 0 || framesY == 0) throw std::invalid_argument("PageCache: no frames");
}

std::optional<FrameId> PageCache::frameOf(uint64_t page) const {
  const auto it = frames_.find(page);
  if (it == frames_.end()) return std::nullopt;
  return it->second.frame;
}

void PageCache::touch(uint64_t page) {
  const auto it = frames_.find(page);
  if (it == frames_.end() || it->second.locked) return;
  lru_.splice(lru_.end(), lru_, it->second.lru);
}

std::optional<PageCache::Placement> PageCache::insert(uint64_t page) {
  if (contains(page))
    throw std::logic_error("PageCache: page " + std::to_string(page) + " is already resident");
  Placement placement;
  if (nextFree_ < capacity()) {
    placement.frame = {static_cast<uint32_t>(nextFree_ % framesX_),
                       static_cast<uint32_t>(nextFree_ / framesX_)};
    ++nextFree_;
  } else if (!lru_.empty()) {
    const uint64_t victim = lru_.front();
    lru_.pop_front();
    placement.frame = frames_.at(victim).frame;
    placement.evicted = victim;
    frames_.erase(victim);
    ++statistics_.evictions;
  } else {
    ++statistics_.refusals;
    return std::nullopt;
  }
  const bool locked = levelOfAbsoluteIndex(page) < lockedLevels_;
  Slot slot{placement.frame, locked, lru_.end()};
  if (!locked) slot.lru = lru_.insert(lru_.end(), page);
  frames_.emplace(page, slot);
  ++statistics_.insertions;
  return placement;
}

std::vector<uint64_t> PageCache::residentPages() const {
  std::vector<uint64_t> pages;
  pages.reserve(frames_.size());
  for (const auto& [page, slot] : frames_) pages.push_back(page);
  std::sort(pages.begin(), pages.end());
  return pages;
}

}  // namespace vt
