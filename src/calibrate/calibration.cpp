#include "calibrate/calibration.h"

#include <epoxy/gl.h>
#include <stdlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "build/synthetic_texture.h"
#include "calibrate/coverage_fit.h"
#include "calibrate/probe_draws.h"
#include "format/virtual_texture_reader.h"
#include "reference/linear_filter.h"
#include "reference/profile_arithmetic.h"
#include "reference/renderer.h"
#include "render/precision_model_file.h"

namespace vt::calibrate {
namespace {

constexpr double kFloatUlp = 0x1p-23;

bool sameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

// The distance of `got` from `exact` in units of the float spacing at `exact` (2^(e - 23) for
// |exact| in [2^e, 2^(e + 1))), the unit of the GLSL precision table.
double ulpsFrom(double got, double exact) {
  if (exact == 0.0) return got == 0.0 ? 0.0 : std::fabs(got) / 0x1p-149;
  const double spacing = std::ldexp(1.0, std::ilogb(exact) - 23);
  return std::fabs(got - exact) / spacing;
}

std::string glString(GLenum name) {
  const GLubyte* text = glGetString(name);
  return text ? reinterpret_cast<const char*>(text) : "";
}

// A measured error widened to twice the largest seen (a sample cannot prove a maximum), at least
// `floor`.
double widened(double largest, double floor) { return std::max(2.0 * largest, floor); }

std::string describe(uint64_t mismatches, uint64_t probes) {
  return std::to_string(mismatches) + " of " + std::to_string(probes) + " values differ";
}

// ---------------------------------------------------------------------------------------------
// Shader arithmetic: log2, sqrt, denormals, the unorm8 conversion, the lerps.

struct ShaderMath {
  ParameterFit log2, sqrt, denormals, conversion;
  Log2Arithmetic log2Arithmetic = Log2Arithmetic::kBounded;
  double log2Absolute = 0, log2Ulps = 0, sqrtUlps = 0, conversionUlps = 0;
  bool flushesDenormals = false;
};

// 65,536 positive normal floats: every exponent, random mantissas (a fixed seed), 1 and the
// powers of two among them.
std::vector<glm::vec4> mathInputs() {
  std::mt19937 random(20261123);
  std::vector<glm::vec4> inputs(65536);
  for (size_t i = 0; i < inputs.size(); ++i) {
    const uint32_t exponent = 1 + static_cast<uint32_t>(i % 254);
    const uint32_t mantissa = i % 509 == 0 ? 0u : static_cast<uint32_t>(random()) >> 9;
    inputs[i] = glm::vec4(std::bit_cast<float>((exponent << 23) | mantissa), 1.0f, 0.0f, 0.0f);
  }
  return inputs;
}

ShaderMath measureShaderMath() {
  ShaderMath m;
  ShaderProbe probe;
  probe.body = "result = vec4(log2(x.x), sqrt(x.x), x.z * x.y, 0.0);";
  probe.inputs = mathInputs();
  probe.inputs[0].z = 0x1p-130f;  // a denormal, times the 1 in y
  const std::vector<glm::vec4> out = runShaderProbe(probe);

  uint64_t notLlvmpipe = 0, notSoftpipe = 0, notIeee = 0, notSqrt = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const float x = probe.inputs[i].x;
    notLlvmpipe += !sameBits(out[i].x, reference::llvmpipeLog2(x));
    notSoftpipe += !sameBits(out[i].x, reference::softpipeLog2(x));
    notIeee += !sameBits(out[i].x, std::log2(x));
    const double exact = std::log2(static_cast<double>(x));
    if (x >= 0.5f && x <= 2.0f)
      m.log2Absolute = std::max(m.log2Absolute, std::fabs(out[i].x - exact));
    else
      m.log2Ulps = std::max(m.log2Ulps, ulpsFrom(out[i].x, exact));
    notSqrt += !sameBits(out[i].y, std::sqrt(x));
    m.sqrtUlps = std::max(m.sqrtUlps, ulpsFrom(out[i].y, std::sqrt(static_cast<double>(x))));
  }
  const uint64_t n = out.size();
  m.log2 = {"log2", "", n, 0, 0, false, false};
  if (notLlvmpipe == 0) {
    m.log2Arithmetic = Log2Arithmetic::kLlvmpipe;
    m.log2.finding = "llvmpipe's polynomial (DESIGN section 7, rule 8), bit for bit";
    m.log2.pinned = true;
  } else if (notIeee == 0) {
    m.log2Arithmetic = Log2Arithmetic::kIeee;
    m.log2.finding = "the C library's log2f, bit for bit";
    m.log2.pinned = true;
  } else if (notSoftpipe == 0) {
    m.log2Arithmetic = Log2Arithmetic::kSoftpipe;
    m.log2.finding =
        "softpipe's logf(x) * 1.442695f (reference/softpipe-arithmetic.md, 5.2), bit for bit";
    m.log2.pinned = true;
  } else {
    m.log2.mismatches = std::min({notLlvmpipe, notIeee, notSoftpipe});
    m.log2.largestResidual = m.log2Ulps;
    m.log2.finding = "neither llvmpipe's polynomial (" + describe(notLlvmpipe, n) +
                     ") nor log2f (" + describe(notIeee, n) + ") nor softpipe's logf * log2(e) (" +
                     describe(notSoftpipe, n) + "): largest error inside [0.5, 2] " +
                     std::to_string(m.log2Absolute) + ", outside " + std::to_string(m.log2Ulps) +
                     " ulps";
  }
  m.sqrt = {"sqrt", "", n, notSqrt, notSqrt ? m.sqrtUlps : 0.0, notSqrt == 0, false};
  m.sqrt.finding = notSqrt == 0 ? "IEEE sqrt, correctly rounded, bit for bit"
                                : describe(notSqrt, n) + " from IEEE sqrt, largest " +
                                      std::to_string(m.sqrtUlps) + " ulps";
  m.flushesDenormals = out[0].z == 0.0f;
  m.denormals = {"denormals",
                 m.flushesDenormals ? "a denormal times 1 gives 0: flushed to zero"
                                    : "a denormal times 1 stays a denormal: kept",
                 1,
                 0,
                 0,
                 true,
                 false};

