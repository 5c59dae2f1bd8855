#include "render/precision_model.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace vt {

namespace {

// One source for every parameter: a model pinned by one measurement or one arithmetic.
std::map<std::string, std::string> everyParameterFrom(const std::string& source) {
  std::map<std::string, std::string> sources;
  for (const char* parameter :
       {"subpixel_bits", "fill_rule", "depth", "attributes", "log2", "sqrt", "arithmetic", "filter",
        "color_conversion", "denormals", "block_decoding"})
    sources[parameter] = source;
  return sources;
}

}  // namespace

bool PrecisionModel::pinned() const {
  // A measured sqrt table reproduces sqrt while sqrtUlps, its residual against the true sqrt,
  // still widens the result sets (calibrate/shader_math_fit.h).
  const bool sqrtPinned = sqrtUlps == 0 || arithmetic.sqrt.table != nullptr;
  return coveragePinned() && depthUlps == 0 && depthRoundsToNearest && attributeUlps == 0 &&
         log2Pinned && sqrtPinned && arithmeticUlps == 0 && filterPinned && colorPinned &&
         denormalsPinned && decodingPinned;
}

bool PrecisionModel::onlyDenormalsFree() const {
  PrecisionModel rest = *this;
  rest.denormalsPinned = true;
  return !denormalsPinned && rest.pinned();
}

PrecisionModel pinnedModel(const Arithmetic& arithmetic, const std::string& name,
                           const std::string& source) {
  PrecisionModel m;
  m.name = name;
  m.arithmetic = arithmetic;
  m.subpixelBits = arithmetic.coverage.subpixelBits;
  m.sources = everyParameterFrom(source);
  return m;
}

PrecisionModel gl45Model() {
  PrecisionModel m;
  m.name = "gl45";
  m.arithmetic = Arithmetic{};  // IEEE float in source order: the centre of gl45's sets
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
  // 2.3.4.1: 84 units of 2^-23, relative to the operands, so of the depth range [0, 1] where the
  // terms of z lie in it and of the terms where they are larger (precision_model.h).
  m.depthUlps = 84;
  m.depthRoundsToNearest = false;
  m.sources["depth"] =
      "GL 4.5 core, section 14.6.1 (z linear in window space over the snapped vertices), section "
      "2.3.4.1 (floating-point computation to about 1 part in 10^5 of its operands: 84 units of "
      "2^-23 of the depth range or of the terms z sums, the larger) and section "
      "2.3.5.2 (fixed-point depth: either of the two nearest values)";
  // The specification gives no precision for interpolation (attributes are evaluated at the pixel
  // centre, section 14.6.1). dEQP's interpolation verifier allows 3 ULP for each of the three
  // barycentric areas, 8 ULP for the division and 1 ULP per addition: 20 units of 2^-23.
  m.attributeUlps = 20;
  m.sources["attributes"] =
      "GL 4.5 core, section 14.6.1 (perspective-correct barycentric interpolation at the pixel "
      "centre, no precision given); dEQP's interpolation verifier: 3 ULP per barycentric area, "
      "8 ULP per division, 1 ULP per addition, 20 units of 2^-23 beyond the snapping";
  m.log2Pinned = false;
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
  m.filterPinned = false;
  m.subTexelBits = 7;
  m.filterErrorUnits = 4;
  m.sources["filter"] =
      "GL 4.5 core, section 8.14.2 gives no precision; dEQP's texture lookup verifier (strict "
      "precision): 7 sub-texel bits, colour threshold of format bits minus 2, 4 units of 1/255";
  m.colorPinned = false;
  m.sources["color_conversion"] =
      "GL 4.5 core, section 2.3.5.2: either of the two nearest unorm values (nearest preferred); "
      "section 17.3.10: dithering, enabled by default, may choose either";
  m.denormalsPinned = false;
  m.sources["denormals"] = "GLSL 4.50, section 4.7.1: denormalized values may be flushed to zero";
  // The extension states the palette in real numbers and no precision; an 8-bit texel holds
  // the fraction rounded either way (section 2.3.5.2), and the decoders GPUs and Mesa are known
  // to use stray further (llvmpipe up to 4/3, the published AMD rule 5/3 and NVIDIA green 16/3
  // units of 1/255): every texel within the least and greatest of these.
  m.decodingPinned = false;
  m.sources["block_decoding"] =
      "EXT_texture_compression_s3tc: palette thirds, halves, sevenths and fifths in real numbers, "
      "no precision given; GL 4.5 core, section 2.3.5.2 (either nearest 8-bit value) and every "
      "known decoder (format/block_decoding.h): each texel within their least and greatest value";
  return m;
}

