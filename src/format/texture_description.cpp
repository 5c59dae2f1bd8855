#include "format/texture_description.h"

#include <bit>

namespace vt {

std::optional<FieldProblem> findProblem(const TextureDescription& d) {
  const auto problem = [](std::string field, std::string text) {
    return std::optional<FieldProblem>(FieldProblem{std::move(field), std::move(text)});
  };
  if (!std::has_single_bit(d.pageSize) || d.pageSize > kMaxPageSize)
    return problem("page_size", std::to_string(d.pageSize) + " is not a power of two in [1, " +
                                    std::to_string(kMaxPageSize) + "]");
  if (d.border >= d.pageSize)
    return problem("border", std::to_string(d.border) + " is not smaller than the page size " +
                                 std::to_string(d.pageSize));
  if (d.levelCount < 1 || d.levelCount > kMaxLevel + 1)
    return problem("level_count", std::to_string(d.levelCount) + " is outside [1, " +
                                      std::to_string(kMaxLevel + 1) + "]");
  if (d.channels < 1 || d.channels > kMaxChannels)
    return problem("channels", std::to_string(d.channels) + " is outside [1, " +
                                   std::to_string(kMaxChannels) + "]");
  if (d.format != PixelFormat::kUnorm8 && d.format != PixelFormat::kBc1 &&
      d.format != PixelFormat::kBc3)
    return problem("pixel_format", std::to_string(static_cast<uint32_t>(d.format)) +
                                       " is not a known pixel format (1 = unorm8, 2 = bc1, 3 = bc3)");
  if (isBlockCompressed(d.format) && d.channels != 4)
    return problem("channels", std::to_string(d.channels) + " with pixel format " +
                                   toString(d.format) + ", which stores 4");
  if (isBlockCompressed(d.format) && d.storedPageSide() % 4 != 0)
    return problem("border", "stored pages of " + std::to_string(d.storedPageSide()) +
                                 " texels (P + 2B) are not whole 4 x 4 blocks of pixel format " +
                                 toString(d.format));
  if (d.colorSpace != ColorSpace::kLinear && d.colorSpace != ColorSpace::kSrgb)
    return problem("color_space", std::to_string(static_cast<uint32_t>(d.colorSpace)) +
                                      " is not a known color space (0 = linear, 1 = sRGB)");
  return std::nullopt;
}

std::string toString(PixelFormat format) {
  switch (format) {
    case PixelFormat::kUnorm8:
      return "unorm8";
    case PixelFormat::kBc1:
      return "bc1";
    case PixelFormat::kBc3:
      return "bc3";
  }
  return "unknown";
}

std::string toString(ColorSpace colorSpace) {
  return colorSpace == ColorSpace::kSrgb ? "sRGB" : "linear";
}

}  // namespace vt