  // texelFetch of every unorm8 value.
  ShaderProbe fetch;
  fetch.body = "result = texelFetch(uTexture, ivec2(int(x.x), 0), 0);";
  fetch.width = 256;
  for (int k = 0; k < 256; ++k) {
    fetch.inputs.push_back(glm::vec4(static_cast<float>(k), 0, 0, 0));
    const auto v = static_cast<uint8_t>(k);
    fetch.texels.push_back(glm::u8vec4(v, static_cast<uint8_t>(255 - k), v, 255));
  }
  fetch.textureSize = {256, 1};
  const std::vector<glm::vec4> fetched = runShaderProbe(fetch);
  uint64_t notConverted = 0;
  for (int k = 0; k < 256; ++k) {
    const glm::vec4 expected = reference::unorm8ToFloat(fetch.texels[static_cast<size_t>(k)]);
    for (int c = 0; c < 4; ++c) {
      const float got = fetched[static_cast<size_t>(k)][c];
      notConverted += !sameBits(got, expected[c]);
      m.conversionUlps = std::max(m.conversionUlps, ulpsFrom(got, expected[c]));
    }
  }

  // The shader's lerps (the exact bilinear filter's rows and columns, the trilinear blend):
  // a + (b - a) * w under `precise`, colours of unorm8 values or any in [0, 1], weights in [0, 1).
  ShaderProbe blend;
  blend.body = "result = vec4(x.x + (x.y - x.x) * x.z, 0.0, 0.0, 0.0);";
  std::mt19937 random(20261124);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto colour = [&]() {
    return random() % 2 ? static_cast<float>(random() % 256) * (1.0f / 255.0f) : unit(random);
  };
  for (int i = 0; i < 16384; ++i) {
    const float a = colour(), b = colour();
    blend.inputs.push_back(glm::vec4(a, b, unit(random), 0.0f));
  }
  const std::vector<glm::vec4> blended = runShaderProbe(blend);
  uint64_t notBlended = 0;
  double blendUlps = 0;
  for (size_t i = 0; i < blended.size(); ++i) {
    const glm::vec4 in = blend.inputs[i];
    const float expected = in.x + (in.y - in.x) * in.z;  // no contraction (-ffp-contract=off)
    notBlended += !sameBits(blended[i].x, expected);
    blendUlps = std::max(blendUlps, ulpsFrom(blended[i].x, expected));
  }
  const uint64_t values = 1024 + blended.size();
  const uint64_t mismatched = notConverted + notBlended;
  m.conversionUlps = std::max(m.conversionUlps, blendUlps);
  m.conversion = {"arithmetic", "",    values, mismatched, mismatched ? m.conversionUlps : 0.0,
                  mismatched == 0, false};
  m.conversion.finding =
      (notConverted == 0 ? std::string("texelFetch of unorm8 k gives k * (1 / 255), bit for bit")
                         : describe(notConverted, 1024) + " from k * (1 / 255)") +
      "; " +
      (notBlended == 0 ? std::string("the lerp a + (b - a) * w rounds each operation, bit for bit")
                       : describe(notBlended, blended.size()) +
                             " lerps a + (b - a) * w differ from rounding each operation") +
      (mismatched ? ", largest " + std::to_string(m.conversionUlps) + " ulps" : std::string());
  return m;
}

// ---------------------------------------------------------------------------------------------
// GL_LINEAR.

struct FilterFit {
  ParameterFit fit;
  FilterArithmetic arithmetic = FilterArithmetic::kBounded;
  int subTexelBits = 0;
  double errorUnits = 0;
};

// Bilinear filtering of `texels` at texel position `x` (centres at +0.5) with positions rounded
// to 2^-bits texel and real-valued weights and lerps, in units of 1/255.
glm::dvec4 snappedBilinear(const std::vector<glm::u8vec4>& texels, int side, glm::vec2 x,
                           int bits) {
  const double step = std::ldexp(1.0, -bits);
  glm::dvec2 p;
  for (int k = 0; k < 2; ++k) p[k] = std::nearbyint((x[k] - 0.5) / step) * step;
  const glm::dvec2 base = glm::floor(p), f = p - base;
  const auto at = [&](int dx, int dy) {
    const int i = std::clamp(static_cast<int>(base.x) + dx, 0, side - 1);
    const int j = std::clamp(static_cast<int>(base.y) + dy, 0, side - 1);
    return glm::dvec4(texels[static_cast<size_t>(j * side + i)]);
  };
  const glm::dvec4 row0 = at(0, 0) + (at(1, 0) - at(0, 0)) * f.x;
  const glm::dvec4 row1 = at(0, 1) + (at(1, 1) - at(0, 1)) * f.x;
  return row0 + (row1 - row0) * f.y;
}

FilterFit measureFilter() {
  constexpr int kSide = 16;
  std::mt19937 random(7);
  ShaderProbe probe;
  probe.body = "result = textureLod(uTexture, x.xy, 0.0);";
  probe.textureSize = {kSide, kSide};
  probe.linear = true;
  for (int i = 0; i < kSide * kSide; ++i) {
    const uint32_t bits = static_cast<uint32_t>(random());
    probe.texels.push_back(
        glm::u8vec4(bits & 255, (bits >> 8) & 255, (bits >> 16) & 255, bits >> 24));
  }
  // Texel positions: half random, half on 1/256-texel steps and one float beside them.
  std::vector<glm::vec2> positions;
  for (int i = 0; i < 32768; ++i) {
    glm::vec2 t;
    for (int k = 0; k < 2; ++k) {
      const uint32_t r = static_cast<uint32_t>(random());
      float v = static_cast<float>(r % (kSide * 4096)) / 4096.0f;
      if (i % 2 == 1) {
        v = static_cast<float>(r % (kSide * 256)) / 256.0f;
        if (r & (1u << 30)) v = std::nextafter(v, (r & (1u << 31)) ? 0.0f : 100.0f);
      }
      t[k] = v;
    }
    positions.push_back(t);
    probe.inputs.push_back(glm::vec4(t / static_cast<float>(kSide), 0.0f, 0.0f));  // exact
  }
  const std::vector<glm::vec4> out = runShaderProbe(probe);
  const auto fetch8 = [&](reference::ivec2 t) {
    return probe.texels[static_cast<size_t>(t.y * kSide + t.x)];
  };
  uint64_t notLlvmpipe = 0, notFloat = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const reference::vec4 llvm =
        reference::sampleLinear(fetch8, positions[i], {kSide, kSide}, PrecisionProfile::kLlvmpipe);
    const reference::vec4 ieee =
        reference::sampleLinear(fetch8, positions[i], {kSide, kSide}, PrecisionProfile::kExact);
    for (int c = 0; c < 4; ++c) {
      // The 8-bit filter's result is a whole number of 1/255 (how it becomes a float, k / 255
      // or k * (1 / 255), does not reach an RGBA8 target).
      notLlvmpipe += std::nearbyint(out[i][c] * 255.0f) != std::nearbyint(llvm[c] * 255.0f) ||
                     std::fabs(out[i][c] * 255.0f - std::nearbyint(out[i][c] * 255.0f)) > 1e-3f;
      notFloat += !sameBits(out[i][c], ieee[c]);
    }
  }
  const uint64_t n = out.size() * 4;
  FilterFit result;
  result.fit = {"filter", "", n, 0, 0, true, false};
  if (notLlvmpipe == 0) {
    result.arithmetic = FilterArithmetic::kLlvmpipe8Bit;
    result.fit.finding =
        "8-bit weights and fixed-point lerps (DESIGN section 7, rule 9): every sample the same "
        "8-bit value";
    return result;
  }
  if (notFloat == 0) {
    result.arithmetic = FilterArithmetic::kFloat;
    result.fit.finding = "float positions, weights and lerps, bit for bit";
    return result;
  }
  // Bounded: the sub-texel precision whose real-valued filter leaves the smallest largest error.
  double best = 1e30;
  for (int bits = 4; bits <= 12; ++bits) {
    double largest = 0;
    for (size_t i = 0; i < out.size(); ++i) {
      const glm::dvec4 expected = snappedBilinear(probe.texels, kSide, positions[i], bits);
      for (int c = 0; c < 4; ++c)
        largest = std::max(largest, std::fabs(out[i][c] * 255.0 - expected[c]));
    }
    if (largest < best) best = largest, result.subTexelBits = bits;
  }
  result.errorUnits = widened(best, 1.0);
  result.fit.pinned = false;
  result.fit.mismatches = std::min(notLlvmpipe, notFloat);
  result.fit.largestResidual = best;
  result.fit.finding = "neither 8-bit weights (" + describe(notLlvmpipe, n) + ") nor float (" +
                       describe(notFloat, n) + "): closest with positions on 2^-" +
                       std::to_string(result.subTexelBits) + " texel, largest error " +
                       std::to_string(best) + " / 255";
  return result;
}

