#pragma once
// The needbuffer encodings of the shader (virtual_texture.glsl, thesis 3.2.3.2), read back on the
// CPU: what a pixel without geometry holds, the page a value names, and the pages a whole
// needbuffer names.
//   32-bit: r = px, g = py, b = m, a = 1; no geometry (0, 0, 0, 0).
//   8-bit:  r = px mod 256, g = py mod 256, b = m, a = px / 256 + (py / 256) * 16;
//           no geometry b = 255.
// A value that names no page of any texture (m above kMaxLevel, or px or py outside level m, or
// an 8-bit component above 255) cannot come from the shader: it decodes as no page rather than
// as an address no table holds.

#include <algorithm>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <vector>

#include "format/page_address.h"

namespace vt {

// The finest level the 8-bit encoding can name: 4 bits of a per axis above the 8 of r and g, 2^12
// pages per side.
inline constexpr uint32_t kNeed8FinestLevel = 12;
inline bool need8Encodes(uint32_t finestLevel) { return finestLevel <= kNeed8FinestLevel; }

inline glm::uvec4 needClearValue(bool need8) {
  return need8 ? glm::uvec4(0, 0, 255, 0) : glm::uvec4(0);
}

inline std::optional<PageId> decodeNeed(glm::uvec4 v, bool need8) {
  PageId page{v.x, v.y, v.z};
  if (need8) {
    if (v.z == 255 || glm::any(glm::greaterThan(v, glm::uvec4(255)))) return std::nullopt;
    page = {v.x + (v.w & 15u) * 256u, v.y + (v.w >> 4) * 256u, v.z};
  } else if (v.w == 0) {
    return std::nullopt;
  }
  if (!isValid(page)) return std::nullopt;
  return page;
}

// The distinct pages a needbuffer names (absolute indices, ascending) and its pixels with geometry.
struct NeededPages {
  std::vector<uint64_t> pages;
  uint64_t coveredPixels = 0;
};

inline NeededPages neededPages(std::span<const glm::uvec4> need, bool need8) {
  NeededPages result;
  for (const glm::uvec4& value : need)
    if (const std::optional<PageId> page = decodeNeed(value, need8)) {
      ++result.coveredPixels;
      // Neighbouring pixels mostly name the same page: keep runs once before sorting.
      const uint64_t index = absoluteIndex(*page);
      if (result.pages.empty() || result.pages.back() != index) result.pages.push_back(index);
    }
  std::sort(result.pages.begin(), result.pages.end());
  result.pages.erase(std::unique(result.pages.begin(), result.pages.end()), result.pages.end());
  return result;
}

}  // namespace vt
