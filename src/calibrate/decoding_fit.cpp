#include "calibrate/decoding_fit.h"

#include <cmath>
#include <glm/glm.hpp>
#include <random>
#include <string>

#include "calibrate/probe_draws.h"

namespace vt::calibrate {
namespace {

constexpr int kBlocksPerSide = kDecodingProbeSide / 4;

// A float texel channel as its 8-bit value, or -1 when it is none (c / 255 within a float's
// rounding of the conversion, whichever member of texel_conversion made it).
int unorm8Of(float v) {
  const double scaled = static_cast<double>(v) * 255.0;
  const double k = std::nearbyint(scaled);
  return k >= 0 && k <= 255 && std::fabs(scaled - k) < 1e-3 ? static_cast<int>(k) : -1;
}

std::string ruleName(PaletteRule rule) { return std::string(nameOf(kPaletteRuleNames, rule)); }

}  // namespace

std::vector<glm::vec4> drawDecodingProbe(PixelFormat format) {
  ShaderProbe probe;
  probe.body = "result = texelFetch(uTexture, ivec2(x.xy), 0);";
  probe.width = kDecodingProbeSide;
  for (int y = 0; y < kDecodingProbeSide; ++y)
    for (int x = 0; x < kDecodingProbeSide; ++x)
      probe.inputs.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.0f, 0.0f);
  probe.blockFormat = format;
  probe.blocks = decodingProbeBlocks(format);
  probe.textureSize = glm::ivec2(kDecodingProbeSide);
  return runShaderProbe(probe);
}

bool reproducesDecoding(const std::vector<glm::vec4>& bc1, const std::vector<glm::vec4>& bc3,
                        BlockDecoding decoding) {
  for (const PixelFormat format : {PixelFormat::kBc1, PixelFormat::kBc3}) {
    const std::vector<glm::vec4>& measured = format == PixelFormat::kBc1 ? bc1 : bc3;
    const std::vector<BlockTexel> expected = decodeProbe(format, decoding);
    if (measured.size() != expected.size()) return false;
    for (size_t i = 0; i < expected.size(); ++i)
      for (int c = 0; c < 4; ++c)
        if (unorm8Of(measured[i][c]) != expected[i][size_t(c)]) return false;
  }
  return true;
}

std::vector<std::byte> decodingProbeBlocks(PixelFormat format) {
  // Random blocks (a fixed seed, mt19937 is the same everywhere): both orders of the end points
  // in about half of them each, so BC1's three-colour mode and both BC3 alpha modes show, and
  // every index. Equal end points come in the first block of each row, where every rule agrees.
  std::mt19937 random(format == PixelFormat::kBc1 ? 1u : 3u);
  const size_t bytes = blockBytes(format);
  std::vector<std::byte> blocks(size_t{kBlocksPerSide} * kBlocksPerSide * bytes);
  for (std::byte& b : blocks) b = static_cast<std::byte>(random() & 0xff);
  for (int row = 0; row < kBlocksPerSide; ++row) {
    std::byte* block = blocks.data() + size_t(row) * kBlocksPerSide * bytes;
    std::byte* colour = format == PixelFormat::kBc1 ? block : block + 8;
    colour[2] = colour[0];
    colour[3] = colour[1];
    if (format == PixelFormat::kBc3) block[1] = block[0];
  }
  return blocks;
}

std::vector<BlockTexel> decodeProbe(PixelFormat format, BlockDecoding decoding) {
  std::vector<std::byte> rgba(size_t{kDecodingProbeSide} * kDecodingProbeSide * 4);
  decodeBlocks(format, kDecodingProbeSide, decodingProbeBlocks(format), rgba, decoding);
  std::vector<BlockTexel> texels(rgba.size() / 4);
  for (size_t i = 0; i < rgba.size(); ++i) texels[i / 4][i % 4] = std::to_integer<uint8_t>(rgba[i]);
  return texels;
}