// ---------------------------------------------------------------------------------------------
// Colour conversion.

ParameterFit measureColourConversion() {
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
  uint64_t other = 0;
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 4; ++c) other += out[i][c] != nearest[i];
  const uint64_t n = out.size() * 4;
  return {"color_conversion",
          other == 0 ? "always the nearest unorm8 value"
                     : describe(other, n) + " from the nearest unorm8 value: either of the two",
          n,
          other,
          other ? 1.0 : 0.0,
          other == 0,
          false};
}

// ---------------------------------------------------------------------------------------------
// Rasterization, attributes and depth.

struct RasterCounts {
  uint64_t pixels = 0, coverage = 0, shared = 0, attributes = 0, depth = 0;
  double attributeUlps = 0, depthUlps = 0;
};

struct RasterFits {
  ParameterFit coverage, attributes, depth;
  PrecisionProfile arithmetic = PrecisionProfile::kExact;
  bool coveragePinned = false;
  double attributeUlps = 0, depthUlps = 0;
  bool depthPinned = false;
};

// A scratch folder for the oracle's texture, removed with it.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "vt-calibrate-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder");
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// `flushesDenormals`: what the shader-math probes found, which decides the arithmetic when no
// plane evaluation reproduces the attributes bit for bit (llvmpipe's arithmetic flushes them).
RasterFits measureRasterization(bool flushesDenormals) {
  const ScratchFolder folder;
  writeSyntheticTexture(
      folder.path() / "t.vt",
      {{.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4}, std::nullopt});
  const VirtualTextureReader reader(folder.path() / "t.vt");
  const reference::ResidentTexture texture(reader);
  const Viewport viewport{160, 120};
  // The arithmetics the oracle can compute in, each drawing the same probes.
  constexpr std::array<PrecisionProfile, 3> kCandidates = {
      PrecisionProfile::kLlvmpipe, PrecisionProfile::kExact, PrecisionProfile::kSoftpipe};
  std::array<RasterCounts, kCandidates.size()> counts{};
  for (const unsigned seed : {1u, 2u, 3u}) {
    const ClipSpaceMesh mesh = randomTriangles(seed, 120);
    const RasterReadback gl = drawTriangles(mesh, viewport);
    for (size_t a = 0; a < kCandidates.size(); ++a) {
      RenderSettings settings;
      settings.debugChannels = true;
      settings.viewport = viewport;
      settings.threads = 1;
      settings.profile = kCandidates[a];
      const Frame oracle = reference::renderFrame(mesh, texture, settings);
      RasterCounts& c = counts[a];
      for (size_t i = 0; i < oracle.triangle.size(); ++i) {
        ++c.pixels;
        if (gl.triangle[i] != oracle.triangle[i]) {
          ++c.coverage;
          continue;
        }
        if (gl.triangle[i] < 0) continue;
        ++c.shared;
        bool differs = false;
        for (int k = 0; k < 2; ++k) {
          differs |= !sameBits(gl.uv[i][k], oracle.uv[i][k]);
          c.attributeUlps = std::max(
              c.attributeUlps, std::fabs(gl.uv[i][k] - oracle.uv[i][k]) /
                                   (std::max(std::fabs(oracle.uv[i][k]), 1e-30f) * kFloatUlp));
        }
        for (int k = 0; k < 4; ++k)
          differs |= !sameBits(gl.derivatives[i][k], oracle.derivatives[i][k]);
        c.attributes += differs;
        if (!sameBits(gl.depth[i], oracle.depth[i])) {
          ++c.depth;
          c.depthUlps = std::max(c.depthUlps, std::fabs(gl.depth[i] - oracle.depth[i]) /
                                                  (std::max(oracle.depth[i], 1e-30f) * kFloatUlp));
        }
      }
    }
  }
  RasterFits fits;
  // The arithmetic that reproduces coverage and every attribute bit for bit, in the order of
  // kCandidates; else the one whose coverage differs least, on a tie llvmpipe's where denormals
  // are flushed (its arithmetic flushes them) and IEEE otherwise.
  size_t chosenIndex = kCandidates.size();
  for (size_t a = 0; a < kCandidates.size() && chosenIndex == kCandidates.size(); ++a)
    if (counts[a].coverage == 0 && counts[a].attributes == 0) chosenIndex = a;
  const bool attributesPinned = chosenIndex < kCandidates.size();
  if (!attributesPinned) {
    chosenIndex = flushesDenormals ? 0 : 1;
    for (size_t a = 0; a < kCandidates.size(); ++a)
      if (counts[a].coverage < counts[chosenIndex].coverage) chosenIndex = a;
  }
  fits.arithmetic = kCandidates[chosenIndex];
  const RasterCounts& chosen = counts[chosenIndex];
  const bool softpipe = fits.arithmetic == PrecisionProfile::kSoftpipe;
  fits.coveragePinned = chosen.coverage == 0;
  fits.coverage = {"coverage",
                   !fits.coveragePinned
                       ? std::to_string(chosen.coverage) + " of " + std::to_string(chosen.pixels) +
                             " pixels show another triangle: sub-pixel bits and fill rule not "
                             "pinned, the gl45 values kept"
                   : softpipe ? "every pixel shows the triangle of softpipe's unsnapped float "
                                "scanline spans (reference/softpipe-arithmetic.md, 2.3)"
                              : "every pixel shows the triangle of 8-bit snapping and the oracle's "
                                "tie rule (DESIGN section 7, rules 2 and 4)",
                   chosen.pixels,
                   chosen.coverage,
                   0,
                   fits.coveragePinned,
                   !fits.coveragePinned};
  const std::string exactly = fits.arithmetic == PrecisionProfile::kLlvmpipe
                                  ? "llvmpipe's fused planes give them (DESIGN section 7, rules 1, "
                                    "3 and 6)"
                              : softpipe ? "softpipe's planes, stepped per quad and divided, give "
                                           "them (reference/softpipe-arithmetic.md, 3)"
                                         : "IEEE planes give them";
  fits.attributeUlps = attributesPinned ? 0.0 : widened(chosen.attributeUlps, 1.0);
  fits.attributes = {
      "attributes",
      attributesPinned
          ? "texture coordinates and fine derivatives as " + exactly + ", bit for bit"
          : std::to_string(chosen.attributes) + " of " + std::to_string(chosen.shared) +
                " pixels' coordinates or derivatives differ, largest relative "
                "error " +
                std::to_string(chosen.attributeUlps) + " ulps",
      chosen.shared,
      attributesPinned ? 0 : chosen.attributes,
      attributesPinned ? 0.0 : chosen.attributeUlps,
      attributesPinned,
      false};
  fits.depthPinned = chosen.depth == 0 && chosen.coverage == 0;
  fits.depthUlps = fits.depthPinned ? 0.0 : widened(chosen.depthUlps, 1.0);
  fits.depth = {"depth",
                fits.depthPinned
                    ? "the stored 32F depth as the oracle computes it, bit for bit"
                    : std::to_string(chosen.depth) + " of " + std::to_string(chosen.shared) +
                          " pixels' depth differs, largest " + std::to_string(chosen.depthUlps) +
                          " ulps",
                chosen.shared,
                chosen.depth,
                fits.depthPinned ? 0.0 : chosen.depthUlps,
                fits.depthPinned,
                false};
  return fits;
}

