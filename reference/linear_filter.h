#pragma once
// The oracle's texture arithmetic: an RGBA8 texel as texelFetch returns it, and the sampler's
// GL_LINEAR under each arithmetic (DESIGN section 7, rule 9). Used by the renderer and by
// `vt calibrate`, which compares an implementation's samples with both.

#include <algorithm>
#include <cmath>
#include <cstring>

#ifdef __SSE4_1__
#include <smmintrin.h>
#endif

#include "render/precision_profile.h"
#include "shader/shader_cpp.h"

namespace vt::reference {

using shader::ivec2;
using shader::vec2;
using shader::vec4;

// An RGBA8 texel as texelFetch returns it: llvmpipe multiplies by 1/255 (a float constant) rather
// than dividing by 255.
inline vec4 unorm8ToFloat(glm::u8vec4 t) { return vec4(t) * (1.0f / 255.0f); }

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
//   llvmpipe (rule 9): s = round-half-even(u * (size * 256)) - 128, texel s >> 8, weight s & 255,
//     each lerp a + ((f * (b - a) + 128) >> 8) on 8-bit values, in x on both rows, then in y.
//   exact, nvidia: the same positions in float, lerps in float.
template <class Fetch8>
vec4 sampleLinear(const Fetch8& fetch8, vec2 texel, ivec2 size, PrecisionProfile profile) {
  const vec2 u = texel / vec2(size);
  if (profile == PrecisionProfile::kLlvmpipe) {
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
    const auto lerp = [](int a, int b, int f) { return a + ((f * (b - a) + 128) >> 8); };
    const glm::u8vec4 c00 = at(0, 0), c10 = at(1, 0), c01 = at(0, 1), c11 = at(1, 1);
    vec4 result;
    for (int c = 0; c < 4; ++c) {
      const int row0 = lerp(c00[c], c10[c], weight[0]), row1 = lerp(c01[c], c11[c], weight[0]);
      result[c] = static_cast<float>(lerp(row0, row1, weight[1])) / 255.0f;
    }
    return result;
  }
  const vec2 x = u * vec2(size) - vec2(0.5f);
  const vec2 base = glm::floor(x);
  const vec2 f = x - base;
  const ivec2 i0(base);
  const auto at = [&](int dx, int dy) {
    return unorm8ToFloat(
        fetch8(ivec2(std::clamp(i0.x + dx, 0, size.x - 1), std::clamp(i0.y + dy, 0, size.y - 1))));
  };
  const vec4 row0 = at(0, 0) + (at(1, 0) - at(0, 0)) * f.x;
  const vec4 row1 = at(0, 1) + (at(1, 1) - at(0, 1)) * f.x;
  return row0 + (row1 - row0) * f.y;
}

}  // namespace vt::reference
