#include "calibrate/fingerprint.h"

#include <array>
#include <bit>
#include <cmath>
#include <random>

#include "calibrate/decoding_fit.h"
#include "calibrate/filter_fit.h"
#include "calibrate/float_bits.h"
#include "common/random_draws.h"
#include "probes/probe_draws.h"
#include "calibrate/probe_texture.h"
#include "calibrate/raster_fit.h"
#include "reference/linear_filter.h"
#include "reference/renderer.h"
#include "reference/shader_math.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"

namespace vt::calibrate {
namespace {

// The fingerprint's draws, made once on the current context and compared with any number of
// arithmetics.
struct FingerprintDraws {
  ShaderProbe log2, fetch, linear;
  std::vector<glm::vec4> log2Out, fetchOut, linearOut;
  ClipSpaceMesh mesh;
  RasterReadback raster;
  std::array<std::vector<glm::vec4>, 2> denormals;  // a clipped and an unclipped draw
  std::vector<glm::vec4> bc1, bc3;                  // the block-decoding probes
};

constexpr Viewport kRasterViewport{64, 48};

FingerprintDraws drawFingerprint() {
  FingerprintDraws d;
  std::mt19937 random(31);
  d.log2.body = "result = vec4(log2(x.x), 1.0 / x.x, sqrt(x.x), 0.0);";
  for (int i = 0; i < 4096; ++i) {
    const uint32_t exponent = 1 + static_cast<uint32_t>(i % 254);
    d.log2.inputs.push_back(
        glm::vec4(std::bit_cast<float>((exponent << 23) | (static_cast<uint32_t>(random()) >> 9))));
  }
  d.log2Out = runShaderProbe(d.log2);

  random.seed(32);
  d.fetch.body = "result = texelFetch(uTexture, ivec2(int(x.x), 0), 0);";
  for (int k = 0; k < 256; ++k) {
    d.fetch.inputs.push_back(glm::vec4(static_cast<float>(k), 0, 0, 0));
    d.fetch.texels.push_back(glm::u8vec4(k, 255 - k, k, 255));
  }
  d.fetch.textureSize = {256, 1};
  d.fetchOut = runShaderProbe(d.fetch);
  d.linear.body = "result = textureLod(uTexture, x.xy, 0.0);";
  d.linear.textureSize = {24, 40};
  d.linear.linear = true;
  for (int i = 0; i < 24 * 40; ++i) {
    const uint32_t bits = static_cast<uint32_t>(random());
    d.linear.texels.push_back(
        glm::u8vec4(bits & 255, (bits >> 8) & 255, (bits >> 16) & 255, bits >> 24));
  }
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 4096; ++i)
    d.linear.inputs.push_back(glm::vec4(drawPoint([&] { return unit(random); }), 0, 0));
  d.linearOut = runShaderProbe(d.linear);

  d.mesh = randomTriangles(33, 40);
  d.raster = drawTriangles(d.mesh, kRasterViewport);

