#pragma once
// The framebuffer's conversion of a shaded float colour channel to RGBA8, as a member of its family
// (render/arithmetic.h, ColourConversion). lane_shading.h converts eight lanes at once for the
// nearest member and calls these for the others.

#include <cmath>
#include <cstdint>

#include "render/arithmetic.h"

namespace vt::reference {

// The framebuffer's conversion: clamp, then round to nearest even. NaN becomes 0.
inline uint8_t toUnorm8(float c) {
  const float clamped = c >= 0.0f ? (c <= 1.0f ? c : 1.0f) : 0.0f;
  return static_cast<uint8_t>(std::nearbyint(clamped * 255.0f));
}

// The framebuffer's conversion as `conversion` says (render/arithmetic.h, ColourConversion):
// clamped alike, then rounded to nearest even or quantized: (255 floor(c 2^bits) + bias) >> bits.
inline uint8_t toUnorm8(float c, const ColourConversion& conversion) {
  if (conversion.rule == ColourConversionRule::kNearest) return toUnorm8(c);
  const float clamped = c >= 0.0f ? (c <= 1.0f ? c : 1.0f) : 0.0f;
  const int64_t k = static_cast<int64_t>(std::ldexp(static_cast<double>(clamped), conversion.bits));
  return static_cast<uint8_t>((255 * k + conversion.bias) >> conversion.bits);
}

}  // namespace vt::reference
