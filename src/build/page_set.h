#pragma once
// Which pages a layout stores: a page is stored when some image touches its area on any level
// (so every stored page's parent is stored too, and the root always is). A layout whose images
// cover the whole texture stores every page and is written dense.

#include <cstdint>
#include <vector>

#include "build/layout.h"
#include "common/resource_limits.h"

namespace vt {

// Absolute indices of the stored pages, rising. Throws InputError when more than
// kMaxStoredPages (common/resource_limits.h) would be stored, before allocating for them.
std::vector<uint64_t> storedPages(const Layout& layout);

}  // namespace vt
