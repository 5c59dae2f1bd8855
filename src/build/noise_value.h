#pragma once
// NoiseValue of a page (thesis 3.3.1.2): how much a page adds over its parent. The quarter of the
// parent that covers the page is upsampled to page size by bilinear filtering, both are turned
// into luminance, and the NoiseValue is the RMSE between them (appendix A.1), on values in [0, 1].
//
// Luminance is Rec. 709's Y = 0.2126 R + 0.7152 G + 0.0722 B of the stored components (1 and 2
// channels: the first component), computed on the values as stored (sRGB-encoded ones included),
// because that is what the renderer shows and what a viewer compares.

#include <cstddef>
#include <span>

#include "format/page_address.h"
#include "format/texture_description.h"

namespace vt {

// Rec. 709 luminance of one texel of `channels` unorm8 components, each divided by `unit` first:
// 255 gives [0, 1] (the NoiseValue's), 1 gives [0, 255] (the ancestor errors'). 1 and 2 channels:
// the first component.
inline float texelLuminance(const std::byte* texel, uint32_t channels, float unit) {
  const auto c = [&](int k) { return static_cast<float>(std::to_integer<int>(texel[k])) / unit; };
  return channels >= 3 ? 0.2126f * c(0) + 0.7152f * c(1) + 0.0722f * c(2) : c(0);
}

// `page` and `parentPage` are stored pages ((P + 2B)^2 texels, with borders) of `child` and of its
// parent. The parent's border supplies the neighbours that bilinear filtering needs at the edge of
// the quarter; with B = 0 the parent's edge texels are repeated.
float noiseValue(const TextureDescription& description, PageId child,
                 std::span<const std::byte> page, std::span<const std::byte> parentPage);

}  // namespace vt
