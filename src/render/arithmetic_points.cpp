#include "render/arithmetic_points.h"

#include <stdexcept>
#include <string>

namespace vt {
namespace {

Arithmetic exactPoint() { return Arithmetic{}; }

Arithmetic llvmpipePoint() {
  Arithmetic a;
  a.fusedViewport = true;                             // rule 1
  a.coverage = {.rule = CoverageRule::kSnappedEdges,  // rules 2, 4
                .subpixelBits = 8,
                .rounding = SnapRounding::kHalfEven,
                .leftEdgesIn = true,
                .bottomEdgesIn = true};
  a.planeSetup = PlaneSetup::kFirstVertex;                                 // rule 3
  a.planeEvaluation = PlaneEvaluation::kFused;                             // rule 6
  a.perspective = Perspective::kReciprocalTimes;                           // rule 6
  a.depth = {.offsetAndClamp = true, .z24 = Z24Conversion::kNearestEven};  // rule 7
  a.log2 = Log2Form::kPolynomialFused;                                     // rule 8
  a.filter = {.weights = FilterWeights::kFixedPoint8};                     // rule 9
  a.texelConversion = UnormConversion::kTimesReciprocal;                   // rule 9
  a.flushDenormals = true;                                                 // rule 8
  // gallivm's S3TC decoder, measured on every palette entry (format/block_decoding.h).
  a.blockDecoding = {PaletteRule::kFixedPointLerp, PaletteRule::kFixedPointLerp};
  return a;
}

Arithmetic softpipePoint() {
  // reference/softpipe-arithmetic.md: sections 2.3 (spans), 3 (planes), 5.2 (log2), 7.1 (depth).
  // Denormals: flushed while draw_vbo shades (5.3); the precision model leaves them free.
  Arithmetic a;
  a.fusedViewport = false;
  a.coverage.rule = CoverageRule::kScanlineSpans;
  a.planeSetup = PlaneSetup::kLowestVertex;
  a.planeEvaluation = PlaneEvaluation::kQuadStepped;
  a.perspective = Perspective::kDivided;
  a.depth = {.offsetAndClamp = false, .z24 = Z24Conversion::kTruncated};
  a.log2 = Log2Form::kNaturalTimesLog2e;
  a.filter = {.weights = FilterWeights::kFloat};
  a.texelConversion = UnormConversion::kTimesReciprocal;
  a.flushDenormals = true;
  // Mesa's util S3TC decoder (u_format_s3tc), measured (format/block_decoding.h).
  a.blockDecoding = {PaletteRule::kTruncated, PaletteRule::kTruncated};
  return a;
}

struct Point {
  const char* name;
  Arithmetic (*make)();
};
constexpr Point kPoints[] = {
    {"exact", exactPoint}, {"llvmpipe", llvmpipePoint}, {"softpipe", softpipePoint}};

}  // namespace

std::vector<std::string> arithmeticPointNames() {
  std::vector<std::string> names;
  for (const Point& p : kPoints) names.emplace_back(p.name);
  return names;
}

std::string joinedArithmeticPointNames() {
  std::string text;
  for (const Point& p : kPoints) text += (text.empty() ? "" : ", ") + std::string(p.name);
  return text;
}

std::optional<Arithmetic> findArithmeticPoint(std::string_view name) {
  for (const Point& p : kPoints)
    if (name == p.name) return p.make();
  return std::nullopt;
}

Arithmetic arithmeticPoint(std::string_view name) {
  if (const auto a = findArithmeticPoint(name)) return *a;
  throw std::invalid_argument("arithmetic '" + std::string(name) + "' is not one of " +
                              joinedArithmeticPointNames());
}

std::string arithmeticPointName(const Arithmetic& arithmetic) {
  for (const Point& p : kPoints)
    if (p.make() == arithmetic) return p.name;
  return "";
}

std::string arithmeticLabel(const Arithmetic& arithmetic) {
  const std::string name = arithmeticPointName(arithmetic);
  return name.empty() ? "calibrated" : name;
}

std::optional<std::string> pointForRenderer(const std::string& glRenderer) {
  if (glRenderer.find("llvmpipe") != std::string::npos && __builtin_cpu_supports("fma"))
    return "llvmpipe";
  if (glRenderer.find("softpipe") != std::string::npos) return "softpipe";
  return std::nullopt;
}

PrecisionModel llvmpipeModel() {
  return pinnedModel(arithmeticPoint("llvmpipe"), "llvmpipe",
                     "measured on Mesa 22.3.6 llvmpipe, x86-64 with FMA: DESIGN section 7");
}

PrecisionModel softpipeModel() {
  PrecisionModel m = pinnedModel(
      arithmeticPoint("softpipe"), "softpipe",
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
  return pinnedModel(arithmeticPoint("exact"), "exact",
                     "the oracle's IEEE float arithmetic in source order, pinned");
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
  if (const std::optional<std::string> point = pointForRenderer(glRenderer))
    return namedModel(*point);
  return gl45Model();
}

bool readVersion1Arithmetic(const std::string& point, const std::string& log2,
                            const std::string& filter, PrecisionModel& m) {
  const std::optional<Arithmetic> base = findArithmeticPoint(point);
  // Version 1 named log2 members after the points computing them ("ieee": exact's), and the
  // filter "llvmpipe_8bit" (llvmpipe's) or "float" (exact's).
  const std::optional<Arithmetic> log2Point = findArithmeticPoint(log2 == "ieee" ? "exact" : log2);
  const std::optional<Arithmetic> filterPoint =
      findArithmeticPoint(filter == "llvmpipe_8bit" ? "llvmpipe" : "exact");
  if (!base || (!log2Point && log2 != "bounded") ||
      (filter != "llvmpipe_8bit" && filter != "float" && filter != "bounded"))
    return false;
  m.arithmetic = *base;
  m.log2Pinned = log2 != "bounded";
  if (m.log2Pinned) m.arithmetic.log2 = log2Point->log2;
  m.filterPinned = filter != "bounded";
  if (m.filterPinned) m.arithmetic.filter = filterPoint->filter;
  return true;
}

}  // namespace vt
