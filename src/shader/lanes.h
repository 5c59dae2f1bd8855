#pragma once
// Eight fragments at a time: the per-fragment types of the shared shader logic (vfloat, vint,
// vuint, vbool and the vectors built from them) as eight SIMD lanes, for shader/shader_lanes.h.
//
// The lanes are GCC's vector extensions, and every function here is compiled for AVX2 (a target
// region, so that the rest of a translation unit stays baseline x86-64 and no symbol a baseline
// function might link to carries an AVX2 instruction). Callers check lanesAvailable() first.
//
// Each operation is the one IEEE operation the scalar build performs, lane by lane, so that a lane
// gives the bits the same fragment gets one at a time:
//   - + - * / and sqrt are correctly rounded (vaddps ... vsqrtps); nothing is fused or
//     reassociated (-ffp-contract=off holds here too), and nothing here computes an FMA.
//   - floor and ceil round to an integral value (vroundps), as std::floor and std::ceil.
//   - float to int truncates (vcvttps2dq), out of range giving 0x80000000 as cvttss2si does for
//     the scalar build's static_cast; int to float rounds to nearest even as cvtsi2ss does.
//   - int << and >> shift each lane by its own count (vpsllvd, vpsravd): arithmetic right shifts,
//     as for a signed int on this compiler.
//   - Comparisons are ordered (false for NaN), as C++'s and GLSL's; a select (mix with a mask)
//     computes nothing.
//   - Denormals follow MXCSR, which governs SSE and AVX alike (reference/shader_math.h sets it).

#include <immintrin.h>

#include <cstdint>

// The AVX2 target region: every function defined between VT_LANES_BEGIN and VT_LANES_END is
// compiled for AVX2 and FMA, with GCC's target pragma or clang's attribute push (the fuzzing
// build).
#if defined(__clang__)
#define VT_LANES_BEGIN \
  _Pragma("clang attribute push (__attribute__((target(\"avx2,fma\"))), apply_to = function)")
#define VT_LANES_END _Pragma("clang attribute pop")
#else
#define VT_LANES_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,fma\")")
#define VT_LANES_END _Pragma("GCC pop_options")
#endif

VT_LANES_BEGIN

