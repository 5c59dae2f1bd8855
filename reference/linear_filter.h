#pragma once
// The oracle's texture arithmetic: an RGBA8 texel as texelFetch returns it, and the sampler's
// GL_LINEAR, each as a member of its family (render/arithmetic.h: texel values, GL_LINEAR). Used
// by the renderer and by `vt calibrate`, which compares an implementation's samples with every
// member.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#ifdef __SSE4_1__
#include <smmintrin.h>
#endif

#include "render/arithmetic.h"
#include "shader/shader_cpp.h"

namespace vt::reference {

using shader::ivec2;
using shader::vec2;
using shader::vec4;

// An RGBA8 texel as texelFetch returns it: multiplied by 1/255 (a float constant; docs/design.md
// section 7, rule 9), or divided by 255 (GL 4.5 section 2.3.5.1 as written).
inline vec4 unorm8ToFloat(glm::u8vec4 t) { return vec4(t) * (1.0f / 255.0f); }
inline vec4 unorm8ToFloat(glm::u8vec4 t, UnormConversion conversion) {
  return conversion == UnormConversion::kDivided ? vec4(t) / 255.0f : unorm8ToFloat(t);
}

// The same for four bytes in memory, in one vector conversion where the CPU has SSE4.1 (the same
// values: every byte converts exactly, and each lane multiplies by the same float).
inline vec4 unorm8ToFloat(const uint8_t* texel) {
#ifdef __SSE4_1__
  int32_t packed;
  std::memcpy(&packed, texel, sizeof packed);
  const __m128 converted = _mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(packed)));
  vec4 result;
  _mm_storeu_ps(&result.x, _mm_mul_ps(converted, _mm_set1_ps(1.0f / 255.0f)));
  return result;
#else
  return unorm8ToFloat(glm::u8vec4(texel[0], texel[1], texel[2], texel[3]));
#endif
}

// GL_LINEAR at a texel position (centres at +0.5), clamp to edge, over a texture of `size`
// texels, given as the shader hands it: divided by the size into [0, 1] first.
//   8-bit weights (rule 9): s = round-half-even(u * (size * 256)) - 128, texel s >> 8, weight
//     s & 255, each lerp a + ((f * (b - a) + 128) >> 8) on 8-bit values (or without the + 128:
//     the product floored), in x on both rows, then in y.
//   float weights: x = u * size - 0.5 (or one fma), texel floor(x), weight x - floor(x), texels
//     converted as `conversion` says, lerps a + (b - a) * w (or fma(w, b - a, a)).
//   corner weights (kFixedPointCorners, Filter's comment): integer positions and weights, the
//     weighted sum S of the four texels returned as unorm8, unorm16 or S / (255 2^weightBits).
// sampleLinearAt takes the normalized coordinate u itself.

// kFixedPointCorners along one axis: the whole number q of 2^-weightBits texel the position
// rounds to, for a normalized coordinate u and a side of `size` texels. u 2^coordinateBits is
// truncated (u outside [0, 1] too: the clamp to edge follows), then
// q = round(P 2^weightBits) with P = U size / 2^coordinateBits - 1/2, in 64-bit integers (exact:
// |U| < 2^(coordinateBits + 1) for |u| < 2, size < 2^16).
inline int64_t fixedPointPosition(float u, int size, const Filter& filter) {
  const double scaled = std::floor(static_cast<double>(u) * std::ldexp(1.0, filter.coordinateBits));
  // Far outside the texture every position clamps alike: keep the products in range.
  const double limit = std::ldexp(1.0, filter.coordinateBits + 2);
  const int64_t U = static_cast<int64_t>(std::clamp(scaled, -limit, limit));
  // 2^(coordinateBits - weightBits) (P 2^weightBits) = U size 2^weightBits / 2 ... exactly:
  const int shift = filter.coordinateBits - filter.weightBits;
  const int64_t numerator = U * size - (int64_t{1} << (filter.coordinateBits - 1));
  // numerator / 2^coordinateBits = P; times 2^weightBits: numerator / 2^shift.
  if (shift <= 0) return numerator << (-shift);
  const int64_t half =
      filter.positionRounding == PositionRounding::kHalfUp ? int64_t{1} << (shift - 1) : 0;
  return (numerator + half) >> shift;  // >> of a negative: floor (C++20)
}

// kFixedPointCorners: the four weights (w00, w10, w01, w11) of fractions fx, fy.
inline std::array<int, 4> cornerWeights(int fx, int fy, const Filter& filter) {
  const int one = 1 << filter.weightBits;
  const int half = filter.lerpRounding == LerpRounding::kNearest ? one / 2 : 0;
  const int w11 = (fx * fy + half) >> filter.weightBits;
  return {one - fx - fy + w11, fx - w11, fy - w11, w11};
}

