#include "render/precision_model.h"

#include <map>
#include <stdexcept>
#include <string>

namespace vt {

namespace {

// One source for every parameter: a model pinned by one measurement or one arithmetic.
std::map<std::string, std::string> everyParameterFrom(const std::string& source) {
  std::map<std::string, std::string> sources;
  for (const char* parameter : {"subpixel_bits", "fill_rule", "depth", "attributes", "log2", "sqrt",
                                "arithmetic", "filter", "color_conversion", "denormals"})
    sources[parameter] = source;
  return sources;
}

}  // namespace

bool PrecisionModel::pinned() const {
  return coveragePinned() && depthUlps == 0 && depthRoundsToNearest && attributeUlps == 0 &&
         log2 != Log2Arithmetic::kBounded && sqrtUlps == 0 && arithmeticUlps == 0 &&
         filter != FilterArithmetic::kBounded && colorRoundsToNearest && denormalsPinned;
}

bool PrecisionModel::onlyDenormalsFree() const {
  PrecisionModel rest = *this;
  rest.denormalsPinned = true;
  return !denormalsPinned && rest.pinned();
}

PrecisionModel llvmpipeModel() {
  PrecisionModel m;
  m.name = "llvmpipe";
  m.arithmetic = PrecisionProfile::kLlvmpipe;
  m.log2 = Log2Arithmetic::kLlvmpipe;
  m.filter = FilterArithmetic::kLlvmpipe8Bit;
  m.sources =
      everyParameterFrom("measured on Mesa 22.3.6 llvmpipe, x86-64 with FMA: DESIGN section 7");
  return m;
}

Log2Arithmetic log2Of(PrecisionProfile arithmetic) {
  switch (arithmetic) {
    case PrecisionProfile::kLlvmpipe:
      return Log2Arithmetic::kLlvmpipe;
    case PrecisionProfile::kSoftpipe:
      return Log2Arithmetic::kSoftpipe;
    case PrecisionProfile::kExact:
      break;
  }
  return Log2Arithmetic::kIeee;
}

PrecisionModel softpipeModel() {
  PrecisionModel m;
  m.name = "softpipe";
  m.arithmetic = PrecisionProfile::kSoftpipe;
  m.log2 = log2Of(m.arithmetic);
  m.filter = FilterArithmetic::kFloat;
  m.sources = everyParameterFrom(
      "Mesa 22.3 softpipe, read from its source and confirmed bit for bit by emulation: "
      "reference/softpipe-arithmetic.md");
  m.sources["subpixel_bits"] = m.sources["fill_rule"] =
      "Mesa 22.3 softpipe: no snapping, coverage by float scanline spans with its own tie rule "
      "(reference/softpipe-arithmetic.md, 2.3); the oracle rasterizes the same way";
  // Flushed while draw_vbo shades, kept for the tail of a batch with a clipped vertex, which is
  // shaded after it returns (vt calibrate's probe quad is such a tail).
  m.denormalsPinned = false;
  m.sources["denormals"] =
      "Mesa 22.3 softpipe: flushed for batches without a clipped vertex, kept for the tail of a "
      "batch with one (reference/softpipe-arithmetic.md, 5.3): free, each pixel's set holds its "
      "value with denormals flushed and with them kept";
  return m;
}

PrecisionModel exactModel() {
  PrecisionModel m;
  m.name = "exact";
  m.arithmetic = PrecisionProfile::kExact;
  m.sources = everyParameterFrom("the oracle's IEEE float arithmetic in source order, pinned");
  return m;
}

PrecisionModel gl45Model() {
  PrecisionModel m;
  m.name = "gl45";
  m.arithmetic = PrecisionProfile::kExact;
  // GL 4.5 core, table 23.53 (implementation-dependent values): SUBPIXEL_BITS is at least 4.
  // Chapter 14 does not say how vertices are snapped; any grid of 2^-4 pixel or finer.
  m.subpixelBits = 4;
  m.sources["subpixel_bits"] = "GL 4.5 core, table 23.53: SUBPIXEL_BITS >= 4";
  // Section 14.6.1 asks only that a centre on a shared edge be covered by exactly one of the
  // polygons; which one is the implementation's choice.
  m.fillRulePinned = false;
  m.sources["fill_rule"] =
      "GL 4.5 core, section 14.6.1: a centre on an edge shared by two polygons goes to exactly "
      "one of them, which one is not specified";
  // Depth is interpolated like any attribute (section 14.6.1, equation 14.10, without the
  // perspective division) and converted to fixed point by section 2.3.5.2.
  // The only number the specification gives is the general "about 1 part in 10^5" of section
  // 2.3.4.1: 84 units of 2^-23.
  m.depthUlps = 84;
  m.depthRoundsToNearest = false;
  m.sources["depth"] =
      "GL 4.5 core, section 14.6.1 (z linear in window space over the snapped vertices), section "
      "2.3.4.1 (floating-point computation to about 1 part in 10^5: 84 units of 2^-23) and section "
      "2.3.5.2 (fixed-point depth: either of the two nearest values)";
  // The specification gives no precision for interpolation (attributes are evaluated at the pixel
  // centre, section 14.6.1). dEQP's interpolation verifier allows 3 ULP for each of the three
  // barycentric areas, 8 ULP for the division and 1 ULP per addition: 20 units of 2^-23.
  m.attributeUlps = 20;
  m.sources["attributes"] =
      "GL 4.5 core, section 14.6.1 (perspective-correct barycentric interpolation at the pixel "
      "centre, no precision given); dEQP's interpolation verifier: 3 ULP per barycentric area, "
      "8 ULP per division, 1 ULP per addition, 20 units of 2^-23 beyond the snapping";
  m.log2 = Log2Arithmetic::kBounded;
  m.log2AbsoluteError = 0x1p-21;
  m.log2Ulps = 3;
  m.sources["log2"] = "GLSL 4.50, section 4.7.1: 3 ULP outside [0.5, 2], absolute 2^-21 inside";
  // sqrt is inherited from 1.0 / inversesqrt(x): 2 ULP for inversesqrt, 2.5 ULP for the division.
  m.sqrtUlps = 4.5;
  m.sources["sqrt"] = "GLSL 4.50, section 4.7.1: sqrt as 1.0 / inversesqrt(x), 2 + 2.5 ULP";
  // + - * are correctly rounded (GLSL 4.50, section 4.7.1); the 1 ulp covers the unorm8 texel
  // conversion, c / 255 by section 2.3.5.1, which llvmpipe computes as c * (1 / 255).
  m.arithmeticUlps = 1;
  m.sources["arithmetic"] =
      "GLSL 4.50, section 4.7.1: + - * correctly rounded; 1 ULP for the unorm8 texel conversion "
      "(GL 4.5 core, section 2.3.5.1)";
  // Section 8.14.2 defines GL_LINEAR in real numbers and gives no precision; dEQP's texture
  // lookup verifier passes, for 8-bit formats, 7 sub-texel bits and a colour threshold of the
  // format's bits minus 2 (its lenient 4 bits only earn a quality warning).
  m.filter = FilterArithmetic::kBounded;
  m.subTexelBits = 7;
  m.filterErrorUnits = 4;
  m.sources["filter"] =
      "GL 4.5 core, section 8.14.2 gives no precision; dEQP's texture lookup verifier (strict "
      "precision): 7 sub-texel bits, colour threshold of format bits minus 2, 4 units of 1/255";
  m.colorRoundsToNearest = false;
  m.sources["color_conversion"] =
      "GL 4.5 core, section 2.3.5.2: either of the two nearest unorm values (nearest preferred); "
      "section 17.3.10: dithering, enabled by default, may choose either";
  m.denormalsPinned = false;
  m.sources["denormals"] = "GLSL 4.50, section 4.7.1: denormalized values may be flushed to zero";
  return m;
}

PrecisionModel modelOfArithmetic(PrecisionProfile arithmetic) {
  switch (arithmetic) {
    case PrecisionProfile::kLlvmpipe:
      return llvmpipeModel();
    case PrecisionProfile::kSoftpipe:
      return softpipeModel();
    case PrecisionProfile::kExact:
      break;
  }
  return exactModel();
}

bool isModelName(const std::string& name) {
  return name == "llvmpipe" || name == "softpipe" || name == "exact" || name == "gl45";
}

PrecisionModel namedModel(const std::string& name) {
  if (name == "llvmpipe") return llvmpipeModel();
  if (name == "softpipe") return softpipeModel();
  if (name == "exact") return exactModel();
  if (name == "gl45") return gl45Model();
  throw std::invalid_argument("precision model '" + name + "' is not one of " + kModelNames);
}

PrecisionModel modelForRenderer(const std::string& glRenderer) {
  if (glRenderer.find("llvmpipe") != std::string::npos && __builtin_cpu_supports("fma"))
    return llvmpipeModel();
  if (glRenderer.find("softpipe") != std::string::npos) return softpipeModel();
  return gl45Model();
}

}  // namespace vt