namespace vt::lanes {

inline constexpr int kLanes = 8;

typedef float f32x8 __attribute__((vector_size(32)));
typedef int32_t i32x8 __attribute__((vector_size(32)));
typedef uint32_t u32x8 __attribute__((vector_size(32)));

struct Int8;
struct Uint8;

// A mask: all bits set in a lane where the condition holds.
struct Bool8 {
  i32x8 v;
};

struct Float8 {
  f32x8 v;
  Float8() = default;
  Float8(f32x8 lanes) : v(lanes) {}
  Float8(float x) : v(f32x8{x, x, x, x, x, x, x, x}) {}
  // The shader compares and selects with floating literals (never computes with them): each is a
  // float exactly (0.0, 0.5, 1.0), as the scalar build's comparison in double then agrees.
  Float8(double x) : Float8(static_cast<float>(x)) {}
  explicit Float8(Int8 i);
  float operator[](int k) const { return v[k]; }
};

struct Int8 {
  i32x8 v;
  Int8() = default;
  Int8(i32x8 lanes) : v(lanes) {}
  Int8(int x) : v(i32x8{x, x, x, x, x, x, x, x}) {}
  explicit Int8(Float8 f) : v(__builtin_convertvector(f.v, i32x8)) {}
  explicit Int8(Uint8 u);
  int32_t operator[](int k) const { return v[k]; }
};

struct Uint8 {
  u32x8 v;
  Uint8() = default;
  Uint8(u32x8 lanes) : v(lanes) {}
  Uint8(unsigned x) : v(u32x8{x, x, x, x, x, x, x, x}) {}
  explicit Uint8(Int8 i) : v(reinterpret_cast<u32x8>(i.v)) {}
  uint32_t operator[](int k) const { return v[k]; }
};

inline Float8::Float8(Int8 i) : v(__builtin_convertvector(i.v, f32x8)) {}
inline Int8::Int8(Uint8 u) : v(reinterpret_cast<i32x8>(u.v)) {}

inline Float8 operator+(Float8 a, Float8 b) { return a.v + b.v; }
inline Float8 operator-(Float8 a, Float8 b) { return a.v - b.v; }
inline Float8 operator*(Float8 a, Float8 b) { return a.v * b.v; }
inline Float8 operator/(Float8 a, Float8 b) { return a.v / b.v; }
inline Bool8 operator<(Float8 a, Float8 b) { return {a.v < b.v}; }
inline Bool8 operator<=(Float8 a, Float8 b) { return {a.v <= b.v}; }
inline Bool8 operator>(Float8 a, Float8 b) { return {a.v > b.v}; }
inline Bool8 operator>=(Float8 a, Float8 b) { return {a.v >= b.v}; }

inline Int8 operator+(Int8 a, Int8 b) { return a.v + b.v; }
inline Int8 operator-(Int8 a, Int8 b) { return a.v - b.v; }
inline Int8 operator*(Int8 a, Int8 b) { return a.v * b.v; }
inline Int8 operator&(Int8 a, Int8 b) { return a.v & b.v; }
inline Int8 operator|(Int8 a, Int8 b) { return a.v | b.v; }
inline Int8 operator<<(Int8 a, Int8 b) { return a.v << b.v; }
inline Int8 operator>>(Int8 a, Int8 b) { return a.v >> b.v; }
inline Bool8 operator<(Int8 a, Int8 b) { return {a.v < b.v}; }

inline Float8 floor(Float8 x) {
  return reinterpret_cast<f32x8>(
      _mm256_round_ps(reinterpret_cast<__m256>(x.v), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}
inline Float8 ceil(Float8 x) {
  return reinterpret_cast<f32x8>(
      _mm256_round_ps(reinterpret_cast<__m256>(x.v), _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC));
}
// Round to nearest even, as std::nearbyint in the default rounding mode.
inline Float8 nearbyint(Float8 x) {
  return reinterpret_cast<f32x8>(
      _mm256_round_ps(reinterpret_cast<__m256>(x.v), _MM_FROUND_CUR_DIRECTION));
}
inline Float8 sqrt(Float8 x) {
  return reinterpret_cast<f32x8>(_mm256_sqrt_ps(reinterpret_cast<__m256>(x.v)));
}

// GLSL's mix with a boolean: y where a holds, else x.
inline Float8 mix(Float8 x, Float8 y, Bool8 a) {
  return reinterpret_cast<f32x8>((a.v & reinterpret_cast<i32x8>(y.v)) |
                                 (~a.v & reinterpret_cast<i32x8>(x.v)));
}
inline Int8 mix(Int8 x, Int8 y, Bool8 a) { return (a.v & y.v) | (~a.v & x.v); }

struct Vec2;

struct IVec2 {
  Int8 x, y;
  IVec2() = default;
  IVec2(Int8 x_, Int8 y_) : x(x_), y(y_) {}
  explicit IVec2(const Vec2& f);
};

struct Vec2 {
  Float8 x, y;
  Vec2() = default;
  Vec2(Float8 x_, Float8 y_) : x(x_), y(y_) {}
  explicit Vec2(IVec2 i) : x(i.x), y(i.y) {}
};

inline IVec2::IVec2(const Vec2& f) : x(f.x), y(f.y) {}

struct UVec4 {
  Uint8 x, y, z, w;
  UVec4() = default;
  UVec4(Uint8 x_, Uint8 y_, Uint8 z_, Uint8 w_) : x(x_), y(y_), z(z_), w(w_) {}
};

struct Vec4 {
  Float8 x, y, z, w;
  Vec4() = default;
  explicit Vec4(Float8 s) : x(s), y(s), z(s), w(s) {}
  Vec4(Float8 x_, Float8 y_, Float8 z_, Float8 w_) : x(x_), y(y_), z(z_), w(w_) {}
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, Float8 s) { return {a.x * s, a.y * s}; }
inline Vec2 floor(Vec2 a) { return {floor(a.x), floor(a.y)}; }
inline IVec2 operator+(IVec2 a, IVec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec4 operator+(Vec4 a, Vec4 b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
inline Vec4 operator-(Vec4 a, Vec4 b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
inline Vec4 operator*(Vec4 a, Float8 s) { return {a.x * s, a.y * s, a.z * s, a.w * s}; }

}  // namespace vt::lanes

VT_LANES_END

namespace vt::lanes {

// Whether this CPU runs the lanes: AVX2 and FMA (every x86-64-v3 machine).
inline bool lanesAvailable() {
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

}  // namespace vt::lanes
