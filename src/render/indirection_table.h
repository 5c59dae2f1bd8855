#pragma once
// The indirection table (thesis 3.2.2.3) as both renderers read it: per page level m, 2^m x 2^m
// entries in page order (p_rel = px + py * 2^m, format/page_address.h). Entry (px, py, m) is
// (fx, fy, i, 0): the cache frame that holds page (px, py, m) or its nearest resident ancestor,
// and that page's level i <= m. The GL path uploads level m into its part of one RGBA16UI texture
// (gl/virtual_texture_program.cpp); the runtime copies it from its page table.

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "format/page_address.h"

namespace vt {

class IndirectionTable {
 public:
  IndirectionTable() = default;
  // Levels 0 .. levelCount - 1, every entry (0, 0, 0, 0): frame (0, 0) holding the root.
  explicit IndirectionTable(uint32_t levelCount) {
    levels_.reserve(levelCount);
    for (uint32_t m = 0; m < levelCount; ++m) levels_.emplace_back(pagesInLevel(m));
  }

  uint32_t levelCount() const { return static_cast<uint32_t>(levels_.size()); }

  glm::u16vec4 entry(PageId page) const { return levels_[page.level][relativeIndex(page)]; }
  void set(PageId page, glm::u16vec4 entry) { levels_[page.level][relativeIndex(page)] = entry; }

  // Level m's entries in page order.
  std::span<const glm::u16vec4> level(uint32_t m) const { return levels_[m]; }
  std::span<glm::u16vec4> level(uint32_t m) { return levels_[m]; }

 private:
  std::vector<std::vector<glm::u16vec4>> levels_;  // [m][px + py * 2^m]
};

}  // namespace vt