DecodingFit fitBlockDecoding() {
  DecodingFit fit;
  const PixelFormat formats[] = {PixelFormat::kBc1, PixelFormat::kBc3};
  std::vector<std::vector<glm::vec4>> measured;
  for (const PixelFormat format : formats) measured.push_back(drawDecodingProbe(format));

  // Every member against every texel; the alpha rules on BC3's alpha only.
  std::vector<MemberResult> colours, alphas;
  constexpr uint64_t kTexels = uint64_t{kDecodingProbeSide} * kDecodingProbeSide;
  const uint64_t colourProbes = 2 * kTexels * 3, alphaProbes = kTexels;
  for (const auto& [rule, name] : kPaletteRuleNames) {
    uint64_t colourMisses = 0, alphaMisses = 0;
    for (size_t f = 0; f < 2; ++f) {
      const std::vector<BlockTexel> expected =
          decodeProbe(formats[f], {rule, PaletteRule::kNearest});
      const std::vector<BlockTexel> expectedAlpha =
          isAlphaRule(rule) ? decodeProbe(formats[f], {PaletteRule::kNearest, rule})
                            : std::vector<BlockTexel>{};
      for (size_t i = 0; i < expected.size(); ++i) {
        for (int c = 0; c < 3; ++c)
          colourMisses += unorm8Of(measured[f][i][c]) != expected[i][size_t(c)];
        if (formats[f] == PixelFormat::kBc3 && isAlphaRule(rule))
          alphaMisses += unorm8Of(measured[f][i][3]) != expectedAlpha[i][3];
      }
    }
    colours.push_back({ruleName(rule), colourMisses});
    if (isAlphaRule(rule)) alphas.push_back({ruleName(rule), alphaMisses});
  }
  fit.colour = ParameterFit{"block_decoding",
                            "texelFetch of every texel of a 64 x 64 BC1 and a 64 x 64 BC3 texture "
                            "of random blocks: RGB",
                            colourProbes, colours};
  fit.alpha = ParameterFit{"block_decoding_alpha",
                           "texelFetch of every texel of a 64 x 64 BC3 texture of random blocks: "
                           "alpha",
                           alphaProbes, alphas};
  fit.decoding.colour = kPaletteRuleNames[fit.colour.choose()].value;
  const size_t alphaIndex = fit.alpha.choose();
  size_t seen = 0;
  for (const auto& [rule, name] : kPaletteRuleNames)
    if (isAlphaRule(rule) && seen++ == alphaIndex) fit.decoding.alpha = rule;

  // Every channel against what any conforming decoder may return there.
  for (size_t f = 0; f < 2; ++f) {
    const std::vector<std::byte> blocks = decodingProbeBlocks(formats[f]);
    const size_t bytes = blockBytes(formats[f]);
    for (int y = 0; y < kDecodingProbeSide; ++y)
      for (int x = 0; x < kDecodingProbeSide; ++x) {
        const size_t block = size_t(y / 4) * kBlocksPerSide + size_t(x / 4);
        const std::array<BlockTexel, 2> range = decodeTexelRange(
            formats[f], blocks.data() + block * bytes, static_cast<uint32_t>((y % 4) * 4 + x % 4));
        const glm::vec4 v = measured[f][size_t(y) * kDecodingProbeSide + size_t(x)];
        for (int c = 0; c < 4; ++c) {
          const int k = unorm8Of(v[c]);
          fit.outsideRange += k < range[0][size_t(c)] || k > range[1][size_t(c)];
        }
      }
  }
  for (ParameterFit* part : {&fit.colour, &fit.alpha}) {
    part->unit = "channels beyond every known decoder and the specification's fraction";
    part->largestResidual = part->pinned ? 0 : static_cast<double>(fit.outsideRange);
    part->finding = part->pinned
                        ? part->chosen + ", every texel bit for bit (" + part->memberSummary() + ")"
                        : "no member reproduces every texel, closest " + part->chosen + " (" +
                              part->memberSummary() + ")";
  }
  return fit;
}

}  // namespace vt::calibrate
