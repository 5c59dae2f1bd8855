#pragma once
// Comparing an implementation's floats with the oracle's: bit for bit, and in units of 2^-23.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace vt::calibrate {

inline constexpr double kFloatUlp = 0x1p-23;

inline bool sameBits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

// How many floats lie between a and b (0 for +0 and -0), at most `cap`; `cap` for NaN.
inline double floatsBetween(float a, float b, double cap) {
  if (std::isnan(a) || std::isnan(b)) return cap;
  const auto ordered = [](float f) {
    const int32_t i = std::bit_cast<int32_t>(f);
    return i >= 0 ? int64_t{i} : -int64_t{i & 0x7fffffff};
  };
  const int64_t d = ordered(a) - ordered(b);
  return std::min(cap, static_cast<double>(d < 0 ? -d : d));
}

// The distance of `got` from `exact` in units of the float spacing at `exact` (2^(e - 23) for
// |exact| in [2^e, 2^(e + 1))), the unit of the GLSL precision table.
inline double ulpsFrom(double got, double exact) {
  if (exact == 0.0) return got == 0.0 ? 0.0 : std::fabs(got) / 0x1p-149;
  const double spacing = std::ldexp(1.0, std::ilogb(exact) - 23);
  return std::fabs(got - exact) / spacing;
}

}  // namespace vt::calibrate