std::vector<Gl45Excess> excessesOverGl45(const PrecisionModel& m) {
  const PrecisionModel g = gl45Model();
  std::vector<Gl45Excess> excesses;
  const auto beyond = [&](const std::string& what, double value, double bound,
                          const std::string& key) {
    const std::string measured = std::isfinite(value)
                                     ? std::to_string(value)
                                     : "not a finite number (" + std::to_string(value) + ")";
    excesses.push_back({key, what + " " + measured + " beyond the specification's " +
                                 std::to_string(bound) + " (" + g.sources.at(key) + ")"});
  };
  // A bound is within the specification's only when it compares at most equal: NaN compares
  // false with everything, so it is never within.
  const auto above = [](double value, double bound) { return !(value <= bound); };
  if (m.subpixelBits < g.subpixelBits)
    beyond("sub-pixel bits", m.subpixelBits, g.subpixelBits, "subpixel_bits");
  if (above(m.depthUlps, g.depthUlps))
    beyond("depth error in ulps", m.depthUlps, g.depthUlps, "depth");
  if (above(m.attributeUlps, g.attributeUlps))
    beyond("attribute error in ulps", m.attributeUlps, g.attributeUlps, "attributes");
  // log2 pinned by a closed form is the oracle's own, and its bounds are ignored, yet written to
  // the file: finite there too. Pinned by a measured table it keeps its residuals against the
  // true log2 (the result sets widen by them), and GLSL bounds those as any other log2's.
  const bool log2Exempt = m.log2Pinned && !m.arithmetic.log2Table.table;
  if ((!log2Exempt || !std::isfinite(m.log2AbsoluteError)) &&
      above(m.log2AbsoluteError, g.log2AbsoluteError))
    beyond("log2 absolute error inside [0.5, 2]", m.log2AbsoluteError, g.log2AbsoluteError, "log2");
  if ((!log2Exempt || !std::isfinite(m.log2Ulps)) && above(m.log2Ulps, g.log2Ulps))
    beyond("log2 error in ulps outside [0.5, 2]", m.log2Ulps, g.log2Ulps, "log2");
  if (above(m.sqrtUlps, g.sqrtUlps)) beyond("sqrt error in ulps", m.sqrtUlps, g.sqrtUlps, "sqrt");
  if (above(m.arithmeticUlps, g.arithmeticUlps))
    beyond("shader arithmetic error in ulps", m.arithmeticUlps, g.arithmeticUlps, "arithmetic");
  if (!m.filterPinned && m.subTexelBits < g.subTexelBits)
    beyond("GL_LINEAR sub-texel bits", m.subTexelBits, g.subTexelBits, "filter");
  if ((!m.filterPinned || !std::isfinite(m.filterErrorUnits)) &&
      above(m.filterErrorUnits, g.filterErrorUnits))
    beyond("GL_LINEAR error in units of 1/255", m.filterErrorUnits, g.filterErrorUnits, "filter");
  // A negative bound admits nothing, not even the oracle's own value: no measurement gives one.
  const std::pair<const char*, double> bounds[] = {
      {"depth", m.depthUlps},        {"attributes", m.attributeUlps},
      {"log2", m.log2AbsoluteError}, {"log2", m.log2Ulps},
      {"sqrt", m.sqrtUlps},          {"arithmetic", m.arithmeticUlps},
      {"filter", m.filterErrorUnits}};
  for (const auto& [key, value] : bounds)
    if (value < 0)
      excesses.push_back({key, std::string(key) + " bound " + std::to_string(value) +
                                   " is negative, which no measurement gives"});
  return excesses;
}

std::string beyondGl45(const PrecisionModel& m) {
  const std::vector<Gl45Excess> excesses = excessesOverGl45(m);
  return excesses.empty() ? "" : excesses.front().text;
}

}  // namespace vt
