#pragma once
// What a virtual texture is: page size, border, levels and texel format (DESIGN section 2).
//
// A stored page is the page's P x P texels surrounded by B texels of its neighbours on every side,
// (P + 2B)^2 texels in rows of increasing t, each texel `channels` components of the pixel format:
//
//     <------- P + 2B ------->
//     +----------------------+  ^
//     |  border (B rows)     |  |
//     |   +--------------+   |  |
//     |   | page P x P   |   |  P + 2B
//     |   +--------------+   |  |
//     |                      |  |
//     +----------------------+  v

#include <cstdint>
#include <optional>
#include <string>

#include "format/page_address.h"

namespace vt {

enum class PixelFormat : uint32_t {
  kUnorm8 = 1,  // one byte per component, 0..255 meaning 0..1
};

enum class ColorSpace : uint32_t {
  kLinear = 0,
  kSrgb = 1,  // components are sRGB-encoded (the usual case for color textures)
};

// Limits every file must respect; each is checked on open and on write.
inline constexpr uint32_t kMaxPageSize = 4096;
inline constexpr uint32_t kMaxChannels = 4;

struct TextureDescription {
  uint32_t pageSize = 128;  // P, a power of two
  uint32_t border = 4;      // B, texels of the neighbouring pages on each side, B < P
  uint32_t levelCount = 1;  // L + 1: levels 0 (coarsest, one page) .. L (finest)
  uint32_t channels = 4;    // components per texel, 1..4
  PixelFormat format = PixelFormat::kUnorm8;
  ColorSpace colorSpace = ColorSpace::kSrgb;

  uint32_t finestLevel() const { return levelCount - 1; }
  uint64_t sideTexels() const { return levelSide(pageSize, finestLevel()); }
  uint64_t totalPages() const { return pageCount(finestLevel()); }
  uint32_t storedPageSide() const { return pageSize + 2 * border; }
  uint64_t bytesPerTexel() const { return channels * uint64_t{1}; }
  uint64_t pageBytes() const {
    return uint64_t{storedPageSide()} * storedPageSide() * bytesPerTexel();
  }

  friend bool operator==(const TextureDescription&, const TextureDescription&) = default;
};

// A field that violates the limits, named as in the file header, with what is wrong with it.
struct FieldProblem {
  std::string field;
  std::string problem;
};

// The first field of `description` outside the limits above, or nothing when all are valid.
std::optional<FieldProblem> findProblem(const TextureDescription& description);

std::string toString(PixelFormat format);
std::string toString(ColorSpace colorSpace);

}  // namespace vt
