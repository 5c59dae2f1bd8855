#include "runtime/page_cache.h"

#include <gtest/gtest.h>

namespace vt {
namespace {

TEST(PageCache, FillsFramesInRowOrderThenEvictsTheLeastRecentlyUsed) {
  PageCache cache(2, 2);
  EXPECT_EQ(cache.insert(10)->frame, (FrameId{0, 0}));
  EXPECT_EQ(cache.insert(11)->frame, (FrameId{1, 0}));
  EXPECT_EQ(cache.insert(12)->frame, (FrameId{0, 1}));
  EXPECT_EQ(cache.insert(13)->frame, (FrameId{1, 1}));
  cache.touch(10);  // 11 is now the least recently used
  const auto placement = cache.insert(14);
  ASSERT_TRUE(placement);
  EXPECT_EQ(placement->evicted, 11u);
  EXPECT_EQ(placement->frame, (FrameId{1, 0}));  // 14 takes 11's frame
  EXPECT_FALSE(cache.contains(11));
  EXPECT_EQ(cache.insert(15)->evicted, 12u);
  EXPECT_EQ(cache.statistics().evictions, 2u);
  EXPECT_EQ(cache.residentPages(), (std::vector<uint64_t>{10, 13, 14, 15}));
}

TEST(PageCache, NeverEvictsALockedPage) {
  // Levels 0 and 1 (pages 0..4) are locked.
  PageCache cache(2, 1, 2);
  ASSERT_TRUE(cache.insert(0));
  ASSERT_TRUE(cache.insert(7));  // level 2: unlocked
  cache.touch(0);
  EXPECT_EQ(cache.insert(8)->evicted, 7u);  // 0 is older but locked
  EXPECT_EQ(cache.insert(9)->evicted, 8u);
  PageCache full(1, 1, 2);
  ASSERT_TRUE(full.insert(1));
  EXPECT_FALSE(full.insert(2));  // the only frame holds a locked page
  EXPECT_EQ(full.statistics().refusals, 1u);
  EXPECT_TRUE(full.contains(1));
}

TEST(PageCache, RejectsMisuse) {
  EXPECT_THROW(PageCache(0, 4), std::invalid_argument);
  PageCache cache(2, 2);
  cache.insert(3);
  EXPECT_THROW(cache.insert(3), std::logic_error);
}

}  // namespace
}  // namespace vt