  for (const bool clipped : {true, false}) {
    ShaderProbe probe;
    probe.body = "result = vec4(x.z * x.y, 0.0, 0.0, 0.0);";
    probe.width = 4;
    probe.inputs.assign(16, glm::vec4(0.0f, 1.0f, 0x1p-130f, 0.0f));
    probe.clipped = clipped;
    d.denormals[clipped ? 0 : 1] = runShaderProbe(probe);
  }
  d.bc1 = drawDecodingProbe(PixelFormat::kBc1);
  d.bc3 = drawDecodingProbe(PixelFormat::kBc3);
  return d;
}

// The first family in which `a` does not reproduce the draws, in words; empty when it does.
std::string differs(const FingerprintDraws& d, const reference::ResidentTexture& texture,
                    const Arithmetic& a, bool denormalsPinned) {
  for (size_t i = 0; i < d.log2Out.size(); ++i)
    if (!sameBits(d.log2Out[i].x, reference::log2Of(a, d.log2.inputs[i].x)))
      return "log2 differs from " + (a.log2Table.table
                                         ? "the measured table " + a.log2Table.table->checksum()
                                         : std::string(nameOf(kLog2FormNames, a.log2)));
  // A measured reciprocal's table, over the exponents whose reciprocal is a normal float.
  if (a.reciprocal.table)
    for (size_t i = 0; i < d.log2Out.size(); ++i) {
      const float x = d.log2.inputs[i].x;
      if (std::fabs(x) < 0x1p126f && !sameBits(d.log2Out[i].y, a.reciprocal.of(x)))
        return "the reciprocal differs from the measured table " + a.reciprocal.table->checksum();
    }
  if (a.sqrt.table)
    for (size_t i = 0; i < d.log2Out.size(); ++i)
      if (!sameBits(d.log2Out[i].z, a.sqrt.of(d.log2.inputs[i].x)))
        return "sqrt differs from the measured table " + a.sqrt.table->checksum();
  for (size_t k = 0; k < d.fetchOut.size(); ++k) {
    const glm::vec4 expected = reference::unorm8ToFloat(d.fetch.texels[k], a.texelConversion);
    for (int c = 0; c < 4; ++c)
      if (!sameBits(d.fetchOut[k][c], expected[c])) return "texelFetch's conversion differs";
  }
  for (size_t i = 0; i < d.linearOut.size(); ++i)
    if (!reproducesSample(d.linear, i, d.linearOut[i], a.filter, a.texelConversion))
      return "GL_LINEAR differs";
  RenderSettings settings;
  settings.viewport = kRasterViewport;
  settings.debugChannels = true;
  settings.arithmetic = a;
  RasterCounts counts;
  compareRaster(d.raster, reference::renderFrame(d.mesh, texture, settings), counts);
  if (counts.coverage) return "coverage or depth order differs";
  if (counts.attributes) return "texture coordinates or fine derivatives differ";
  if (counts.depth) return "depth differs";
  if (denormalsPinned)
    for (const std::vector<glm::vec4>& out : d.denormals)
      for (const glm::vec4& v : out)
        if ((v.x == 0.0f) != a.flushDenormals) return "the denormal mode differs";
  if (!reproducesDecoding(d.bc1, d.bc3, a.blockDecoding)) return "block decoding differs";
  return "";
}

// The named point the draws reproduce, if any.
std::optional<std::string> reproducedPoint(const FingerprintDraws& d,
                                           const reference::ResidentTexture& texture) {
  for (const std::string& name : arithmeticPointNames()) {
    const PrecisionModel model = namedModel(name);
    if (differs(d, texture, model.arithmetic, model.denormalsPinned).empty()) return name;
  }
  return std::nullopt;
}

}  // namespace

Fingerprint fingerprint(const Arithmetic& arithmetic, bool denormalsPinned) {
  const ProbeTexture probes(3);
  const std::string finding =
      differs(drawFingerprint(), probes.texture(), arithmetic, denormalsPinned);
  return {finding.empty(), finding};
}

std::optional<std::string> fingerprintedPoint() {
  const ProbeTexture probes(3);
  return reproducedPoint(drawFingerprint(), probes.texture());
}

PrecisionModel autoModel(const std::string& glRenderer, std::string* note) {
  note->clear();
  if (const auto file = measuredModelFile(glRenderer)) {
    const PrecisionModel measured = readModelFile(*file);
    if (!measured.pinned() && !measured.onlyDenormalsFree()) return measured;
    const Fingerprint f = fingerprint(measured.arithmetic, measured.denormalsPinned);
    if (f.reproduced) return measured;
    *note = "the measured model " + file->string() + " does not reproduce here (" + f.finding +
            "): judged under gl45; run vt calibrate";
    return gl45Model();
  }
  if (const std::optional<std::string> point = fingerprintedPoint()) return namedModel(*point);
  *note = glRenderer + " reproduces none of the pinned models (" + joinedArithmeticPointNames() +
          "): judged under gl45; vt calibrate measures a model for it";
  return gl45Model();
}

PrecisionModel resolveModelHere(const std::string& nameOrFile, const std::string& glRenderer,
                                std::string* note) {
  if (nameOrFile == "auto") return autoModel(glRenderer, note);
  note->clear();
  return resolveModel(nameOrFile, glRenderer);
}

}  // namespace vt::calibrate
