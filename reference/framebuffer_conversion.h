#pragma once
// The framebuffer's conversion of a shaded float colour channel to RGBA8, as a member of its family
// (render/arithmetic.h, ColourConversion). lane_shading.h converts eight lanes at once for the
// nearest member and calls these for the others.

#include <cmath>
#include <cstdint>

#include "render/arithmetic.h"

namespace vt::reference {

// A colour channel clamped to [0, 1]; NaN becomes 0.
inline float clampedUnit(float c) { return c >= 0.0f ? (c <= 1.0f ? c : 1.0f) : 0.0f; }

// The framebuffer's conversion: clamp, then round to nearest even. NaN becomes 0.
inline uint8_t toUnorm8(float c) {
  return static_cast<uint8_t>(std::nearbyint(clampedUnit(c) * 255.0f));
}

// The quantized member at x in [0, 1]: (255 floor(x 2^bits) + bias) >> bits, in double (exact for
// bits <= 24). It does not decrease with x, so the result sets bound an interval by its ends.
inline int quantizedUnorm8(double x, const ColourConversion& conversion) {
  const double k = std::floor(std::ldexp(x, conversion.bits));
  return static_cast<int>(std::floor(std::ldexp(255 * k + conversion.bias, -conversion.bits)));
}

// The framebuffer's conversion as `conversion` says (render/arithmetic.h, ColourConversion):
// clamped alike, then rounded to nearest even or quantized.
inline uint8_t toUnorm8(float c, const ColourConversion& conversion) {
  if (conversion.rule == ColourConversionRule::kNearest) return toUnorm8(c);
  return static_cast<uint8_t>(quantizedUnorm8(static_cast<double>(clampedUnit(c)), conversion));
}

}  // namespace vt::reference