// kFixedPointCorners: the sampler's value of a weighted sum S (units of 1 / 2^weightBits of a
// unorm8 step).
inline float fixedPointOutput(int64_t sum, const Filter& filter) {
  const int64_t one = int64_t{1} << filter.weightBits;
  switch (filter.output) {
    case FilterOutput::kUnorm8:
      return static_cast<float>((sum + one / 2) >> filter.weightBits) / 255.0f;
    case FilterOutput::kUnorm16: {
      const int64_t denominator = 255 * one;
      return static_cast<float>((sum * 65535 + denominator / 2) / denominator) / 65535.0f;
    }
    case FilterOutput::kFloat:
      break;
  }
  return static_cast<float>(static_cast<double>(sum) / static_cast<double>(255 * one));
}

template <class Fetch8>
vec4 sampleLinearAt(const Fetch8& fetch8, vec2 u, ivec2 size, const Filter& filter,
                    UnormConversion conversion = UnormConversion::kTimesReciprocal) {
  if (filter.weights == FilterWeights::kFixedPointCorners) {
    int position[2], fraction[2];
    for (int k = 0; k < 2; ++k) {
      const int64_t q = fixedPointPosition(u[k], size[k], filter);
      const int64_t far = int64_t{size[k] + 1} << filter.weightBits;
      const int64_t clamped = std::clamp<int64_t>(q, -far, far);
      position[k] = static_cast<int>(clamped >> filter.weightBits);
      fraction[k] = static_cast<int>(clamped & ((int64_t{1} << filter.weightBits) - 1));
    }
    const auto at = [&](int dx, int dy) {
      return fetch8(ivec2(std::clamp(position[0] + dx, 0, size.x - 1),
                          std::clamp(position[1] + dy, 0, size.y - 1)));
    };
    const std::array<int, 4> w = cornerWeights(fraction[0], fraction[1], filter);
    const glm::u8vec4 c00 = at(0, 0), c10 = at(1, 0), c01 = at(0, 1), c11 = at(1, 1);
    vec4 result;
    for (int c = 0; c < 4; ++c)
      result[c] = fixedPointOutput(int64_t{w[0]} * c00[c] + int64_t{w[1]} * c10[c] +
                                       int64_t{w[2]} * c01[c] + int64_t{w[3]} * c11[c],
                                   filter);
    return result;
  }
  if (filter.weights == FilterWeights::kFixedPoint8) {
    int position[2], weight[2];
    for (int k = 0; k < 2; ++k) {
      const int s =
          static_cast<int>(std::nearbyint(u[k] * (static_cast<float>(size[k]) * 256.0f))) - 128;
      position[k] = s >> 8;
      weight[k] = s & 255;
    }
    const auto at = [&](int dx, int dy) {
      return fetch8(ivec2(std::clamp(position[0] + dx, 0, size.x - 1),
                          std::clamp(position[1] + dy, 0, size.y - 1)));
    };
    const int half = filter.lerpRounding == LerpRounding::kNearest ? 128 : 0;
    const auto lerp = [half](int a, int b, int f) { return a + ((f * (b - a) + half) >> 8); };
    const glm::u8vec4 c00 = at(0, 0), c10 = at(1, 0), c01 = at(0, 1), c11 = at(1, 1);
    vec4 result;
    for (int c = 0; c < 4; ++c) {
      const int row0 = lerp(c00[c], c10[c], weight[0]), row1 = lerp(c01[c], c11[c], weight[0]);
      result[c] = static_cast<float>(lerp(row0, row1, weight[1])) / 255.0f;
    }
    return result;
  }
  vec2 x;
  for (int k = 0; k < 2; ++k)
    x[k] = filter.fusedCoordinate ? std::fma(u[k], static_cast<float>(size[k]), -0.5f)
                                  : u[k] * static_cast<float>(size[k]) - 0.5f;
  const vec2 base = glm::floor(x);
  const vec2 f = x - base;
  const ivec2 i0(base);
  const auto at = [&](int dx, int dy) {
    return unorm8ToFloat(
        fetch8(ivec2(std::clamp(i0.x + dx, 0, size.x - 1), std::clamp(i0.y + dy, 0, size.y - 1))),
        conversion);
  };
  const auto lerp = [&](vec4 a, vec4 b, float w) {
    if (!filter.fusedLerp) return a + (b - a) * w;
    vec4 r;
    for (int c = 0; c < 4; ++c) r[c] = std::fma(w, b[c] - a[c], a[c]);
    return r;
  };
  const vec4 row0 = lerp(at(0, 0), at(1, 0), f.x);
  const vec4 row1 = lerp(at(0, 1), at(1, 1), f.x);
  return lerp(row0, row1, f.y);
}

template <class Fetch8>
vec4 sampleLinear(const Fetch8& fetch8, vec2 texel, ivec2 size, const Filter& filter,
                  UnormConversion conversion = UnormConversion::kTimesReciprocal) {
  return sampleLinearAt(fetch8, texel / vec2(size), size, filter, conversion);
}

}  // namespace vt::reference
