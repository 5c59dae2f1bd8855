#pragma once
// Which pages a layout stores: a page is stored when some image touches its area on any level
// (so every stored page's parent is stored too, and the root always is). A layout whose images
// cover the whole texture stores every page and is written dense.

#include <cstdint>
#include <vector>

#include "build/layout.h"

namespace vt {

// The most pages one texture may store (2^28 pages of 128^2 RGBA texels are about 19 TiB).
inline constexpr uint64_t kMaxStoredPages = uint64_t{1} << 28;

// Absolute indices of the stored pages, rising. Throws InputError when more than
// kMaxStoredPages would be stored, before allocating for them.
std::vector<uint64_t> storedPages(const Layout& layout);

}  // namespace vt
