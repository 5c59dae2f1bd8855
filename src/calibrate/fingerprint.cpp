#include "calibrate/fingerprint.h"

#include <stdlib.h>

#include <filesystem>
#include <random>

#include "build/synthetic_texture.h"
#include "calibrate/float_bits.h"
#include "calibrate/probe_draws.h"
#include "format/virtual_texture_reader.h"
#include "reference/linear_filter.h"
#include "reference/renderer.h"
#include "reference/shader_math.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"

namespace vt::calibrate {
namespace {

std::string log2Differs(const Arithmetic& a) {
  std::mt19937 random(31);
  ShaderProbe probe;
  probe.body = "result = vec4(log2(x.x), 0.0, 0.0, 0.0);";
  for (int i = 0; i < 4096; ++i) {
    const uint32_t exponent = 1 + static_cast<uint32_t>(i % 254);
    probe.inputs.push_back(
        glm::vec4(std::bit_cast<float>((exponent << 23) | (static_cast<uint32_t>(random()) >> 9))));
  }
  const std::vector<glm::vec4> out = runShaderProbe(probe);
  for (size_t i = 0; i < out.size(); ++i)
    if (!sameBits(out[i].x, reference::log2Of(a.log2, probe.inputs[i].x)))
      return "log2 differs from " + std::string(nameOf(kLog2FormNames, a.log2));
  return "";
}

std::string texelsDiffer(const Arithmetic& a) {
  std::mt19937 random(32);
  ShaderProbe fetch;
  fetch.body = "result = texelFetch(uTexture, ivec2(int(x.x), 0), 0);";
  for (int k = 0; k < 256; ++k) {
    fetch.inputs.push_back(glm::vec4(static_cast<float>(k), 0, 0, 0));
    fetch.texels.push_back(glm::u8vec4(k, 255 - k, k, 255));
  }
  fetch.textureSize = {256, 1};
  const std::vector<glm::vec4> fetched = runShaderProbe(fetch);
  for (size_t k = 0; k < 256; ++k) {
    const glm::vec4 expected = reference::unorm8ToFloat(fetch.texels[k], a.texelConversion);
    for (int c = 0; c < 4; ++c)
      if (!sameBits(fetched[k][c], expected[c])) return "texelFetch's conversion differs";
  }
  ShaderProbe linear;
  linear.body = "result = textureLod(uTexture, x.xy, 0.0);";
  linear.textureSize = {24, 40};
  linear.linear = true;
  for (int i = 0; i < 24 * 40; ++i) {
    const uint32_t bits = static_cast<uint32_t>(random());
    linear.texels.push_back(
        glm::u8vec4(bits & 255, (bits >> 8) & 255, (bits >> 16) & 255, bits >> 24));
  }
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 4096; ++i)
    linear.inputs.push_back(glm::vec4(unit(random), unit(random), 0, 0));
  const std::vector<glm::vec4> sampled = runShaderProbe(linear);
  const auto fetch8 = [&](glm::ivec2 t) {
    return linear.texels[static_cast<size_t>(t.y * 24 + t.x)];
  };
  for (size_t i = 0; i < sampled.size(); ++i) {
    const glm::vec4 expected = reference::sampleLinearAt(
        fetch8, glm::vec2(linear.inputs[i]), linear.textureSize, a.filter, a.texelConversion);
    for (int c = 0; c < 4; ++c) {
      const bool same =
          a.filter.weights == FilterWeights::kFixedPoint8
              ? std::nearbyint(sampled[i][c] * 255.0f) == std::nearbyint(expected[c] * 255.0f)
              : sameBits(sampled[i][c], expected[c]);
      if (!same) return "GL_LINEAR differs";
    }
  }
  return "";
}

std::string denormalsDiffer(const Arithmetic& a) {
  for (const bool clipped : {true, false}) {
    ShaderProbe probe;
    probe.body = "result = vec4(x.z * x.y, 0.0, 0.0, 0.0);";
    probe.width = 4;
    probe.inputs.assign(16, glm::vec4(0.0f, 1.0f, 0x1p-130f, 0.0f));
    probe.clipped = clipped;
    for (const glm::vec4& v : runShaderProbe(probe))
      if ((v.x == 0.0f) != a.flushDenormals) return "the denormal mode differs";
  }
  return "";
}

// A scratch texture for the oracle, removed with it.
class ScratchTexture {
 public:
  ScratchTexture() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "vt-fingerprint-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder");
    folder_ = pattern;
    writeSyntheticTexture(
        folder_ / "t.vt",
        {{.pageSize = 16, .border = 2, .levelCount = 3, .channels = 4}, std::nullopt});
  }
  ~ScratchTexture() {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
  std::filesystem::path file() const { return folder_ / "t.vt"; }

 private:
  std::filesystem::path folder_;
};

std::string rasterDiffers(const Arithmetic& a) {
  const ScratchTexture scratch;
  const VirtualTextureReader reader(scratch.file());
  const reference::ResidentTexture texture(reader);
  const Viewport viewport{64, 48};
  const ClipSpaceMesh mesh = randomTriangles(33, 40);
  const RasterReadback gl = drawTriangles(mesh, viewport);
  RenderSettings settings;
  settings.viewport = viewport;
  settings.debugChannels = true;
  settings.arithmetic = a;
  const Frame oracle = reference::renderFrame(mesh, texture, settings);
  for (size_t i = 0; i < oracle.triangle.size(); ++i) {
    if (gl.triangle[i] != oracle.triangle[i]) return "coverage or depth order differs";
    if (gl.triangle[i] < 0) continue;
    for (int k = 0; k < 2; ++k)
      if (!sameBits(gl.uv[i][k], oracle.uv[i][k])) return "texture coordinates differ";
    for (int k = 0; k < 4; ++k)
      if (!sameBits(gl.derivatives[i][k], oracle.derivatives[i][k]))
        return "fine derivatives differ";
    if (!sameBits(gl.depth[i], oracle.depth[i])) return "depth differs";
  }
  return "";
}

}  // namespace

Fingerprint fingerprint(const Arithmetic& arithmetic, bool denormalsPinned) {
  for (const auto& check : {log2Differs, texelsDiffer, rasterDiffers}) {
    const std::string differs = check(arithmetic);
    if (!differs.empty()) return {false, differs};
  }
  if (denormalsPinned)
    if (const std::string differs = denormalsDiffer(arithmetic); !differs.empty())
      return {false, differs};
  return {true, ""};
}

std::optional<std::string> fingerprintedPoint() {
  for (const std::string& name : arithmeticPointNames()) {
    const PrecisionModel model = namedModel(name);
    if (fingerprint(model.arithmetic, model.denormalsPinned).reproduced) return name;
  }
  return std::nullopt;
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
