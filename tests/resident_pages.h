#pragma once
// Residency for tests of the cache's fallback: which pages of a dense texture a cache holds.

#include <cstdint>
#include <initializer_list>
#include <vector>

#include "format/page_address.h"

namespace vt::test {

// Every page of levels 0 to `whole`, then of each next level every strides[k]-th page (from its
// first): a lookup beyond the levels held whole falls back to a resident ancestor where its own
// page is left out.
inline std::vector<uint64_t> pagesFallingBack(uint32_t whole,
                                              std::initializer_list<uint64_t> strides) {
  std::vector<uint64_t> pages;
  for (uint64_t p = 0; p < pageCount(whole); ++p) pages.push_back(p);
  uint32_t level = whole + 1;
  for (const uint64_t stride : strides) {
    for (uint64_t p = firstPageOfLevel(level); p < pageCount(level); p += stride)
      pages.push_back(p);
    ++level;
  }
  return pages;
}

}  // namespace vt::test
