// The shared shader logic, compiled as C++, against values derived by hand from the thesis's
// formulas and docs/design.md section 3.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "format/page_address.h"
#include "shader/shader_cpp.h"

namespace vt::shader {
namespace {

// A backend with an identity-like cache: every page is resident in the frame (px, py) of its own
// level, and a cache texel's colour encodes its coordinates.
struct ToyBackend {
  int residentLevelCap = 15;  // pages finer than this fall back to their ancestor on this level
  float log2(float x) { return std::log2(x); }
  float sqrt(float x) { return std::sqrt(x); }
  uvec4 vtFetchIndirection(ivec2 page, int level) {
    const int i = level < residentLevelCap ? level : residentLevelCap;
    return uvec4(uint(page.x >> (level - i)), uint(page.y >> (level - i)), uint(i), 0u);
  }
  vec4 vtFetchCacheTexel(ivec2 texel) {
    return vec4(static_cast<float>(texel.x), static_cast<float>(texel.y), 0.0f, 1.0f);
  }
  vec4 vtSampleCacheLinear(vec2 texel) { return vec4(texel.x, texel.y, 0.0f, 1.0f); }
};

using Logic = ShaderLogic<ToyBackend>;

VtParameters parameters(int pageSize, int border, int finestLevel) {
  VtParameters p{};
  p.pageSize = pageSize;
  p.border = border;
  p.finestLevel = finestLevel;
  p.trilinear = 0;
  p.exactFilter = 1;
  p.need8 = 0;
  p.cacheSize = vec2(4096.0f, 4096.0f);
  return p;
}

TEST(VirtualTextureShader, HeckbertLodFollowsAppendixB) {
  Logic logic;
  const VtParameters p = parameters(128, 4, 5);  // finest level 4096 texels wide
  // One finest texel per pixel: e_max * 4096 = 1, d = 0, lod = L.
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(1.0f / 4096, 0), vec2(0, 1.0f / 4096), p), 5.0f);
  // Four finest texels per pixel along y, one along x: e_max from the longer edge, d = 2.
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(1.0f / 4096, 0), vec2(0, 4.0f / 4096), p), 3.0f);
  // The edge length is sqrt(s'^2 + t'^2): (3, 4) / 4096 has length 5 texels, d = log2(5).
  EXPECT_FLOAT_EQ(logic.vtLevelOfDetail(vec2(3.0f / 4096, 4.0f / 4096), vec2(0, 0), p),
                  5.0f - std::log2(5.0f));
  // Clamped at both ends: magnification to L, minification beyond the root to 0.
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(1e-6f, 0), vec2(0, 1e-6f), p), 5.0f);
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(0.9f, 0), vec2(0, 0.9f), p), 0.0f);
}

TEST(VirtualTextureShader, AReducedNeedbufferCompensatesItsLargerDerivativesExactly) {
  // At 1/2^k of the resolution the derivatives are 2^k times larger; the LOD divides them back.
  Logic logic;
  VtParameters full = parameters(128, 4, 5), reduced = full;
  for (int k = 1; k <= 3; ++k) {
    reduced.needScaleLog2 = k;
    const float scale = static_cast<float>(1 << k);
    for (const vec2 dx : {vec2(1.0f / 4096, 0), vec2(3e-4f, 1.7e-5f), vec2(0.013f, 0.002f)})
      for (const vec2 dy : {vec2(0, 1.0f / 4096), vec2(2.9e-5f, 4e-4f), vec2(0, 0)})
        EXPECT_EQ(logic.vtLevelOfDetail(dx * scale, dy * scale, reduced),
                  logic.vtLevelOfDetail(dx, dy, full))
            << "k " << k;
  }
}

