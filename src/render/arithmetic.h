#pragma once
// The oracle's arithmetic as independent choices (docs/design.md section 3, "An implementation is a
// point in a space of choices"). Each step a GL implementation may compute in more than one
// conforming way is a family below; an implementation is one member of each family. The oracle
// draws any point of this space (reference/triangle_setup.h, reference/shader_math.h,
// reference/linear_filter.h), `vt calibrate` measures each family from its own probes
// (src/calibrate/), and the named points of implementations read from their source or measured
// bit for bit are data in one file (arithmetic_points.cpp).
//
// The choices are values, not template parameters: a calibrated point is any combination, known
// only at run time. Each per-pixel function takes the one choice it needs.
//
// Families and their members, with where each member comes from ("rule N": the rules of llvmpipe's
// arithmetic in docs/design.md section 7):
//
//   viewport       window x, y, z of the mesh's vertices as fma(ndc, half, half) or as a product
//                  and a sum (vertices made by the clipper are never fused: rule 5)
//   coverage       snapped edge functions (rules 2 and 4): sub-pixel bits 1-16, the
//                  rounding of (X - 0.5) * 2^bits, and which edges own a centre on them (left or
//                  right, bottom or top: the four rules GL 4.5 section 14.6.1 allows); or float
//                  scanline spans over unsnapped vertices with truncated span ends
//                  (reference/softpipe-arithmetic.md, 2.3)
//   plane setup    the attribute planes from the first vertex of the oriented triangle (rule 3),
//                  or from the lowest vertex over the y-sorted edges (softpipe-arithmetic.md, 3.1)
//   plane eval     at integer pixel coordinates fused (fma(dady, y, fma(dadx, x, a0))), the same
//                  unfused, or at the quad's even corner stepped to its other pixels by + dadx
//                  and + dady (softpipe-arithmetic.md, 3.2)
//   perspective    s/w and t/w times the reciprocal of the 1/w plane, or divided by it; the
//                  reciprocal is IEEE 1 / q or a measured table (render/measured_table.h)
//   depth          a + 0.0 offset term and a clamp to [0, 1] (rule 7) or neither; Z24
//                  stored as round-half-even(z * (2^24 - 1)) or truncated (unsigned)(z * ...)
//   derivatives    fine: the differences within the pixel's quad row and column, helpers
//                  included (the shader asks for dFdxFine and dFdyFine; coarse derivatives would
//                  break GLSL 4.50 section 8.13.1, so they are not a member)
//   log2           a degree-4 minimax polynomial in (m - 1) / (m + 1) evaluated with fused
//                  multiply-adds (rule 8) or with products and sums, the C library's
//                  log2f, or logf(x) * 1.442695f (softpipe-arithmetic.md, 5.2)
//   GL_LINEAR      weights on 8 bits with fixed-point lerps a + ((f * (b - a) + 128) >> 8)
//                  (rule 9) or with the product floored, a + ((f * (b - a)) >> 8)
//                  (a multiply-high without rounding), or float weights with lerps a + (b - a) * w
//                  rounded per operation or fma(w, b - a, a); the texel position u * size - 0.5 as
//                  a product and a difference or one fma or corner weights on fixed-point positions
//                  with the result as unorm16 (the parameters of Filter: coordinate bits, position
//                  rounding, weight bits, how the corner product rounds, the output's precision;
//                  measured on a GPU)
//   texel values   texelFetch of unorm8 k as k * (1 / 255) (rule 9) or k / 255
//   precision      each float operation rounded to float (SSE arithmetic), or expressions
//                  evaluated in extended precision and rounded once (an x87 code generator):
//                  measured, not emulated (the oracle computes the first)
//   denormals      flushed to zero in fragment arithmetic (DAZ and FTZ) or kept
//   block decoding how a BC1/BC3 palette's thirds, halves, sevenths and fifths become 8 bits, one
//                  rule for colour and one for alpha: rounded to nearest, truncated (Mesa's util
//                  decoder, softpipe), llvmpipe's fixed-point lerps, or a published hardware
//                  rule, or for alpha measured integer weights (format/block_decoding.h)
//   framebuffer    a float colour to unorm8 rounded to nearest even, or truncated to a number of
//                  bits first and scaled with a bias (ColourConversion; measured on a GPU)
//
//   sqrt           IEEE, or a measured table (render/measured_table.h)
//   (log2, again)  a measured table in place of the forms above, where none reproduces it
//
// The shader's + - * are IEEE in every member (GLSL 4.50 section 4.7.1 allows more; a
// measurement that differs is bounded, see precision_model.h).

#include <string>

#include "common/enum_names.h"
#include "format/block_decoding.h"
#include <cmath>

#include "render/measured_table.h"

