#pragma once
// The shared shader logic (virtual_texture.glsl) compiled as C++: GLSL's types and built-ins are
// GLM's, `precise` is empty (the build never contracts or reassociates floating point:
// -ffp-contract=off, no -ffast-math), and the functions become members of ShaderLogic<Backend>,
// whose Backend supplies the texture fetches and the target's log2 and sqrt (a precision
// profile). The per-fragment types (vfloat, vint, vuint, vbool) are one value each here;
// shader/shader_lanes.h compiles the same file over SIMD lanes, one fragment per lane.
//
// Backend must provide, callable on a non-const object:
//   uvec4 vtFetchIndirection(ivec2 page, int level);
//   vec4  vtFetchCacheTexel(ivec2 texel);
//   vec4  vtSampleCacheLinear(vec2 texel);
//   float log2(float x);
//   float sqrt(float x);

#include <cstdint>
#include <glm/glm.hpp>

namespace vt::shader {

using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = uint32_t;
using glm::ceil;
using glm::floor;
using glm::ldexp;
using glm::mix;
using glm::sqrt;

#define VT_CPP
#define precise
#include "shader/virtual_texture_types.glsl"
#undef precise

template <class Backend>
class ShaderLogic : public Backend {
 public:
  using Backend::Backend;
  using Backend::log2;
  using Backend::sqrt;
  using Backend::vtFetchCacheTexel;
  using Backend::vtFetchIndirection;
  using Backend::vtSampleCacheLinear;

  // One fragment per call.
  using vfloat = float;
  using vint = int;
  using vuint = uint;
  using vbool = bool;

#define precise
#include "shader/virtual_texture.glsl"
#undef precise
};

#undef VT_CPP

}  // namespace vt::shader