TEST(VirtualTextureShader, DegenerateDerivativesHaveDefinedLevels) {
  Logic logic;
  const VtParameters p = parameters(128, 4, 5);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(0, 0), vec2(0, 0), p), 5.0f);    // log2(0) = -Inf: finest
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(nan, 0), vec2(0, 0), p), 0.0f);  // NaN: coarsest
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(0, 0), vec2(0, nan), p), 0.0f);
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(1e-3f, 0), vec2(nan, nan), p), 0.0f);
  EXPECT_EQ(logic.vtLevelOfDetail(vec2(inf, 0), vec2(0, 0), p), 0.0f);
}

TEST(VirtualTextureShader, PagesClampAtTheTexturesEdge) {
  Logic logic;
  EXPECT_EQ(logic.vtPageAt(vec2(0.0f, 0.0f), 3), ivec2(0, 0));
  EXPECT_EQ(logic.vtPageAt(vec2(1.0f, 1.0f), 3), ivec2(7, 7));  // s = 1.0 is in the last page
  EXPECT_EQ(logic.vtPageAt(vec2(0.5f, 0.49999997f), 1), ivec2(1, 0));
  EXPECT_EQ(logic.vtPageAt(vec2(0.375f, 0.624f), 3), ivec2(3, 4));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(logic.vtPageAt(vec2(nan, -3.0f), 4), ivec2(0, 0));
  EXPECT_EQ(logic.vtPageAt(vec2(std::numeric_limits<float>::infinity(), 2.0f), 4), ivec2(15, 15));
}

// The C++ page index the result sets and the crosscheck use (format/page_address.h, pageAt) is
// the shader's vtPageAt: on every page boundary of a level, a float step either side of it, 0,
// -0, 1 and the float just below it, negative values, values above 1, infinities, NaN and the
// smallest denormal, at levels 0 to 15.
TEST(VirtualTextureShader, TheCppPageIndexIsTheShadersAtEveryEdge) {
  Logic logic;
  const float inf = std::numeric_limits<float>::infinity();
  for (const int level : {0, 1, 2, 3, 5, 8, 11, 15}) {
    std::vector<float> coordinates = {0.0f,
                                      -0.0f,
                                      1.0f,
                                      std::nextafter(1.0f, 0.0f),
                                      -1e-30f,
                                      -0.5f,
                                      -1.0f,
                                      -inf,
                                      1.5f,
                                      2.0f,
                                      1e30f,
                                      inf,
                                      std::numeric_limits<float>::quiet_NaN(),
                                      std::numeric_limits<float>::denorm_min()};
    const int pages = 1 << level;
    const int step = std::max(1, pages / 64);  // every boundary up to level 6, then 64 of them
    for (int k = 0; k <= pages; k += step) {
      const float boundary = std::ldexp(static_cast<float>(k), -level);
      coordinates.insert(coordinates.end(),
                         {boundary, std::nextafter(boundary, -inf), std::nextafter(boundary, inf)});
    }
    for (const float s : coordinates) {
      const ivec2 shader = logic.vtPageAt(vec2(s, s), level);
      EXPECT_EQ(pageAt(s, level), shader.x) << "s = " << s << " at level " << level;
      EXPECT_EQ(shader.x, shader.y);
    }
  }
  // The page a boundary starts, and the last page for s = 1.0, by hand.
  EXPECT_EQ(pageAt(0.25f, 2), 1);
  EXPECT_EQ(pageAt(std::nextafter(0.25f, 0.0f), 2), 0);
  EXPECT_EQ(pageAt(1.0f, 4), 15);
  EXPECT_EQ(pageAt(-0.0f, 4), 0);
}

TEST(VirtualTextureShader, NeedbufferEncodings) {
  Logic logic;
  EXPECT_EQ(logic.vtEncodeNeed32(ivec2(70000, 3), 15), uvec4(70000u, 3u, 15u, 1u));
  // Thesis 3.2.3.2: r = px mod 256, g = py mod 256, b = m, a = px / 256 + (py / 256) * 16.
  EXPECT_EQ(logic.vtEncodeNeed8(ivec2(4095, 300), 12), uvec4(255u, 44u, 12u, 15u + 16u * 1u));
  EXPECT_EQ(logic.vtEncodeNeed8(ivec2(0, 0), 0), uvec4(0u, 0u, 0u, 0u));
}

