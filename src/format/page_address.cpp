#include "format/page_address.h"

namespace vt {

std::vector<PageId> ancestors(PageId page) {
  std::vector<PageId> path;
  path.reserve(page.level);
  for (uint32_t level = page.level; level-- > 0;) path.push_back(ancestorAt(page, level));
  return path;
}

}  // namespace vt
