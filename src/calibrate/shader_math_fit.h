#pragma once
// The shader-math families of the arithmetic (render/arithmetic.h) fitted from probe draws
// (probes/probe_draws.h): log2, sqrt, texel values, the `precise` lerps, denormals.
//
//   log2, sqrt   65,536 positive floats of every exponent through log2() and sqrt(): every member
//                of the log2 family bit for bit; where none reproduces them and the folder holds
//                the sweep of [0.5, 2), its [1, 2) as a measured table (render/measured_table.h),
//                pinned where it reproduces every sample and the whole sweep; else the residual
//                against the true log2
//                (absolute inside [0.5, 2], ulps outside: the GLSL 4.50 table's units). sqrt is
//                IEEE; or, where the folder holds the sweep of [1, 4), the measured table
//                (render/measured_table.h), pinned where it reproduces the samples of every
//                exponent too; or bounded by its residual in ulps, which bounds the result sets
//                under a table as well.
//   texel values texelFetch of the 256 unorm8 values against both conversions
//   lerps        16,384 of the shader's `precise` lerps a + (b - a) * w rounded per operation;
//                else the residual in units of 2^-23 of the larger operand (the precision
//                model's arithmetic_ulps: a relative error per operation)
//   denormals    a denormal times a 1 read from the inputs, in a draw the clipper cuts and in one
//                it leaves whole: flushed or kept, or free where the two differ
//   reciprocal   1.0 / x of every float of [1, 2), where the folder holds the pack's sweep
//                (probes/function_sweeps.h): IEEE division bit for bit, or its residual in ulps
//                and the measured table (render/measured_table.h), which the rasterization
//                fit offers the perspective member reciprocal_times beside IEEE 1 / q: the
//                perspective triangles decide (raster_fit.h).

#include <optional>

#include "calibrate/family_fit.h"
#include "render/arithmetic.h"

namespace vt::calibrate {

// GLSL 4.50 section 4.7.1: 1.0 / x within 2.5 ulps for x in [2^-126, 2^126].
inline constexpr double kGlslReciprocalUlps = 2.5;

struct ShaderMathFits {
  ParameterFit log2, sqrt, texelConversion, lerp, denormals;
  std::optional<ParameterFit> reciprocal;  // where the reciprocal sweep was drawn
  Reciprocal measuredReciprocal;           // its table, where IEEE division missed some
  SquareRoot sqrtMember;                   // the measured table where it pinned sqrt
  MeasuredMember log2Table;                // the measured table where it pinned log2
  Log2Form log2Form = Log2Form::kLibm;    // the chosen member
  double log2Absolute = 0, log2Ulps = 0;  // residuals against the true log2 (unpinned only)
  double sqrtUlps = 0;
  UnormConversion conversion = UnormConversion::kTimesReciprocal;
  double arithmeticUlps = 0;      // texel values and lerps, per operation (unpinned only)
  bool flushesDenormals = false;  // in a draw the clipper leaves whole
  bool denormalsAlike = true;     // the same in every draw
};

// Draws the probes on the current GL context and fits the families.
ShaderMathFits fitShaderMath();

}  // namespace vt::calibrate
