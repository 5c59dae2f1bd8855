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
  line("plane_setup", std::string(nameOf(kPlaneSetupNames, a.planeSetup)));
  line("plane_evaluation", std::string(nameOf(kPlaneEvaluationNames, a.planeEvaluation)));
  line("perspective", std::string(nameOf(kPerspectiveNames, a.perspective)));
  line("depth", std::string(a.depth.offsetAndClamp ? "offset and clamp" : "as interpolated") +
                    ", Z24 " + std::string(nameOf(kZ24ConversionNames, a.depth.z24)));
  line("log2", std::string(nameOf(kLog2FormNames, a.log2)));
  line("filter",
       std::string(nameOf(kFilterWeightsNames, a.filter.weights)) +
           (a.filter.weights == FilterWeights::kFloat
                ? std::string(a.filter.fusedLerp ? ", fused lerp" : ", unfused lerp") +
                      (a.filter.fusedCoordinate ? ", fused position" : ", unfused position")
                : ", lerp products rounded to " +
                      std::string(nameOf(kLerpRoundingNames, a.filter.lerpRounding))));
  line("texel_conversion", std::string(nameOf(kUnormConversionNames, a.texelConversion)));
  line("denormals", a.flushDenormals ? "flushed" : "kept");
  line("block_decoding", "colour " + std::string(nameOf(kPaletteRuleNames, a.blockDecoding.colour)) +
                             ", alpha " + std::string(nameOf(kPaletteRuleNames, a.blockDecoding.alpha)));
  return text;
}

}  // namespace vt
