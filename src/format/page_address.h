#pragma once
// Page addressing of a virtual texture (thesis 3.1.1.1 and 3.1.1.2).
//
// Levels are numbered as in the thesis: m = 0 is the coarsest level (one page), m = L the finest.
// Level m has 2^m x 2^m pages, n_m = 4^m. Pages are enumerated level by level, row by row:
//
//        level 0     level 1        level 2
//        +---+      +---+---+      +----+----+----+----+
//        | 0 |      | 1 | 2 |      |  5 |  6 |  7 |  8 |   py = 0
//        +---+      +---+---+      +----+----+----+----+
//                   | 3 | 4 |      |  9 | 10 | 11 | 12 |   py = 1
//                   +---+---+      +----+----+----+----+
//                                  | 13 | 14 | 15 | 16 |
//                                  +----+----+----+----+
//                                  | 17 | 18 | 19 | 20 |   py = 3
//                                  +----+----+----+----+
//                                   px=0           px=3
//
// py grows with the texture's t coordinate (row 0 holds t in [0, 2^-m)), so page rows follow
// texel rows in memory. All arithmetic is 64-bit; every function is exact for m <= kMaxLevel.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace vt {

// The finest level index a virtual texture may have: 4^16 pages still fit comfortably in 64 bits.
inline constexpr uint32_t kMaxLevel = 15;

struct PageId {
  uint32_t x = 0;      // p_x^m, in [0, 2^m)
  uint32_t y = 0;      // p_y^m, in [0, 2^m)
  uint32_t level = 0;  // m

  friend constexpr bool operator==(const PageId&, const PageId&) = default;
};

// Pages along one side of level m: 2^m.
constexpr uint64_t pagesPerSide(uint32_t level) { return uint64_t{1} << level; }

// n_m = 2^m * 2^m (thesis 3.1.1.1).
constexpr uint64_t pagesInLevel(uint32_t level) { return uint64_t{1} << (2 * level); }

// Absolute index of the first page of level m: sum_{i<m} 4^i = (4^m - 1) / 3.
constexpr uint64_t firstPageOfLevel(uint32_t level) { return (pagesInLevel(level) - 1) / 3; }

// Pages in levels 0..finestLevel together.
constexpr uint64_t pageCount(uint32_t finestLevel) { return firstPageOfLevel(finestLevel + 1); }

// Texels along one side of level m for pages of pageSize texels: 2^m * P.
constexpr uint64_t levelSide(uint32_t pageSize, uint32_t level) {
  return uint64_t{pageSize} << level;
}

// p_rel^m = p_x^m + p_y^m * 2^m (thesis 3.1.1.1).
constexpr uint64_t relativeIndex(PageId page) { return page.x + (uint64_t{page.y} << page.level); }

// p_x^m = p_rel^m mod 2^m, p_y^m = floor(p_rel^m / 2^m).
constexpr PageId fromRelativeIndex(uint64_t relative, uint32_t level) {
  return {static_cast<uint32_t>(relative & (pagesPerSide(level) - 1)),
          static_cast<uint32_t>(relative >> level), level};
}

// p_abs = p_rel^m + (4^m - 1) / 3 (thesis 3.1.1.1).
constexpr uint64_t absoluteIndex(PageId page) {
  return relativeIndex(page) + firstPageOfLevel(page.level);
}

// The page column (or row) of level m under a texture coordinate s: floor(s * 2^m) (thesis
// 3.2.3.1), clamped to [0, 2^m - 1] so that s = 1.0 falls in the last page, and 0 for NaN. It
// mirrors the shader's vtPageAt (shader/virtual_texture.glsl) for every float s: there s * 2^m is
// a float product by a power of two, exact unless it overflows to infinity, which clamps to the
// last page as the exact double product does here. Change one, change both
// (tests/shader/virtual_texture_shader_test.cpp checks that they agree).
inline int pageAt(double coordinate, int level) {
  if (!(coordinate >= 0)) return 0;
  const int last = (1 << level) - 1;
  return static_cast<int>(std::min<double>(std::floor(std::ldexp(coordinate, level)), last));
}

// The level holding absolute page p: the m with (4^m - 1) / 3 <= p < (4^(m+1) - 1) / 3, that is
// 4^m <= 3p + 1 < 4^(m+1), so m = floor(log2(3p + 1) / 2).
constexpr uint32_t levelOfAbsoluteIndex(uint64_t absolute) {
  return static_cast<uint32_t>((std::bit_width(3 * absolute + 1) - 1) / 2);
}

constexpr PageId fromAbsoluteIndex(uint64_t absolute) {
  const uint32_t level = levelOfAbsoluteIndex(absolute);
  return fromRelativeIndex(absolute - firstPageOfLevel(level), level);
}

// The page of level m-1 that covers the same texture area (thesis 3.1.1.2). Level 0 has none.
constexpr PageId parent(PageId page) { return {page.x / 2, page.y / 2, page.level - 1}; }

// The absolute index of the parent of absolute page p (level > 0).
constexpr uint64_t parentIndex(uint64_t absolute) {
  return absoluteIndex(parent(fromAbsoluteIndex(absolute)));
}

// The four pages of level m+1 inside this page, in enumeration order:
// (2x, 2y), (2x+1, 2y), (2x, 2y+1), (2x+1, 2y+1).
constexpr std::array<PageId, 4> children(PageId page) {
  const uint32_t x = 2 * page.x, y = 2 * page.y, m = page.level + 1;
  return {PageId{x, y, m}, PageId{x + 1, y, m}, PageId{x, y + 1, m}, PageId{x + 1, y + 1, m}};
}

// The ancestor of `page` on level `level` <= page.level (the page itself when equal).
constexpr PageId ancestorAt(PageId page, uint32_t level) {
  const uint32_t shift = page.level - level;
  return {page.x >> shift, page.y >> shift, level};
}

// All pages on the path from `page` (exclusive) to the root (inclusive), nearest first.
std::vector<PageId> ancestors(PageId page);

// True when `ancestor` lies on the path from `page` to the root (a page is not its own ancestor).
constexpr bool isAncestor(PageId ancestor, PageId page) {
  return ancestor.level < page.level && ancestorAt(page, ancestor.level) == ancestor;
}

// True when the page's coordinates lie inside its level.
constexpr bool isValid(PageId page) {
  return page.level <= kMaxLevel && page.x < pagesPerSide(page.level) &&
         page.y < pagesPerSide(page.level);
}

}  // namespace vt