// ---------------------------------------------------------------------------------------------
// Sub-pixel grid and fill rule from coverage alone (coverage_fit.h): evidence on every
// implementation, and where no arithmetic of the oracle reproduces coverage, the grid that bounds
// how far vertices move.

struct GridFit {
  ParameterFit fit;
  int subpixelBits = 0;  // the coarsest consistent grid; 0: none fits
};

GridFit measureSubpixelGrid() {
  const Viewport viewport{1024, 512};
  const std::vector<CoverageProbe> probes = coverageProbes(12, viewport);
  const RasterReadback drawn = drawTriangles(coverageMesh(probes, viewport), viewport);
  const CoverageFit fit = fitCoverage(probes, viewport, drawn.triangle);
  GridFit result;
  result.subpixelBits = fit.coarsestBits();
  const std::string over = std::to_string(fit.pixels) + " pixels of " +
                           std::to_string(probes.size()) +
                           " probe triangles at 2^-12 offsets around pixel centres";
  std::string finding;
  if (fit.consistent.empty()) {
    finding = "no snapping grid of 1 to 14 bits nor unsnapped vertices with a fixed tie rule "
              "covers the " + over + " as drawn; closest: " + describe(fit.closest) + " (" +
              std::to_string(fit.closestMismatches) + " pixels differ)";
  } else {
    finding = "the " + over + " are covered as drawn by " +
              (fit.consistent.size() == 1
                   ? std::string("exactly one rasterizer of the grid family")
                   : std::to_string(fit.consistent.size()) +
                         " rasterizers of the grid family, the coarsest " +
                         std::to_string(result.subpixelBits) + " sub-pixel bits") +
              ":";
    for (size_t i = 0; i < fit.consistent.size() && i < 6; ++i)
      finding += (i ? "; " : " ") + describe(fit.consistent[i]);
    if (fit.consistent.size() > 6) finding += "; ...";
  }
  result.fit = {"subpixel_bits",
                finding,
                fit.pixels,
                fit.consistent.empty() ? fit.closestMismatches : 0,
                0,
                !fit.consistent.empty(),
                fit.consistent.empty()};
  return result;
}

}  // namespace

