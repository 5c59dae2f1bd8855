#include "gl/virtual_texture_program.h"

#include "shader/virtual_texture_source.h"

namespace vt {

std::string virtualTextureVertexSource() {
  // Clip-space positions come from the CPU, computed once for both renderers (docs/design.md
  // section 3).
  return R"(#version 450 core
layout(location = 0) in vec4 aClipPosition;
layout(location = 1) in vec2 aUV;
out vec2 vUV;
void main() {
  vUV = aUV;
  gl_Position = aClipPosition;
}
)";
}

std::string virtualTextureFragmentSource() {
  const std::string backend = R"(#version 450 core
uniform usampler2D uIndirection;
uniform sampler2D uCache;
uniform int uFinestLevel;
// The indirection table (thesis 3.2.2.3), every level in level 0 of one texture of
// (3/2 2^L) x 2^L entries, fetched at a constant level: level L at the origin, level m < L at
// (2^L, 2^L - 2^(m+1)), so the levels lie side by side without overlap:
//   +---------------+-------+
//   |               | L - 1 |
//   |       L       +---+---+
//   |               |L-2|
//   +---------------+---+ ...
// (A mipmapped texture fetched at level L - m would do the same, but Mesa 22.3's softpipe fetches
// one level for a whole 2x2 quad: docs/precision-models.md, softpipe.)
uvec4 vtFetchIndirection(ivec2 page, int level) {
  ivec2 origin = (level == uFinestLevel)
                     ? ivec2(0, 0)
                     : ivec2(1 << uFinestLevel, (1 << uFinestLevel) - (2 << level));
  return texelFetch(uIndirection, origin + page, 0);
}
vec4 vtFetchCacheTexel(ivec2 texel) { return texelFetch(uCache, texel, 0); }
vec4 vtSampleCacheLinear(vec2 texel) {
  return textureLod(uCache, texel / vec2(textureSize(uCache, 0)), 0.0);
}
)";
  const std::string main = R"(
in vec2 vUV;
uniform VtParameters uVt;
layout(location = 0) out vec4 outColor;
layout(location = 1) out uvec4 outNeed;
void main() {
  VtFragment f = vtShadeFragment(vUV, dFdxFine(vUV), dFdyFine(vUV), uVt);
  outColor = f.color;
  outNeed = f.need;
}
)";
  return backend + kVirtualTextureShaderSource + main;
}

}  // namespace vt
