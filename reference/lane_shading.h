#pragma once
// The oracle's shading of eight pixels at once: the shared shader logic over SIMD lanes
// (shader/shader_lanes.h), one pixel per lane, on the texture views of shader_backends.h. The
// shader's arithmetic runs lane-wide; the indirection lookups and texel reads are made lane by
// lane through the same one-pixel backends, and their texels converted lane-wide. Every lane gets
// the bits the one-pixel shader (ShaderLogic) gets for its pixel: the renderer uses either, and
// tests compare them frame by frame.
//
// Compiled for AVX2 (shader/lanes.h): call only where lanes::lanesAvailable().

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>

#include "reference/framebuffer_conversion.h"
#include "reference/shader_math.h"
#include "reference/triangle_setup.h"
#include "render/arithmetic.h"
#include "shader/shader_lanes.h"

namespace vt::reference {

// One call's pixels: the shader's inputs per lane, and which lanes hold a pixel to shade.
struct LaneFragments {
  float u[lanes::kLanes], v[lanes::kLanes];
  float dudx[lanes::kLanes], dvdx[lanes::kLanes], dudy[lanes::kLanes], dvdy[lanes::kLanes];
  bool active[lanes::kLanes];
};

// What the shader returned per lane: the framebuffer's bytes of the colour, the needbuffer value,
// the LOD and the level actually sampled (-1 when only the needbuffer was computed).
struct LaneResults {
  uint8_t color[lanes::kLanes][4];
  uint32_t need[lanes::kLanes][4];
  float lod[lanes::kLanes];
  int32_t neededLevel[lanes::kLanes];
  int32_t residentLevel[lanes::kLanes];
};

VT_LANES_BEGIN

namespace lane_detail {

inline lanes::Float8 load(const float* values) {
  lanes::Float8 result;
  std::memcpy(&result.v, values, sizeof result.v);
  return result;
}

// The framebuffer's conversion (toUnorm8, shader_backends.h): clamp (NaN to 0), times 255, round
// to nearest even.
inline lanes::Int8 toUnorm8(lanes::Float8 c) {
  const lanes::Float8 below = mix(lanes::Float8(1.0f), c, c <= lanes::Float8(1.0f));
  const lanes::Float8 clamped = mix(lanes::Float8(0.0f), below, c >= lanes::Float8(0.0f));
  return lanes::Int8(nearbyint(clamped * lanes::Float8(255.0f)));
}

// a * b + c, as one fused operation or as a product and a sum.
inline lanes::Float8 multiplyAdd(lanes::Float8 a, lanes::Float8 b, lanes::Float8 c, bool fused) {
  if (!fused) return a * b + c;
  return reinterpret_cast<lanes::f32x8>(_mm256_fmadd_ps(
      reinterpret_cast<__m256>(a.v), reinterpret_cast<__m256>(b.v), reinterpret_cast<__m256>(c.v)));
}

// polynomialLog2 (reference/shader_math.h) lane-wide, step by step the same operations.
inline lanes::Float8 polynomialLog2(lanes::Float8 x, bool fused) {
  using lanes::Float8;
  using lanes::Int8;
  const Int8 bits = reinterpret_cast<lanes::i32x8>(x.v);
  const Float8 e(
      Int8(reinterpret_cast<lanes::i32x8>(reinterpret_cast<lanes::u32x8>(bits.v) >> 23)) -
      Int8(127));
  const Float8 m = reinterpret_cast<lanes::f32x8>(((bits & Int8(0x007fffff)) | 0x3f800000).v);
  const Float8 one(1.0f);
  const Float8 y = (m - one) / (m + one);
  const Float8 z = y * y;
  const Float8 z2 = z * z;
  const Float8 c0(kLog2Coefficients[0]), c1(kLog2Coefficients[1]), c2(kLog2Coefficients[2]),
      c3(kLog2Coefficients[3]), c4(kLog2Coefficients[4]);
  const Float8 p = multiplyAdd(multiplyAdd(z2, c3, c1, fused), z,
                               multiplyAdd(z2, multiplyAdd(z2, c4, c2, fused), c0, fused), fused);
  Float8 result = multiplyAdd(y, p, e, fused);
  // The scalar function's special cases, the first that applies winning: NaN or negative x
  // gives NaN, +Inf itself, zero and denormals -Inf.
  const float inf = std::numeric_limits<float>::infinity();
  const lanes::Bool8 expZero{(bits & Int8(0x7f800000)).v == 0};
  result = mix(result, Float8(-inf), expZero);
  result = mix(result, Float8(inf), lanes::Bool8{x.v == Float8(inf).v});
  const lanes::Bool8 nanOrNegative{(x.v != x.v) | (x.v < Float8(0.0f).v)};
  return mix(result, Float8(std::bit_cast<float>(0x7fc00000u)), nanOrNegative);
}

// evaluatePlane (reference/triangle_setup.h) at eight pixels (x, y), step by step the same
// operations; (x0, y0) is each pixel's quad origin and oddX, oddY say whether it lies in the quad's
// right column or upper row (the quad-stepped form's steps).
inline lanes::Float8 evaluatePlane(const Plane& plane, lanes::Float8 x, lanes::Float8 y,
                                   lanes::Float8 x0, lanes::Float8 y0, lanes::Bool8 oddX,
                                   lanes::Bool8 oddY, PlaneEvaluation evaluation) {
  using lanes::Float8;
  const Float8 a0(plane.a0), dadx(plane.dadx), dady(plane.dady);
  if (evaluation == PlaneEvaluation::kQuadStepped) {
    Float8 value = (a0 + dadx * x0) + dady * y0;
    value = mix(value, value + dadx, oddX);
    return mix(value, value + dady, oddY);
  }
  if (evaluation == PlaneEvaluation::kFused)
    return multiplyAdd(dady, y, multiplyAdd(dadx, x, a0, true), true);
  return dady * y + (dadx * x + a0);
}

}  // namespace lane_detail

// attributesAt (reference/triangle_setup.h) of `t` at the eight pixels of the quads at (qx, qy)
// and (qx + 2, qy), qx and qy even, helpers included: lane 4 h + k is pixel k of quad h, (qx + 2 h
// + (k & 1), qy + (k >> 1)). Each lane's (u, v) are the bits the one-pixel function gives.
inline void quadPairAttributes(const SetupTriangle& t, int qx, int qy,
                               const Arithmetic& arithmetic, float* u, float* v) {
  using lanes::Float8;
  using lanes::Int8;
  const Int8 lane(lanes::i32x8{0, 1, 2, 3, 4, 5, 6, 7});
  const Int8 column = lane & Int8(1), row = (lane >> Int8(1)) & Int8(1);
  const Int8 originX = Int8(qx) + ((lane >> Int8(2)) << Int8(1));
  const Float8 x0(originX), y0(static_cast<float>(qy));
  const Float8 x(originX + column), y(Int8(qy) + row);
  const lanes::Bool8 oddX{column.v != 0}, oddY{row.v != 0};
  const PlaneEvaluation e = arithmetic.planeEvaluation;
  const Float8 q = lane_detail::evaluatePlane(t.oneOverW, x, y, x0, y0, oddX, oddY, e);
  const Float8 s = lane_detail::evaluatePlane(t.s, x, y, x0, y0, oddX, oddY, e);
  const Float8 tt = lane_detail::evaluatePlane(t.t, x, y, x0, y0, oddX, oddY, e);
  Float8 su, tv;
  if (arithmetic.perspective == Perspective::kDivided) {
    su = s / q;
    tv = tt / q;
  } else {
    Float8 recip(0.0f);
    if (arithmetic.reciprocal.table) {  // a measured table: looked up lane by lane
      for (int k = 0; k < 8; ++k) recip.v[k] = arithmetic.reciprocal.of(q[k]);
    } else {
      recip = Float8(1.0f) / q;
    }
    su = s * recip;
    tv = tt * recip;
  }
  std::memcpy(u, &su.v, sizeof su.v);
  std::memcpy(v, &tv.v, sizeof tv.v);
}

// polynomialLog2 of eight values at once (tests compare it with the scalar function).
inline void polynomialLog2EightAtOnce(const float* x, float* out, bool fused) {
  const lanes::Float8 result = lane_detail::polynomialLog2(lane_detail::load(x), fused);
  std::memcpy(out, &result.v, sizeof result.v);
}

// A one-pixel backend (ResidentBackend, CacheBackend) seen by the lanes: each active lane's lookup
// and reads through it in turn, remembering the page each lane's lookup named for its reads.
template <class Scalar>
class LaneBackend {
 public:
  LaneBackend(Scalar& scalar, const Arithmetic& arithmetic, const bool* active)
      : scalar_(scalar),
        conversion_(arithmetic.texelConversion),
        log2Form_(arithmetic.log2),
        log2Table_(arithmetic.log2Table),
        sqrt_(arithmetic.sqrt),
        active_(active) {}