TEST(VirtualTextureShader, CacheTexelAddsFrameBorderAndInternalOffset) {
  Logic logic;
  const VtParameters p = parameters(128, 4, 5);
  // s = 0.3, level 2: page 1 (0.25..0.5), internal offset 0.2 * 128 = 25.6 texels, in frame
  // (3, 1) of 136 texels: 3 * 136 + 4 + 25.6 = 437.6.
  const vec2 texel = logic.vtCacheTexel(vec2(0.3f, 0.25f), ivec2(1, 1), 2, uvec4(3, 1, 2, 0), p);
  EXPECT_NEAR(texel.x, 437.6f, 1e-4f);
  EXPECT_EQ(texel.y, 136.0f + 4.0f);  // t = 0.25 is the top edge of page row 1
  // An ancestor two levels up: page (5, 2) of level 3 falls back to page (1, 0) of level 1, and
  // the internal offset is measured on level 1: s = 0.7 -> 1.4 - 1 = 0.4.
  const vec2 up = logic.vtCacheTexel(vec2(0.7f, 0.3f), ivec2(5, 2), 3, uvec4(0, 0, 1, 0), p);
  EXPECT_NEAR(up.x, 4.0f + 0.4f * 128.0f, 1e-4f);
  EXPECT_NEAR(up.y, 4.0f + 0.6f * 128.0f, 1e-4f);
  // s = 1.0 on the last page lies on the page's right edge, inside the border.
  const vec2 edge = logic.vtCacheTexel(vec2(1.0f, 1.0f), ivec2(3, 3), 2, uvec4(0, 0, 2, 0), p);
  EXPECT_EQ(edge, vec2(132.0f, 132.0f));
}

TEST(VirtualTextureShader, ExactBilinearInterpolatesTexelCentres) {
  Logic logic;
  // At a texel centre the filter returns that texel; halfway between centres the mean.
  EXPECT_EQ(logic.vtBilinearExact(vec2(10.5f, 20.5f)), vec4(10, 20, 0, 1));
  EXPECT_EQ(logic.vtBilinearExact(vec2(11.0f, 21.0f)), vec4(10.5f, 20.5f, 0, 1));
}

TEST(VirtualTextureShader, TrilinearBlendsTheTwoLevelsAroundTheLod) {
  Logic logic;
  VtParameters p = parameters(16, 1, 3);  // 128 texels at the finest level
  p.trilinear = 1;
  // Derivatives of 2 finest texels per pixel: lod = 3 - 1 = 2 exactly: needs level 2, weight 0.
  const Logic::VtFragment f =
      logic.vtShadeFragment(vec2(0.5f, 0.5f), vec2(2.0f / 128, 0), vec2(0, 0), p);
  EXPECT_EQ(f.lod, 2.0f);
  EXPECT_EQ(f.neededLevel, 2);
  EXPECT_EQ(f.need, uvec4(2u, 2u, 2u, 1u));
  // sqrt(2) texels per pixel: lod = 2.5, needs level 3; the colour blends levels 2 and 3 halfway.
  const Logic::VtFragment g =
      logic.vtShadeFragment(vec2(0.5f, 0.5f), vec2(std::sqrt(2.0f) / 128, 0), vec2(0, 0), p);
  EXPECT_NEAR(g.lod, 2.5f, 1e-6f);
  EXPECT_EQ(g.neededLevel, 3);
  EXPECT_EQ(g.residentLevel, 3);
  // Fall back: nothing finer than level 1 resident: the fragment samples level 1 for both.
  Logic limited;
  limited.residentLevelCap = 1;
  EXPECT_EQ(
      limited.vtShadeFragment(vec2(0.5f, 0.5f), vec2(2.0f / 128, 0), vec2(0, 0), p).residentLevel,
      1);
}

}  // namespace
}  // namespace vt::shader
