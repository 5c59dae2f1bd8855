#pragma once
// The shared shader logic (virtual_texture.glsl) compiled as C++ over eight SIMD lanes, one
// fragment per lane (shader/lanes.h): the same source as ShaderLogic (shader/shader_cpp.h), with
// vfloat, vint, vuint, vbool and GLSL's vectors as lane types. Uniform values (VtParameters and
// what the source computes from them alone) stay scalar. Compiled for AVX2 like the lanes: call
// only where lanes::lanesAvailable().
//
// Backend must provide, callable on a non-const object:
//   lanes::UVec4  vtFetchIndirection(lanes::IVec2 page, lanes::Int8 level);
//   lanes::Vec4   vtFetchCacheTexel(lanes::IVec2 texel);
//   lanes::Vec4   vtSampleCacheLinear(lanes::Vec2 texel);
//   lanes::Float8 log2(lanes::Float8 x);
//   lanes::Float8 sqrt(lanes::Float8 x);

#include "shader/lanes.h"
#include "shader/shader_cpp.h"

VT_LANES_BEGIN

namespace vt::shader {

template <class Backend>
class LaneShaderLogic : public Backend {
 public:
  using Backend::Backend;
  using Backend::log2;
  using Backend::sqrt;
  using Backend::vtFetchCacheTexel;
  using Backend::vtFetchIndirection;
  using Backend::vtSampleCacheLinear;

  // One fragment per lane.
  using vfloat = lanes::Float8;
  using vint = lanes::Int8;
  using vuint = lanes::Uint8;
  using vbool = lanes::Bool8;
  using vec2 = lanes::Vec2;
  using vec4 = lanes::Vec4;
  using ivec2 = lanes::IVec2;
  using uvec4 = lanes::UVec4;

#define VT_CPP
#define precise
#include "shader/virtual_texture.glsl"
#undef precise
#undef VT_CPP
};

}  // namespace vt::shader

VT_LANES_END
