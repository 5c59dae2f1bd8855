#include "runtime/page_table.h"

#include <gtest/gtest.h>

#include <random>

namespace vt {
namespace {

TEST(PageTable, EntriesNameTheBestResidentAncestor) {
  PageTable table(3);
  table.insert(PageId{0, 0, 0}, FrameId{5, 6});
  EXPECT_EQ(table.entry(PageId{3, 2, 2}), glm::u16vec4(5, 6, 0, 0));
  table.insert(PageId{1, 1, 1}, FrameId{1, 2});
  EXPECT_EQ(table.entry(PageId{3, 2, 2}), glm::u16vec4(1, 2, 1, 0));  // (3, 2) lies in (1, 1)
  EXPECT_EQ(table.entry(PageId{1, 2, 2}), glm::u16vec4(5, 6, 0, 0));  // (1, 2) lies in (0, 1)
  table.insert(PageId{3, 2, 2}, FrameId{7, 7});
  EXPECT_EQ(table.entry(PageId{3, 2, 2}), glm::u16vec4(7, 7, 2, 0));
  table.evict(PageId{1, 1, 1});
  EXPECT_EQ(table.entry(PageId{2, 2, 2}), glm::u16vec4(5, 6, 0, 0));  // back to the root
  EXPECT_EQ(table.entry(PageId{3, 2, 2}), glm::u16vec4(7, 7, 2, 0));  // still itself
}

TEST(PageTable, IncrementalUpdatesEqualTheFullRecomputationAfterAnySequence) {
  // Random inserts and evictions through an LRU cache, checked against the thesis's full loop
  // after every operation.
  std::mt19937 random(99);
  const uint32_t levels = 6;
  PageTable table(levels);
  PageCache cache(5, 4, 1);
  std::uniform_int_distribution<uint64_t> anyPage(0, pageCount(levels - 1) - 1);
  uint64_t operations = 0;
  for (int step = 0; step < 3000; ++step) {
    const uint64_t page = step == 0 ? 0 : anyPage(random);
    if (cache.contains(page)) {
      cache.touch(page);
      continue;
    }
    const auto placement = cache.insert(page);
    if (!placement) continue;
    if (placement->evicted) table.evict(fromAbsoluteIndex(*placement->evicted));
    table.insert(fromAbsoluteIndex(page), placement->frame);
    ++operations;
    PageTable full = table;
    full.recomputeAll();
    for (uint32_t m = 0; m < levels; ++m)
      ASSERT_EQ(table.level(m), full.level(m)) << "step " << step;
  }
  EXPECT_GT(operations, 2000u);
  // Far fewer entries than the full loop would write (pageCount(5) = 1365 per change).
  EXPECT_LT(table.entriesWritten(), operations * pageCount(levels - 1) / 10);
}

}  // namespace
}  // namespace vt
