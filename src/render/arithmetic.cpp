#include "render/arithmetic.h"

namespace vt {

std::string describe(const Arithmetic& a) {
  std::string text;
  const auto line = [&](const std::string& family, const std::string& member) {
    text += family + ": " + member + "\n";
  };
  line("viewport", a.fusedViewport ? "fused" : "unfused");
  if (a.coverage.rule == CoverageRule::kScanlineSpans)
    line("coverage", "scanline_spans");
  else
    line("coverage", "snapped_edges, " + std::to_string(a.coverage.subpixelBits) + " bits, " +
                         std::string(nameOf(kSnapRoundingNames, a.coverage.rounding)) + ", " +
                         (a.coverage.leftEdgesIn ? "left" : "right") + " and " +
                         (a.coverage.bottomEdgesIn ? "bottom" : "top") + " edges in");
  // The positions are said for the snapped member only, so that the others read as before.
  line("plane_setup", std::string(nameOf(kPlaneSetupNames, a.planeSetup)) +
                          (a.planePositions == PlanePositions::kSnapped
                               ? ", through the positions snapped to the coverage's grid"
                               : ""));
  line("plane_evaluation", std::string(nameOf(kPlaneEvaluationNames, a.planeEvaluation)));
  line("perspective", std::string(nameOf(kPerspectiveNames, a.perspective)) +
                         (a.reciprocal.table ? ", the measured reciprocal (table " +
                                                   a.reciprocal.table->checksum() + ")"
                                             : ""));
  line("depth", std::string(a.depth.offsetAndClamp ? "offset and clamp" : "as interpolated") +
                    ", Z24 " + std::string(nameOf(kZ24ConversionNames, a.depth.z24)));
  line("log2", a.log2Table.table ? "the measured table " + a.log2Table.table->checksum()
                                 : std::string(nameOf(kLog2FormNames, a.log2)));
  // Said for a measured sqrt only, so that the named points describe themselves as before.
  if (a.sqrt.table) line("sqrt", "the measured table " + a.sqrt.table->checksum());
  const Filter& f = a.filter;
  const std::string rounding(nameOf(kLerpRoundingNames, f.lerpRounding));
  std::string filter(nameOf(kFilterWeightsNames, f.weights));
  if (f.weights == FilterWeights::kFloat)
    filter += std::string(f.fusedLerp ? ", fused lerp" : ", unfused lerp") +
              (f.fusedCoordinate ? ", fused position" : ", unfused position");
  else if (f.weights == FilterWeights::kFixedPoint8)
    filter += ", lerp products rounded to " + rounding;
  else
    filter += ", coordinates on " + std::to_string(f.coordinateBits) + " bits, positions " +
              std::string(nameOf(kPositionRoundingNames, f.positionRounding)) + " to 2^-" +
              std::to_string(f.weightBits) + " texel, corner product rounded to " + rounding +
              ", " + std::string(nameOf(kFilterOutputNames, f.output)) + " result";
  line("filter", filter);
  line("texel_conversion", std::string(nameOf(kUnormConversionNames, a.texelConversion)));
  line("denormals", a.flushDenormals ? "flushed" : "kept");
  std::string alpha(nameOf(kPaletteRuleNames, a.blockDecoding.alpha));
  if (a.blockDecoding.alpha == PaletteRule::kWeights) {
    alpha += " (of 4096:";
    for (const uint16_t w : a.blockDecoding.alphaWeights) alpha += " " + std::to_string(w);
    alpha += ")";
  }
  line("block_decoding", "colour " +
                             std::string(nameOf(kPaletteRuleNames, a.blockDecoding.colour)) +
                             ", alpha " + alpha);
  // Written for a measured member only, so that the named points describe themselves as before.
  if (a.colourConversion.rule == ColourConversionRule::kQuantized)
    line("colour_conversion", "quantized to " + std::to_string(a.colourConversion.bits) +
                                  " bits, bias " + std::to_string(a.colourConversion.bias));
  return text;
}

}  // namespace vt
