#include "reference/shader_math.h"

#include <xmmintrin.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace vt::reference {

float polynomialLog2(float x, bool fused) {
  // Rule 8: e = exponent - 127, m = mantissa in [1, 2), y = (m - 1) / (m + 1), z = y * y,
  // P = fma(fma(z*z, c3, c1), z, fma(z*z, fma(z*z, c4, c2), c0)), result fma(y, P, e).
  if (std::isnan(x) || x < 0.0f) return std::bit_cast<float>(0x7fc00000u);
  if (x == std::numeric_limits<float>::infinity()) return x;
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  if ((bits & 0x7f800000u) == 0) return -std::numeric_limits<float>::infinity();  // 0, denormals
  const float e = static_cast<float>(static_cast<int>(bits >> 23) - 127);
  const float m = std::bit_cast<float>((bits & 0x007fffffu) | 0x3f800000u);
  const float y = (m - 1.0f) / (m + 1.0f);
  const float z = y * y;
  const float z2 = z * z;
  const auto [c0, c1, c2, c3, c4] = kLog2Coefficients;
  const auto madd = [fused](float a, float b, float c) {
    return fused ? std::fma(a, b, c) : a * b + c;
  };
  const float p = madd(madd(z2, c3, c1), z, madd(z2, madd(z2, c4, c2), c0));
  return madd(y, p, e);
}

float naturalTimesLog2e(float x) {
  // tgsi_exec's micro_lg2: the C library's logf, then one float multiply by (float)M_LOG2E.
  const float natural = std::log(x);
  return natural * 1.442695f;
}

float log2Of(Log2Form form, float x) {
  switch (form) {
    case Log2Form::kPolynomialFused:
      return polynomialLog2(x, true);
    case Log2Form::kPolynomialUnfused:
      return polynomialLog2(x, false);
    case Log2Form::kNaturalTimesLog2e:
      return naturalTimesLog2e(x);
    case Log2Form::kLibm:
      break;
  }
  return std::log2(x);
}

DenormalMode::DenormalMode(bool flush) : saved_(_mm_getcsr()) {
  constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
  if (flush)
    _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
  else
    _mm_setcsr(saved_ & ~(kFlushToZero | kDenormalsAreZero));
}

DenormalMode::~DenormalMode() { _mm_setcsr(saved_); }

}  // namespace vt::reference