  // The log2 member: the polynomial lane-wide (polynomialLog2, reference/shader_math.h, step by
  // step), the library's functions lane by lane.
  lanes::Float8 log2(lanes::Float8 x) {
    if (!log2Table_.table &&
        (log2Form_ == Log2Form::kPolynomialFused || log2Form_ == Log2Form::kPolynomialUnfused))
      return lane_detail::polynomialLog2(x, log2Form_ == Log2Form::kPolynomialFused);
    lanes::Float8 result(0.0f);
    for (int k = 0; k < lanes::kLanes; ++k)
      if (active_[k]) result.v[k] = scalar_.log2(x[k]);
    return result;
  }

  // The sqrt member: IEEE lane-wide, a measured table lane by lane.
  lanes::Float8 sqrt(lanes::Float8 x) {
    if (!sqrt_.table) return lanes::sqrt(x);
    lanes::Float8 result(0.0f);
    for (int k = 0; k < lanes::kLanes; ++k) result.v[k] = sqrt_.table->of(x[k]);
    return result;
  }

  lanes::UVec4 vtFetchIndirection(lanes::IVec2 page, lanes::Int8 level) {
    lanes::UVec4 entry(0u, 0u, 0u, 0u);
    for (int k = 0; k < lanes::kLanes; ++k) {
      if (!active_[k]) continue;
      const glm::uvec4 e = scalar_.vtFetchIndirection(glm::ivec2(page.x[k], page.y[k]), level[k]);
      entry.x.v[k] = e.x;
      entry.y.v[k] = e.y;
      entry.z.v[k] = e.z;
      entry.w.v[k] = e.w;
      pages_[k] = scalar_.currentPage();
    }
    return entry;
  }

