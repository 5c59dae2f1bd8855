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
//
// The oracle computes in these arithmetics in reference/profile_arithmetic.h.

#include <string>

namespace vt {

enum class PrecisionProfile { kExact, kLlvmpipe };

PrecisionProfile parsePrecisionProfile(const std::string& name);  // throws std::invalid_argument
std::string toString(PrecisionProfile profile);

// Whether the profile evaluates planes and window z with fused multiply-adds.
bool usesFusedPlanes(PrecisionProfile profile);
// Whether fragment arithmetic flushes denormals to zero (DAZ and FTZ).
bool flushesDenormals(PrecisionProfile profile);

}  // namespace vt
