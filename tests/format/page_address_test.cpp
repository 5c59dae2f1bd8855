#include "format/page_address.h"

#include <gtest/gtest.h>

namespace vt {
namespace {

TEST(PageAddress, ThesisExampleAbsolutePageSixIsPageOneOnLevelTwo) {
  // Thesis 3.1.1.1: "In the relative scheme, we would identify for example page 6 as page 1 on
  // mip level 2."
  const PageId page = fromAbsoluteIndex(6);
  EXPECT_EQ(page.level, 2u);
  EXPECT_EQ(relativeIndex(page), 1u);
  EXPECT_EQ(page, (PageId{1, 0, 2}));
  EXPECT_EQ(absoluteIndex(PageId{1, 0, 2}), 6u);
}

TEST(PageAddress, LevelSizesFollowPowersOfFour) {
  EXPECT_EQ(pagesInLevel(0), 1u);
  EXPECT_EQ(pagesInLevel(3), 64u);
  EXPECT_EQ(firstPageOfLevel(0), 0u);
  EXPECT_EQ(firstPageOfLevel(1), 1u);
  EXPECT_EQ(firstPageOfLevel(2), 5u);
  EXPECT_EQ(firstPageOfLevel(3), 21u);
  EXPECT_EQ(pageCount(2), 21u);
  EXPECT_EQ(levelSide(128, 0), 128u);
  EXPECT_EQ(levelSide(128, 8), 32768u);
}

TEST(PageAddress, ExhaustiveRoundTripsUpToLevelSix) {
  uint64_t expected = 0;
  for (uint32_t m = 0; m <= 6; ++m) {
    for (uint32_t y = 0; y < pagesPerSide(m); ++y) {
      for (uint32_t x = 0; x < pagesPerSide(m); ++x, ++expected) {
        const PageId page{x, y, m};
        // Enumeration is level by level, row by row (the order of the file).
        ASSERT_EQ(absoluteIndex(page), expected);
        ASSERT_EQ(fromAbsoluteIndex(expected), page);
        ASSERT_EQ(levelOfAbsoluteIndex(expected), m);
        ASSERT_EQ(fromRelativeIndex(relativeIndex(page), m), page);
        ASSERT_EQ(relativeIndex(page), x + y * pagesPerSide(m));
        if (m == 0) continue;
        const PageId up = parent(page);
        ASSERT_EQ(up, (PageId{x / 2, y / 2, m - 1}));
        int found = 0;
        for (const PageId child : children(up)) found += child == page;
        ASSERT_EQ(found, 1);
      }
    }
  }
  EXPECT_EQ(expected, pageCount(6));
}

TEST(PageAddress, ChildrenAreInEnumerationOrderAndShareTheParent) {
  const auto kids = children(PageId{3, 5, 4});
  EXPECT_EQ(kids[0], (PageId{6, 10, 5}));
  EXPECT_EQ(kids[1], (PageId{7, 10, 5}));
  EXPECT_EQ(kids[2], (PageId{6, 11, 5}));
  EXPECT_EQ(kids[3], (PageId{7, 11, 5}));
  for (size_t i = 1; i < kids.size(); ++i)
    EXPECT_LT(absoluteIndex(kids[i - 1]), absoluteIndex(kids[i]));
  for (const PageId kid : kids) EXPECT_EQ(parent(kid), (PageId{3, 5, 4}));
}

TEST(PageAddress, AncestorsRunFromParentToRoot) {
  const PageId page{13, 6, 4};
  const auto path = ancestors(page);
  ASSERT_EQ(path.size(), 4u);
  EXPECT_EQ(path[0], (PageId{6, 3, 3}));
  EXPECT_EQ(path[1], (PageId{3, 1, 2}));
  EXPECT_EQ(path[2], (PageId{1, 0, 1}));
  EXPECT_EQ(path[3], (PageId{0, 0, 0}));
  for (const PageId a : path) EXPECT_TRUE(isAncestor(a, page));
  EXPECT_FALSE(isAncestor(page, page));
  EXPECT_FALSE(isAncestor(PageId{0, 0, 1}, page));
  EXPECT_TRUE(ancestors(PageId{}).empty());
}

TEST(PageAddress, BoundariesAtLevelFifteen) {
  const uint32_t m = kMaxLevel;
  const uint32_t last = static_cast<uint32_t>(pagesPerSide(m) - 1);
  EXPECT_EQ(last, 32767u);
  EXPECT_EQ(firstPageOfLevel(m), 357913941u);  // (4^15 - 1) / 3
  EXPECT_EQ(pageCount(m), 1431655765u);        // (4^16 - 1) / 3
  const PageId first{0, 0, m}, lastPage{last, last, m};
  EXPECT_EQ(absoluteIndex(first), firstPageOfLevel(m));
  EXPECT_EQ(absoluteIndex(lastPage), pageCount(m) - 1);
  EXPECT_EQ(fromAbsoluteIndex(pageCount(m) - 1), lastPage);
  EXPECT_EQ(fromAbsoluteIndex(firstPageOfLevel(m)), first);
  // The page just before level 15 is the last of level 14.
  EXPECT_EQ(fromAbsoluteIndex(firstPageOfLevel(m) - 1), (PageId{16383, 16383, 14}));
  EXPECT_EQ(parent(lastPage), (PageId{16383, 16383, 14}));
  EXPECT_EQ(ancestorAt(lastPage, 0), PageId{});
  EXPECT_EQ(ancestors(lastPage).size(), 15u);
  EXPECT_EQ(relativeIndex(lastPage), pagesInLevel(m) - 1);
  EXPECT_EQ(levelSide(4096, m), uint64_t{1} << 27);
  EXPECT_TRUE(isValid(lastPage));
  EXPECT_FALSE(isValid(PageId{last + 1, 0, m}));
  EXPECT_FALSE(isValid(PageId{0, 0, m + 1}));
}

TEST(PageAddress, LevelOfAbsoluteIndexAtEveryLevelBoundary) {
  for (uint32_t m = 0; m <= kMaxLevel; ++m) {
    EXPECT_EQ(levelOfAbsoluteIndex(firstPageOfLevel(m)), m);
    EXPECT_EQ(levelOfAbsoluteIndex(firstPageOfLevel(m + 1) - 1), m);
  }
}

}  // namespace
}  // namespace vt