  // The texel's bytes, read lane by lane, then converted to float lane-wide as unorm8ToFloat
  // converts them (reference/linear_filter.h): times the float 1/255, or divided by 255.
  lanes::Vec4 vtFetchCacheTexel(lanes::IVec2 texel) {
    if constexpr (requires { scalar_.texels(); }) {
      // One RGBA8 texture: the eight texels in one gather, at coordinates clamped to its edge
      // as fetch8 clamps them (every lane's address is inside the texture, active or not).
      const lanes::Int8 x = clampLanes(texel.x, scalar_.width() - 1);
      const lanes::Int8 y = clampLanes(texel.y, scalar_.height() - 1);
      const lanes::Int8 index = y * scalar_.width() + x;
      const lanes::Int8 rgba = reinterpret_cast<lanes::i32x8>(_mm256_i32gather_epi32(
          reinterpret_cast<const int*>(scalar_.texels()), reinterpret_cast<__m256i>(index.v), 4));
      const lanes::Int8 byte(255);
      return {unorm(rgba & byte), unorm((rgba >> 8) & byte), unorm((rgba >> 16) & byte),
              unorm((rgba >> 24) & byte)};
    }
    lanes::Int8 channel[4] = {0, 0, 0, 0};
    for (int k = 0; k < lanes::kLanes; ++k) {
      if (!active_[k]) continue;
      scalar_.usePage(pages_[k]);
      const glm::u8vec4 t = scalar_.fetch8(glm::ivec2(texel.x[k], texel.y[k]));
      for (int c = 0; c < 4; ++c) channel[c].v[k] = t[c];
    }
    return {unorm(channel[0]), unorm(channel[1]), unorm(channel[2]), unorm(channel[3])};
  }

