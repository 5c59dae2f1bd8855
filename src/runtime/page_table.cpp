#include "runtime/page_table.h"

#include <stdexcept>
#include <string>

namespace vt {

PageTable::PageTable(uint32_t levelCount) {
  if (levelCount < 1 || levelCount > kMaxLevel + 1)
    throw std::invalid_argument("PageTable: bad level count");
  for (uint32_t m = 0; m < levelCount; ++m) {
    entries_.emplace_back(pagesInLevel(m), glm::u16vec4(0, 0, kNone, 0));
    resident_.emplace_back(pagesInLevel(m), 0);
  }
}

void PageTable::propagate(PageId page, glm::u16vec4 old, glm::u16vec4 value) {
  if (page.level + 1 >= levelCount()) return;
  for (const PageId child : children(page)) {
    const size_t i = index(child);
    if (resident_[child.level][i] || entries_[child.level][i] != old) continue;
    entries_[child.level][i] = value;
    ++entriesWritten_;
    propagate(child, old, value);
  }
}

void PageTable::insert(PageId page, FrameId frame) {
  const size_t i = index(page);
  if (resident_[page.level][i]) throw std::logic_error("PageTable: page already resident");
  const glm::u16vec4 old = entries_[page.level][i];
  const glm::u16vec4 value(frame.x, frame.y, page.level, 0);
  resident_[page.level][i] = 1;
  entries_[page.level][i] = value;
  ++entriesWritten_;
  // Below, every entry that named the same (coarser) page as this one did now names this page.
  propagate(page, old, value);
  changes_.push_back(page);
}

void PageTable::evict(PageId page) {
  const size_t i = index(page);
  if (!resident_[page.level][i]) throw std::logic_error("PageTable: page not resident");
  const glm::u16vec4 old = entries_[page.level][i];
  const glm::u16vec4 value = page.level == 0 ? glm::u16vec4(0, 0, kNone, 0) : entry(parent(page));
  resident_[page.level][i] = 0;
  entries_[page.level][i] = value;
  ++entriesWritten_;
  propagate(page, old, value);
  changes_.push_back(page);
}

std::vector<PageId> PageTable::takeChanges() {
  std::vector<PageId> changes;
  changes.swap(changes_);
  return changes;
}

void PageTable::recomputeAll() {
  for (uint32_t m = 0; m < levelCount(); ++m)
    for (uint64_t p = 0; p < pagesInLevel(m); ++p) {
      if (resident_[m][p]) continue;  // a resident page keeps its own frame
      entries_[m][p] =
          m == 0 ? glm::u16vec4(0, 0, kNone, 0) : entry(parent(fromRelativeIndex(p, m)));
    }
}

}  // namespace vt