Calibration calibrate() {
  Calibration c;
  c.renderer = glString(GL_RENDERER);
  c.version = glString(GL_VERSION);
  c.vendor = glString(GL_VENDOR);
  const ShaderMath math = measureShaderMath();
  const FilterFit filter = measureFilter();
  const ParameterFit colour = measureColourConversion();
  const RasterFits raster = measureRasterization(math.flushesDenormals);
  const GridFit grid = measureSubpixelGrid();

  // Start from gl45: what no probe pins keeps the specification's slack.
  PrecisionModel& m = c.model;
  m = gl45Model();
  m.name = "calibrated";
  m.renderer = c.renderer;
  m.glVersion = c.version;
  m.arithmetic = raster.arithmetic;
  if (raster.coveragePinned) {
    m.subpixelBits = 8;  // with the fill rule pinned: the arithmetic's own coverage
    m.fillRulePinned = true;
  } else if (grid.subpixelBits > 0) {
    // Coverage is not the oracle's, but vertices move at most 2^-bits pixel: the result sets'
    // corner boxes shrink from gl45's 2^-4 to that; ties stay free.
    m.subpixelBits = grid.subpixelBits;
  }
  m.depthUlps = raster.depthUlps;
  m.depthRoundsToNearest = raster.depthPinned;
  m.attributeUlps = raster.attributeUlps;
  m.log2 = math.log2Arithmetic;
  m.log2AbsoluteError = 0;
  m.log2Ulps = 0;
  // The oracle computes its arithmetic's own log2: another one measured bit for bit is still
  // free under it.
  if (m.log2 != Log2Arithmetic::kBounded && m.log2 != log2Of(m.arithmetic))
    m.log2 = Log2Arithmetic::kBounded;
  if (m.log2 == Log2Arithmetic::kBounded) {
    m.log2AbsoluteError = widened(math.log2Absolute, 0x1p-23);
    m.log2Ulps = widened(math.log2Ulps, 1.0);
  }
  m.sqrtUlps = math.sqrt.pinned ? 0.0 : widened(math.sqrtUlps, 1.0);
  m.arithmeticUlps = math.conversion.pinned ? 0.0 : widened(math.conversionUlps, 1.0);
  m.filter = filter.arithmetic;
  m.subTexelBits = filter.subTexelBits;
  m.filterErrorUnits = filter.errorUnits;
  m.colorRoundsToNearest = colour.pinned;
  m.denormalsPinned = math.flushesDenormals == flushesDenormals(m.arithmetic);

  c.fits = {raster.coverage, grid.fit,       raster.attributes, raster.depth,
            math.log2,       math.sqrt,      math.conversion,   filter.fit,
            colour,          math.denormals};
  if (!m.denormalsPinned) {
    c.fits.back().pinned = false;
    c.fits.back().finding += ", unlike the arithmetic chosen: free";
  }
  const std::string by = "measured by vt calibrate on " + c.renderer + ": ";
  const auto source = [&](const char* parameter, const ParameterFit& fit) {
    m.sources[parameter] = fit.fromGl45
                               ? m.sources[parameter] + " (not pinned by " + by + fit.finding + ")"
                               : by + fit.finding;
  };
  if (raster.coveragePinned) {
    m.sources["subpixel_bits"] = by + raster.coverage.finding + "; " + grid.fit.finding;
  } else {
    source("subpixel_bits", grid.fit);
  }
  source("fill_rule", raster.coverage);
  source("attributes", raster.attributes);
  source("depth", raster.depth);
  source("log2", math.log2);
  source("sqrt", math.sqrt);
  source("arithmetic", math.conversion);
  source("filter", filter.fit);
  source("color_conversion", colour);
  source("denormals", c.fits.back());
  return c;
}

std::string calibrationJson(const Calibration& c) {
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(modelJson(c.model));
  nlohmann::ordered_json evidence = nlohmann::ordered_json::array();
  for (const ParameterFit& fit : c.fits)
    evidence.push_back({{"parameter", fit.parameter},
                        {"finding", fit.finding},
                        {"probes", fit.probes},
                        {"mismatches", fit.mismatches},
                        {"largest_residual", fit.largestResidual},
                        {"pinned", fit.pinned},
                        {"gl45_kept", fit.fromGl45}});
  json["calibration"] = {{"gl_renderer", c.renderer},
                         {"gl_version", c.version},
                         {"gl_vendor", c.vendor},
                         {"parameters", evidence}};
  return json.dump(2) + "\n";
}

}  // namespace vt::calibrate