  lanes::Vec4 vtSampleCacheLinear(lanes::Vec2 texel) {
    lanes::Vec4 result(0.0f, 0.0f, 0.0f, 0.0f);
    for (int k = 0; k < lanes::kLanes; ++k) {
      if (!active_[k]) continue;
      scalar_.usePage(pages_[k]);
      const glm::vec4 s = scalar_.vtSampleCacheLinear(glm::vec2(texel.x[k], texel.y[k]));
      result.x.v[k] = s.x;
      result.y.v[k] = s.y;
      result.z.v[k] = s.z;
      result.w.v[k] = s.w;
    }
    return result;
  }

 private:
  static lanes::Int8 clampLanes(lanes::Int8 v, int hi) {
    const lanes::Int8 below = mix(lanes::Int8(hi), v, v < lanes::Int8(hi));
    return mix(lanes::Int8(0), below, lanes::Int8(0) < below);
  }

  lanes::Float8 unorm(lanes::Int8 byte) const {
    const lanes::Float8 value(byte);
    return conversion_ == UnormConversion::kDivided ? value / lanes::Float8(255.0f)
                                                    : value * lanes::Float8(1.0f / 255.0f);
  }

  Scalar& scalar_;
  UnormConversion conversion_;
  Log2Form log2Form_;
  MeasuredMember log2Table_;
  SquareRoot sqrt_;
  const bool* active_;
  const void* pages_[lanes::kLanes] = {};
};

// Shades the active lanes of `in` through `scalar` (the tile's one-pixel backend) into `out`:
// vtShadeFragment, or with `needOnly` vtNeedOfFragment (the LOD and the needbuffer entry).
template <class Scalar>
void shadeLanes(Scalar& scalar, const Arithmetic& arithmetic, const shader::VtParameters& p,
                bool needOnly, const LaneFragments& in, LaneResults& out) {
  using Logic = shader::LaneShaderLogic<LaneBackend<Scalar>>;
  Logic shader(scalar, arithmetic, in.active);
  using lane_detail::load;
  const lanes::Vec2 uvIn(load(in.u), load(in.v));
  const lanes::Vec2 dUVdx(load(in.dudx), load(in.dvdx)), dUVdy(load(in.dudy), load(in.dvdy));
  const typename Logic::VtFragment f = needOnly ? shader.vtNeedOfFragment(uvIn, dUVdx, dUVdy, p)
                                                : shader.vtShadeFragment(uvIn, dUVdx, dUVdy, p);
  const lanes::Int8 color[4] = {lane_detail::toUnorm8(f.color.x), lane_detail::toUnorm8(f.color.y),
                                lane_detail::toUnorm8(f.color.z), lane_detail::toUnorm8(f.color.w)};
  const lanes::Float8* channels[4] = {&f.color.x, &f.color.y, &f.color.z, &f.color.w};
  // A quantizing framebuffer (a measured member) converts lane by lane, as toUnorm8 does.
  const bool nearest = arithmetic.colourConversion.rule == ColourConversionRule::kNearest;
  for (int k = 0; k < lanes::kLanes; ++k) {
    for (int c = 0; c < 4; ++c)
      out.color[k][c] = nearest ? static_cast<uint8_t>(color[c][k])
                                : toUnorm8((*channels[c])[k], arithmetic.colourConversion);
    out.need[k][0] = f.need.x[k];
    out.need[k][1] = f.need.y[k];
    out.need[k][2] = f.need.z[k];
    out.need[k][3] = f.need.w[k];
    out.lod[k] = f.lod[k];
    out.neededLevel[k] = f.neededLevel[k];
    out.residentLevel[k] = f.residentLevel[k];
  }
}

VT_LANES_END

}  // namespace vt::reference
