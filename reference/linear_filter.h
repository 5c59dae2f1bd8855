#pragma once
// The oracle's texture arithmetic: an RGBA8 texel as texelFetch returns it, and the sampler's
// GL_LINEAR, each as a member of its family (render/arithmetic.h: texel values, GL_LINEAR). Used
// by the renderer and by `vt calibrate`, which compares an implementation's samples with every
// member.

#include <algorithm>
#include <cmath>
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

// An RGBA8 texel as texelFetch returns it: multiplied by 1/255 (a float constant; DESIGN section
// 7, rule 9), or divided by 255 (GL 4.5 section 2.3.5.1 as written).
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
// sampleLinearAt takes the normalized coordinate u itself.
template <class Fetch8>
vec4 sampleLinearAt(const Fetch8& fetch8, vec2 u, ivec2 size, const Filter& filter,
                    UnormConversion conversion = UnormConversion::kTimesReciprocal) {
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
