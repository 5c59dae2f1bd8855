#include "build/page_set.h"

#include <algorithm>

#include "common/error.h"

namespace vt {
namespace {

// Pages of level m an image touches: [x0, x1] x [y0, y1], inclusive.
struct PageRect {
  uint64_t x0, y0, x1, y1;
  uint64_t count() const { return (x1 - x0 + 1) * (y1 - y0 + 1); }
};

PageRect pagesTouched(const Placement& image, const TextureDescription& d, uint32_t level) {
  // A page of level m covers P * 2^(L - m) texels of the finest level along each side.
  const uint64_t pageSpan = uint64_t{d.pageSize} << (d.finestLevel() - level);
  return {image.x / pageSpan, image.y / pageSpan, (image.x + image.width - 1) / pageSpan,
          (image.y + image.height - 1) / pageSpan};
}

}  // namespace

std::vector<uint64_t> storedPages(const Layout& layout) {
  const TextureDescription& d = layout.description;
  // Images do not overlap, but their pages may be shared: the sum is an upper bound.
  uint64_t bound = 0;
  for (uint32_t m = 0; m < d.levelCount; ++m)
    for (const Placement& image : layout.images) bound += pagesTouched(image, d, m).count();
  if (bound > kMaxStoredPages) {
    uint64_t finest = 0;
    for (const Placement& image : layout.images)
      finest += pagesTouched(image, d, d.finestLevel()).count();
    throw InputError(layout.source, "the texture would store up to " + std::to_string(bound) +
                                        " pages (" + std::to_string(finest) +
                                        " on the finest level), more than the limit of " +
                                        std::to_string(kMaxStoredPages));
  }

  std::vector<uint64_t> pages;
  pages.reserve(bound);
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    const size_t levelStart = pages.size();
    for (const Placement& image : layout.images) {
      const PageRect rect = pagesTouched(image, d, m);
      for (uint64_t y = rect.y0; y <= rect.y1; ++y)
        for (uint64_t x = rect.x0; x <= rect.x1; ++x)
          pages.push_back(absoluteIndex(
              PageId{static_cast<uint32_t>(x), static_cast<uint32_t>(y), m}));
    }
    std::sort(pages.begin() + static_cast<long>(levelStart), pages.end());
    pages.erase(std::unique(pages.begin() + static_cast<long>(levelStart), pages.end()),
                pages.end());
  }
  return pages;
}

}  // namespace vt
