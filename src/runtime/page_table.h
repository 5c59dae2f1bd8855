#pragma once
// The page table (thesis 3.2.2.2) as the quadtree in arrays, one per level, which is also the
// indirection table (3.2.2.3) the shader reads: entry (px, py, m) holds the frame (fx, fy) of the
// page itself when resident, else of its best resident ancestor, and that page's level i <= m:
// (fx, fy, i, 0). An entry without any resident ancestor (before the root is loaded) has i = kNone.
//
// The thesis loops over the whole array after each cache change. Here an insertion or eviction
// walks only the part of the page's subtree whose entries change: it stops at resident pages,
// below which nothing changes. A test checks that after any sequence the table equals the full
// recomputation.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "format/page_address.h"
#include "runtime/page_cache.h"

namespace vt {

class PageTable {
 public:
  static constexpr uint16_t kNone = 0xffff;

  explicit PageTable(uint32_t levelCount);

  uint32_t levelCount() const { return static_cast<uint32_t>(entries_.size()); }
  glm::u16vec4 entry(PageId page) const { return entries_[page.level][index(page)]; }
  bool resident(PageId page) const { return resident_[page.level][index(page)] != 0; }
  // Entries of level m, row by row (2^m x 2^m): the indirection table's level m.
  const std::vector<glm::u16vec4>& level(uint32_t m) const { return entries_[m]; }

  void insert(PageId page, FrameId frame);
  void evict(PageId page);

  // Subtree roots whose entries changed since the last call (for partial uploads).
  std::vector<PageId> takeChanges();
  // Entries written since construction (the cost of the incremental updates).
  uint64_t entriesWritten() const { return entriesWritten_; }

  // The thesis's full recomputation from the resident set, for checking.
  void recomputeAll();

 private:
  static size_t index(PageId page) { return page.x + (size_t{page.y} << page.level); }
  // Sets `value` on every non-resident page below `page` whose entry equals `old`.
  void propagate(PageId page, glm::u16vec4 old, glm::u16vec4 value);

  std::vector<std::vector<glm::u16vec4>> entries_;
  std::vector<std::vector<uint8_t>> resident_;
  std::vector<PageId> changes_;
  uint64_t entriesWritten_ = 0;
};

}  // namespace vt
