#include "calibrate/calibration.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "calibrate/decoding_fit.h"
#include "calibrate/filter_fit.h"
#include "calibrate/noperspective_fit.h"
#include "calibrate/raster_fit.h"
#include "calibrate/shader_math_fit.h"
#include "probes/probe_draws.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"

namespace vt::calibrate {
namespace {

struct ColourConversionFit {
  ParameterFit fit;
  ColourConversion conversion;  // the member pinned (nearest when none is)
};

// The quantized members (render/arithmetic.h, ColourConversion) that reproduce every channel: per
// number of bits the biases each (input, output) pair allows, out 2^bits <= 255 k + bias <
// (out + 1) 2^bits with k = floor(x 2^bits), intersected.
std::vector<ColourConversion> quantizedConversions(const std::vector<glm::vec4>& inputs,
                                                   const std::vector<glm::u8vec4>& out) {
  std::vector<ColourConversion> fitting;
  for (int bits = 8; bits <= 24; ++bits) {
    const int64_t one = int64_t{1} << bits;
    int64_t lo = 0, hi = one - 1;
    for (size_t i = 0; i < out.size() && lo <= hi; ++i)
      for (int c = 0; c < 4; ++c) {
        const double x = std::clamp(static_cast<double>(inputs[i][c]), 0.0, 1.0);
        const auto k = static_cast<int64_t>(std::ldexp(x, bits));
        lo = std::max(lo, out[i][c] * one - 255 * k);
        hi = std::min(hi, (out[i][c] + 1) * one - 255 * k - 1);
      }
    for (int64_t bias = lo; bias <= hi && fitting.size() < 2; ++bias)
      fitting.push_back({ColourConversionRule::kQuantized, bits, static_cast<int>(bias)});
    if (fitting.size() > 1) break;  // more than one: the probe cannot tell them apart
  }
  return fitting;
}

// Colour conversion: floats between two unorm8 values written to an RGBA8 target.
ColourConversionFit fitColourConversion() {
  ShaderProbe probe;
  probe.body = "result = x;";
  probe.width = 255;
  const float fractions[] = {0.1f, 0.3f, 0.45f, 0.49f, 0.51f, 0.55f, 0.7f, 0.9f};
  std::vector<uint8_t> nearest;
  for (const float f : fractions)
    for (int k = 0; k < 255; ++k) {
      probe.inputs.push_back(glm::vec4((static_cast<float>(k) + f) / 255.0f));
      nearest.push_back(static_cast<uint8_t>(k + (f > 0.5f ? 1 : 0)));
    }
  const std::vector<glm::u8vec4> out = runColourProbe(probe);
  uint64_t other = 0, beyond = 0;
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      other += out[i][c] != nearest[i];
      // Either of the two nearest (GL 4.5 section 2.3.5.2): k or k + 1.
      const int k = static_cast<int>(i % 255);
      beyond += out[i][c] != k && out[i][c] != k + 1;
    }
  ColourConversionFit result{ParameterFit{"color_conversion",
                                          "2,040 floats between two unorm8 values",
                                          out.size() * 4,
                                          {{"nearest", other}}},
                             {}};
  ParameterFit& fit = result.fit;
  // Not the nearest value: the one quantized member that reproduces every channel, if one does
  // (none, or several the probe cannot tell apart, leave the conversion free).
  std::vector<ColourConversion> quantized;
  if (other != 0 && beyond == 0) quantized = quantizedConversions(probe.inputs, out);
  if (quantized.size() == 1) {
    const ColourConversion& q = quantized[0];
    fit.members.push_back(
        {"quantized_" + std::to_string(q.bits) + "_bits_bias_" + std::to_string(q.bias), 0});
    result.conversion = q;
  }
  fit.choose();
  fit.unit = "values beyond the two nearest";
  fit.largestResidual = fit.pinned ? 0.0 : static_cast<double>(beyond);
  const std::string alone = quantized.size() > 1 ? ", more than one quantization reproduces it"
                            : fit.pinned
                                ? ""
                                : ", no quantization of 8 to 24 bits with a bias reproduces it";
  fit.finding =
      other == 0   ? "always the nearest unorm8 value"
      : fit.pinned ? "(255 floor(x 2^" + std::to_string(result.conversion.bits) + ") + " +
                         std::to_string(result.conversion.bias) + ") >> " +
                         std::to_string(result.conversion.bits) + ", every channel bit for bit (" +
                         fit.memberSummary() + ")"
                   : differ(other, fit.probes) + " from the nearest unorm8 value" +
                         (beyond ? ", " + std::to_string(beyond) + " beyond both of the two nearest"
                                 : std::string(": either of the two")) +
                         alone;
  return result;
}

// Two overlapping quads, one at window z 0.25 and one at 0.75, drawn far then near and near then
// far (32F depth, GL_LESS): every pixel both cover shows the near one.
ParameterFit fitDepthTest() {
  const Viewport viewport{64, 64};
  ClipSpaceMesh mesh;
  const auto quad = [&](float x0, float x1, float z) {
    const glm::vec4 corners[4] = {
        {x0, -0.8f, z, 1}, {x1, -0.8f, z, 1}, {x1, 0.8f, z, 1}, {x0, 0.8f, z, 1}};
    for (const int k : {0, 1, 2, 0, 2, 3}) {
      mesh.vertices.push_back({corners[k], {0.5f, 0.5f}});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  };
  // Triangles 0, 1: far, left; 2, 3: near, over all; 4, 5: far, right (after the near one).
  quad(-0.9f, 0.1f, 0.5f);
  quad(-0.6f, 0.6f, -0.5f);
  quad(-0.1f, 0.9f, 0.5f);
  const RasterReadback drawn = drawTriangles(mesh, viewport);
  uint64_t covered = 0, far = 0;
  for (int py = 0; py < viewport.height; ++py)
    for (int px = 0; px < viewport.width; ++px) {
      // Pixel centres well inside the near quad (window x in (12.8, 51.2), y in (6.4, 57.6)).
      const double x = px + 0.5, y = py + 0.5;
      if (x < 14 || x > 50 || y < 8 || y > 56) continue;
      ++covered;
      const int32_t t = drawn.triangle[static_cast<size_t>(py * viewport.width + px)];
      far += t != 2 && t != 3;
    }
  ParameterFit fit{"depth_test",
                   "a near quad drawn between two far ones, 32F depth, GL_LESS",
                   covered,
                   {{"near_wins", far}}};
  fit.choose();
  fit.unit = "pixels";
  fit.largestResidual = static_cast<double>(far);
  fit.finding = far == 0 ? "every pixel of the overlap shows the near quad"
                         : std::to_string(far) + " of " + std::to_string(covered) +
                               " pixels of the overlap show a far quad or nothing";
  return fit;
}

// What breaks a rule of the specification, one line each, with the probe that showed it.
std::vector<std::string> nonConformance(const PrecisionModel& m,
                                        const std::vector<ParameterFit>& fits,
                                        const DecodingFit& decoding) {
  std::vector<std::string> lines;
  const auto fit = [&](const std::string& parameter) -> const ParameterFit& {
    return fitNamed(fits, parameter);
  };
  if (const ParameterFit& depth = fit("depth_test"); !depth.pinned)
    lines.push_back(
        "depth test (GL 4.5 core, section 17.3, the depth buffer test: GL_LESS keeps "
        "the nearer fragment): " +
        depth.finding + "; probe: " + depth.probe);
  if (const ParameterFit& colour = fit("color_conversion"); colour.largestResidual > 0)
    lines.push_back(
        "colour conversion (GL 4.5 core, section 2.3.5.2: one of the two nearest "
        "unorm values): " +
        colour.finding + "; probe: " + colour.probe);
  for (const ParameterFit& f : fits)
    if (f.parameter == "reciprocal" && f.largestResidual > kGlslReciprocalUlps)
      lines.push_back("the reciprocal (GLSL 4.50, section 4.7.1: 1.0 / x within 2.5 ulps): " +
                      f.finding + "; probe: " + f.probe);
  if (decoding.outsideRange > 0)
    lines.push_back(
        "block decoding (EXT_texture_compression_s3tc: the palette's fractions of the "
        "end points; no known decoder strays further): " +
        std::to_string(decoding.outsideRange) +
        " channels beyond every known decoder and the fraction rounded either way; "
        "probe: " +
        decoding.colour.probe);
  for (const Gl45Excess& excess : excessesOverGl45(m)) {
    const ParameterFit& measured = fit(excess.parameter);
    lines.push_back(excess.text + "; probe: " + measured.probe + "; measured: " + measured.finding);
  }
  return lines;
}

}  // namespace

Calibration calibrate() {
  Calibration c;
  const ProbeIdentity identity = probeIdentity();
  c.renderer = identity.renderer;
  c.version = identity.version;
  c.vendor = identity.vendor;
  const ShaderMathFits math = fitShaderMath();
  std::vector<FilterSample> filterSamples = drawFilterProbes();
  const ColourConversionFit colourFit = fitColourConversion();
  const ParameterFit& colour = colourFit.fit;
  const ParameterFit depthTest = fitDepthTest();
  const DecodingFit decoding = fitBlockDecoding();
  Arithmetic shaderMembers;
  shaderMembers.log2 = math.log2Form;
  shaderMembers.texelConversion = math.conversion;
  shaderMembers.flushDenormals = math.flushesDenormals;
  shaderMembers.reciprocal = math.measuredReciprocal;  // offered beside IEEE 1 / q
  shaderMembers.sqrt = math.sqrtMember;
  shaderMembers.log2Table = math.log2Table;
  const RasterFits raster = fitRasterization(shaderMembers);
  // Drawn after the first pack's last draw (raster's); the filter members draw no coordinate.
  drawFilterProbesAtCacheSizes(filterSamples,
                               {decoding.decoding, decoding.colour.pinned, decoding.alpha.pinned});
  const FilterFit filter = fitFilter(filterSamples, math.conversion);
  // The noperspective group comes after the filter group's draws.
  const std::optional<ParameterFit> noperspective = fitNoperspectivePlanes(raster.arithmetic);

  // Start from gl45: what no probe pins keeps at most the specification's slack, and what a
  // probe measured narrows it to the residual.
  PrecisionModel& m = c.model;
  m = gl45Model();
  m.name = "calibrated";
  m.renderer = c.renderer;
  m.glVersion = c.version;
  m.arithmetic = raster.arithmetic;
  setCoverageBounds(m, raster.coveragePinned, raster.subpixelBits);
  m.attributeUlps = raster.attributeUlps;
  m.depthUlps = raster.depthUlps;
  m.depthRoundsToNearest = raster.z24Pinned && raster.depth.pinned;
  m.log2Pinned = math.log2.pinned;
  m.log2AbsoluteError = math.log2Absolute;
  m.log2Ulps = math.log2Ulps;
  m.sqrtUlps = math.sqrtUlps;
  m.arithmeticUlps = math.arithmeticUlps;
  m.arithmetic.filter = filter.filter;
  m.filterPinned = filter.fit.pinned;
  m.subTexelBits = filter.fit.pinned ? 0 : filter.subTexelBits;
  m.filterErrorUnits = filter.fit.pinned ? 0 : filter.errorUnits;
  m.colorPinned = colour.pinned;
  m.arithmetic.colourConversion = colourFit.conversion;
  m.denormalsPinned = math.denormalsAlike;
  m.arithmetic.blockDecoding = decoding.decoding;
  m.decodingPinned = decoding.pinned();

  c.fits = raster.fits;
  c.fits.insert(c.fits.begin() + 2, raster.attributes);
  c.fits.insert(c.fits.begin() + 3, raster.depth);
  for (const ParameterFit& f : {math.log2, math.sqrt, math.texelConversion, math.lerp, filter.fit,
                                colour, math.denormals, depthTest, decoding.colour, decoding.alpha})
    c.fits.push_back(f);
  if (math.reciprocal) c.fits.push_back(*math.reciprocal);
  if (noperspective) c.fits.push_back(*noperspective);
  c.conformance = nonConformance(m, c.fits, decoding);

  const std::string by = "measured by vt calibrate on " + c.renderer + ": ";
  const auto source = [&](const char* parameter, const ParameterFit& fit) {
    m.sources[parameter] = fit.fromGl45
                               ? m.sources[parameter] + " (not pinned by " + by + fit.finding + ")"
                               : by + fit.finding;
  };
  source("subpixel_bits", fitNamed(c.fits, "subpixel_bits"));
  source("fill_rule", fitNamed(c.fits, "coverage"));
  source("attributes", raster.attributes);
  source("depth", raster.depth);
  source("log2", math.log2);
  source("sqrt", math.sqrt);
  source("arithmetic", math.lerp);
  m.sources["arithmetic"] += "; " + math.texelConversion.finding;
  source("filter", filter.fit);
  source("color_conversion", colour);
  source("denormals", math.denormals);
  m.sources["block_decoding"] =
      decoding.pinned()
          ? by + "colour " + decoding.colour.finding + "; alpha " + decoding.alpha.finding
          : m.sources["block_decoding"] + " (not pinned by " + by + "colour " +
                decoding.colour.finding + "; alpha " + decoding.alpha.finding + ")";
  return c;
}

std::string calibrationJson(const Calibration& c) {
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(modelJson(c.model));
  nlohmann::ordered_json evidence = nlohmann::ordered_json::array();
  for (const ParameterFit& fit : c.fits) {
    nlohmann::ordered_json members = nlohmann::ordered_json::array();
    for (const MemberResult& member : fit.members)
      members.push_back({{"member", member.member}, {"mismatches", member.mismatches}});
    evidence.push_back({{"parameter", fit.parameter},
                        {"finding", fit.finding},
                        {"probe", fit.probe},
                        {"probes", fit.probes},
                        {"members", members},
                        {"chosen", fit.chosen},
                        {"mismatches", fit.mismatches},
                        {"largest_residual", fit.largestResidual},
                        {"unit", fit.unit},
                        {"pinned", fit.pinned},
                        {"gl45_kept", fit.fromGl45}});
  }
  json["calibration"] = {{"gl_renderer", c.renderer},
                         {"gl_version", c.version},
                         {"gl_vendor", c.vendor},
                         {"point", arithmeticPointName(c.model.arithmetic)},
                         {"parameters", evidence}};
  return json.dump(2) + "\n";
}

}  // namespace vt::calibrate
