#pragma once
// What a virtual texture is: page size, border, levels and texel format (docs/design.md section 2).
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
  // Block-compressed RGBA (S3TC, EXT_texture_compression_s3tc): each 4 x 4 texels of a stored page
  // one block, rows of blocks of increasing t. Pages are read decoded, as unorm8 RGBA.
  kBc1 = 2,  // 8 bytes a block: two RGB565 end points and 2-bit indices; opaque (alpha 255)
  kBc3 = 3,  // 16 bytes a block: 8 of interpolated alpha, then a BC1 colour block
};

// Whether pages of `format` are stored as 4 x 4 blocks.
constexpr bool isBlockCompressed(PixelFormat format) { return format != PixelFormat::kUnorm8; }

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
  uint32_t channels = 4;    // components per texel, 1..4; 4 for the block formats
  PixelFormat format = PixelFormat::kUnorm8;
  ColorSpace colorSpace = ColorSpace::kSrgb;

  uint32_t finestLevel() const { return levelCount - 1; }
  uint64_t sideTexels() const { return levelSide(pageSize, finestLevel()); }
  uint64_t totalPages() const { return pageCount(finestLevel()); }
  uint32_t storedPageSide() const { return pageSize + 2 * border; }
  uint64_t bytesPerTexel() const { return channels * uint64_t{1}; }
  // A stored page as it is read: (P + 2B)^2 texels of `channels` unorm8 components (decoded from
  // its blocks where the format compresses).
  uint64_t pageBytes() const {
    return uint64_t{storedPageSide()} * storedPageSide() * bytesPerTexel();
  }
  // A stored page as it lies in the file and travels from it: pageBytes() for unorm8; for the
  // block formats ((P + 2B) / 4)^2 blocks of 8 (BC1) or 16 (BC3) bytes.
  uint64_t storedPageBytes() const {
    if (!isBlockCompressed(format)) return pageBytes();
    const uint64_t blocks = uint64_t{storedPageSide() / 4} * (storedPageSide() / 4);
    return blocks * (format == PixelFormat::kBc1 ? 8 : 16);
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
