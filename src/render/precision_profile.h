#pragma once
// The oracle's arithmetic: how it computes the one value at the centre of every pixel's result set
// (precision_model.h says how far another implementation may stray from it).
//
//   exact     IEEE float in the order the source states it, no fused multiply-add, denormals
//             kept, log2 from the C library (glibc's log2f).
//   llvmpipe  Mesa 22.3 llvmpipe on x86-64 with FMA, as measured (DESIGN section 7): plane
//             evaluation fma(dqdy, y, fma(dqdx, x, q0)), window z with fma, log2 and exp2 as
//             llvmpipe's polynomials, denormals flushed to zero in fragment arithmetic. Pin
//             GALLIUM_OVERRIDE_CPU_CAPS to match a CPU without FMA (then use `exact` planes).
//   softpipe  Mesa 22.3 softpipe, as read from its source and confirmed by emulation
//             (reference/softpipe-arithmetic.md): vertices not snapped, coverage by float
//             scanline spans, planes from the lowest vertex evaluated per quad by increments,
//             attributes divided by the 1/w plane, depth neither offset nor clamped (Z24
//             truncated), log2 as logf(x) * 1.442695f, denormals flushed, no fused multiply-add.
//
// The oracle computes in these arithmetics in reference/profile_arithmetic.h and
// reference/triangle_setup.h.

#include <string>

#include "common/enum_names.h"

namespace vt {

enum class PrecisionProfile { kExact, kLlvmpipe, kSoftpipe };
inline constexpr EnumNames<PrecisionProfile, 3> kPrecisionProfileNames = {
    {{PrecisionProfile::kExact, "exact"},
     {PrecisionProfile::kLlvmpipe, "llvmpipe"},
     {PrecisionProfile::kSoftpipe, "softpipe"}}};

PrecisionProfile parsePrecisionProfile(const std::string& name);  // throws std::invalid_argument
std::string toString(PrecisionProfile profile);

// Whether the profile evaluates planes and window z with fused multiply-adds. (Inline: the oracle
// asks for every plane it evaluates.)
constexpr bool usesFusedPlanes(PrecisionProfile profile) {
  return profile == PrecisionProfile::kLlvmpipe;
}
// Whether fragment arithmetic flushes denormals to zero (DAZ and FTZ). softpipe: draw_vbo sets
// FTZ and DAZ while it shades; only the tail of a batch with a clipped vertex is shaded after it
// returns (reference/softpipe-arithmetic.md, 5.3), which no shader value of this project's scenes
// reaches.
constexpr bool flushesDenormals(PrecisionProfile profile) {
  return profile != PrecisionProfile::kExact;
}
// Whether the profile rasterizes as softpipe does: unsnapped vertices, scanline coverage, planes
// stepped per quad, attributes divided, depth unclamped.
constexpr bool rasterizesLikeSoftpipe(PrecisionProfile profile) {
  return profile == PrecisionProfile::kSoftpipe;
}

}  // namespace vt
