#pragma once
// Comparing an implementation's floats with the oracle's: bit for bit, and in units of 2^-23.

#include <bit>
#include <cmath>
#include <cstdint>

namespace vt::calibrate {

inline constexpr double kFloatUlp = 0x1p-23;

inline bool sameBits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

// The distance of `got` from `exact` in units of the float spacing at `exact` (2^(e - 23) for
// |exact| in [2^e, 2^(e + 1))), the unit of the GLSL precision table.
inline double ulpsFrom(double got, double exact) {
  if (exact == 0.0) return got == 0.0 ? 0.0 : std::fabs(got) / 0x1p-149;
  const double spacing = std::ldexp(1.0, std::ilogb(exact) - 23);
  return std::fabs(got - exact) / spacing;
}

}  // namespace vt::calibrate