namespace vt {

enum class SnapRounding { kHalfEven, kHalfUp, kFloor, kCeil };
inline constexpr EnumNames<SnapRounding, 4> kSnapRoundingNames = {
    {{SnapRounding::kHalfEven, "half_even"},
     {SnapRounding::kHalfUp, "half_up"},
     {SnapRounding::kFloor, "floor"},
     {SnapRounding::kCeil, "ceil"}}};

enum class CoverageRule { kSnappedEdges, kScanlineSpans };
inline constexpr EnumNames<CoverageRule, 2> kCoverageRuleNames = {
    {{CoverageRule::kSnappedEdges, "snapped_edges"},
     {CoverageRule::kScanlineSpans, "scanline_spans"}}};

struct Coverage {
  CoverageRule rule = CoverageRule::kSnappedEdges;
  // kSnappedEdges only: X snaps to 0.5 + round((X - 0.5) * 2^subpixelBits) / 2^subpixelBits.
  int subpixelBits = 8;
  SnapRounding rounding = SnapRounding::kHalfEven;
  // A centre exactly on an edge belongs to the triangle when the edge is a left edge and
  // leftEdgesIn (else a right edge), or a horizontal bottom edge and bottomEdgesIn (else top).
  bool leftEdgesIn = true;
  bool bottomEdgesIn = true;
  bool operator==(const Coverage&) const = default;
};

enum class PlaneSetup { kFirstVertex, kLowestVertex };
inline constexpr EnumNames<PlaneSetup, 2> kPlaneSetupNames = {
    {{PlaneSetup::kFirstVertex, "first_vertex"}, {PlaneSetup::kLowestVertex, "lowest_vertex"}}};

// The window positions the planes go through: the float positions the viewport transform gives, or
// those positions snapped to the coverage's sub-pixel grid (X = 1/2 + round((X - 1/2) 2^bits) /
// 2^bits, the rounding the coverage member says), so that the planes and the edges are of one
// triangle. Snapped applies to snapped-edge coverage only (scanline spans snap nothing), and to
// triangles the near or far plane did not clip (the corners clipping makes are no vertex of the
// mesh; such a triangle keeps the planes through the float positions).
enum class PlanePositions { kUnsnapped, kSnapped };
inline constexpr EnumNames<PlanePositions, 2> kPlanePositionsNames = {
    {{PlanePositions::kUnsnapped, "unsnapped"}, {PlanePositions::kSnapped, "snapped"}}};

enum class PlaneEvaluation { kFused, kUnfused, kQuadStepped };
inline constexpr EnumNames<PlaneEvaluation, 3> kPlaneEvaluationNames = {
    {{PlaneEvaluation::kFused, "fused"},
     {PlaneEvaluation::kUnfused, "unfused"},
     {PlaneEvaluation::kQuadStepped, "quad_stepped"}}};

enum class Perspective { kReciprocalTimes, kDivided };
inline constexpr EnumNames<Perspective, 2> kPerspectiveNames = {
    {{Perspective::kReciprocalTimes, "reciprocal_times"}, {Perspective::kDivided, "divided"}}};

enum class Z24Conversion { kNearestEven, kTruncated };
inline constexpr EnumNames<Z24Conversion, 2> kZ24ConversionNames = {
    {{Z24Conversion::kNearestEven, "nearest_even"}, {Z24Conversion::kTruncated, "truncated"}}};

struct Depth {
  bool offsetAndClamp = true;  // z + 0.0, clamped to [0, 1]; false: the plane's value as it is
  Z24Conversion z24 = Z24Conversion::kNearestEven;
  bool operator==(const Depth&) const = default;
};

enum class Log2Form { kPolynomialFused, kPolynomialUnfused, kLibm, kNaturalTimesLog2e };
inline constexpr EnumNames<Log2Form, 4> kLog2FormNames = {
    {{Log2Form::kPolynomialFused, "polynomial_fused"},
     {Log2Form::kPolynomialUnfused, "polynomial_unfused"},
     {Log2Form::kLibm, "libm"},
     {Log2Form::kNaturalTimesLog2e, "natural_times_log2e"}}};

enum class FilterWeights { kFixedPoint8, kFloat, kFixedPointCorners };
inline constexpr EnumNames<FilterWeights, 3> kFilterWeightsNames = {
    {{FilterWeights::kFixedPoint8, "fixed_point_8"},
     {FilterWeights::kFloat, "float"},
     {FilterWeights::kFixedPointCorners, "fixed_point_corners"}}};

// kFixedPoint8: how a lerp's product f * (b - a) comes back to 8 bits; kFixedPointCorners: how
// the product of the two weights does.
enum class LerpRounding { kNearest, kFloor };
inline constexpr EnumNames<LerpRounding, 2> kLerpRoundingNames = {
    {{LerpRounding::kNearest, "nearest"}, {LerpRounding::kFloor, "floor"}}};

// kFixedPointCorners: how the texel position becomes a whole number of 2^-weightBits texel.
enum class PositionRounding { kHalfUp, kFloor };
inline constexpr EnumNames<PositionRounding, 2> kPositionRoundingNames = {
    {{PositionRounding::kHalfUp, "half_up"}, {PositionRounding::kFloor, "floor"}}};

// kFixedPointCorners: what the sampler returns, the weighted sum S of the four texels (a whole
// number of 1 / (255 * 2^weightBits)) rounded half up to a unorm8 or unorm16 value, or S divided
// in float.
enum class FilterOutput { kUnorm8, kUnorm16, kFloat };
inline constexpr EnumNames<FilterOutput, 3> kFilterOutputNames = {
    {{FilterOutput::kUnorm8, "unorm8"},
     {FilterOutput::kUnorm16, "unorm16"},
     {FilterOutput::kFloat, "float"}}};

struct Filter {
  FilterWeights weights = FilterWeights::kFloat;
  bool fusedLerp = false;        // kFloat: fma(w, b - a, a) instead of a + (b - a) * w
  bool fusedCoordinate = false;  // kFloat: fma(u, size, -0.5) instead of u * size - 0.5
  // kFixedPoint8: + 128 before >> 8 (kNearest) or >> 8 alone (kFloor); kFixedPointCorners: the
  // same for the corner weight w11 = fx fy / 2^weightBits.
  LerpRounding lerpRounding = LerpRounding::kNearest;
  // kFixedPointCorners only (the other members ignore them):
  //   U = floor(u 2^coordinateBits)          the normalized coordinate truncated
  //   P = U size / 2^coordinateBits - 1/2    the texel position, exact
  //   q = round(P 2^weightBits)              by positionRounding; i0 = q >> weightBits,
  //                                          f = q & (2^weightBits - 1) per axis
  //   w11 = fx fy / 2^weightBits (rounded by lerpRounding), w10 = fx - w11, w01 = fy - w11,
  //   w00 = 2^weightBits - fx - fy + w11;  S = sum of w t over the four texels (unorm8 t)
  //   the result: S as `output` says.
  int coordinateBits = 21;
  int weightBits = 8;
  PositionRounding positionRounding = PositionRounding::kHalfUp;
  FilterOutput output = FilterOutput::kUnorm16;
  bool operator==(const Filter&) const = default;
};

enum class UnormConversion { kTimesReciprocal, kDivided };
inline constexpr EnumNames<UnormConversion, 2> kUnormConversionNames = {
    {{UnormConversion::kTimesReciprocal, "times_reciprocal"},
     {UnormConversion::kDivided, "divided"}}};

// The framebuffer's conversion of a float colour x in [0, 1] to unorm8: rounded to nearest even
// (x * 255 in float, docs/design.md section 7), or quantized first: x truncated to `bits`
// fractional bits, then k = floor(x 2^bits) scaled to (255 k + bias) >> bits.
enum class ColourConversionRule { kNearest, kQuantized };
inline constexpr EnumNames<ColourConversionRule, 2> kColourConversionRuleNames = {
    {{ColourConversionRule::kNearest, "nearest"}, {ColourConversionRule::kQuantized, "quantized"}}};

struct ColourConversion {
  ColourConversionRule rule = ColourConversionRule::kNearest;
  int bits = 12;    // kQuantized: 8 to 24
  int bias = 2047;  // kQuantized: 0 to 2^bits - 1
  bool operator==(const ColourConversion&) const = default;
};

// A function as IEEE computes it or as a measured table says (render/measured_table.h). Two are
// the same member when their tables' checksums are.
struct MeasuredMember {
  std::shared_ptr<const MeasuredTable> table;  // none: IEEE
  bool operator==(const MeasuredMember& other) const {
    return table ? other.table && other.table->checksum() == table->checksum() : !other.table;
  }
};
// The reciprocal that reciprocal_times multiplies by.
struct Reciprocal : MeasuredMember {
  float of(float q) const { return table ? table->of(q) : 1.0f / q; }
};
// The shader's sqrt (the LOD's e_max).
struct SquareRoot : MeasuredMember {
  float of(float x) const { return table ? table->of(x) : std::sqrt(x); }
};

struct Arithmetic {
  bool fusedViewport = false;
  Coverage coverage;
  PlaneSetup planeSetup = PlaneSetup::kFirstVertex;
  PlanePositions planePositions = PlanePositions::kUnsnapped;
  PlaneEvaluation planeEvaluation = PlaneEvaluation::kUnfused;
  Perspective perspective = Perspective::kReciprocalTimes;
  Reciprocal reciprocal;  // kReciprocalTimes only
  Depth depth;
  Log2Form log2 = Log2Form::kLibm;
  // A measured log2 (render/measured_table.h) in place of the form, where one is set.
  MeasuredMember log2Table;
  SquareRoot sqrt;  // IEEE, or measured
  Filter filter;
  UnormConversion texelConversion = UnormConversion::kTimesReciprocal;
  bool flushDenormals = false;
  BlockDecoding blockDecoding;
  ColourConversion colourConversion;
  bool operator==(const Arithmetic&) const = default;
};

// One line per family, e.g. "log2: polynomial_fused", for messages and reports.
std::string describe(const Arithmetic& arithmetic);

}  // namespace vt
