#include "calibrate/decoding_fit.h"

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <optional>
#include <random>
#include <span>
#include <string>

#include "probes/probe_draws.h"

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

// The weights member's fit: per step (six sevenths, then four fifths) the whole weights w in
// [0, 4096] with (a0 (4096 - w) + a1 w + 2048) >> 12 equal to every measured value.
struct WeightRanges {
  std::array<int, 10> lo{}, hi{};
  uint64_t samples = 0;
  WeightRanges() {
    lo.fill(0);
    hi.fill(1 << kPaletteWeightBits);
  }
  // One measured value v of step k (1-based) between a0 and a1.
  void add(int a0, int a1, int k, int v) {
    const size_t i = alphaWeightSlot(a0, a1, k);
    ++samples;
    constexpr int kOne = 1 << kPaletteWeightBits;
    // v 4096 <= a0 4096 + d w + 2048 < (v + 1) 4096, with d = a1 - a0.
    const int d = a1 - a0, low = v * kOne - a0 * kOne - kOne / 2, high = low + kOne - 1;
    if (d == 0) {
      if (low > 0 || high < 0) hi[i] = lo[i] - 1;  // no weight gives v
      return;
    }
    const auto floorDiv = [](int n, int m) {
      return n / m - ((n % m != 0) && ((n < 0) != (m < 0)));
    };
    const auto ceilDiv = [&](int n, int m) { return -floorDiv(-n, m); };
    const int from = d > 0 ? ceilDiv(low, d) : ceilDiv(high, d);
    const int to = d > 0 ? floorDiv(high, d) : floorDiv(low, d);
    lo[i] = std::max(lo[i], from);
    hi[i] = std::min(hi[i], to);
  }
  bool consistent() const {
    for (size_t i = 0; i < lo.size(); ++i)
      if (lo[i] > hi[i]) return false;
    return true;
  }
  bool unique() const {
    for (size_t i = 0; i < lo.size(); ++i)
      if (lo[i] != hi[i]) return false;
    return true;
  }
  std::string text() const {
    std::string t;
    for (size_t i = 0; i < lo.size(); ++i) {
      t += (i ? (i == 6 ? "; fifths " : ", ") : "sevenths ");
      t += lo[i] > hi[i]    ? std::string("none")
           : lo[i] == hi[i] ? std::to_string(lo[i])
                            : std::to_string(lo[i]) + " to " + std::to_string(hi[i]);
    }
    return t + " (of 4096)";
  }
};

WeightRanges alphaWeightRanges(const std::vector<glm::vec4>& bc3Measured,
                               const std::optional<std::vector<uint8_t>>& table) {
  WeightRanges ranges;
  if (table) {
    for (int pair = 0; pair < 65536; ++pair) {
      const int a0 = pair >> 8, a1 = pair & 255, n = a0 > a1 ? 7 : 5;
      for (int k = 1; k < n; ++k)
        ranges.add(a0, a1, k, (*table)[static_cast<size_t>(pair) * 6 + static_cast<size_t>(k - 1)]);
    }
    return ranges;
  }
  const std::vector<std::byte> blocks = decodingProbeBlocks(PixelFormat::kBc3);
  for (int y = 0; y < kDecodingProbeSide; ++y)
    for (int x = 0; x < kDecodingProbeSide; ++x) {
      const std::byte* block = blocks.data() + (size_t(y / 4) * kBlocksPerSide + size_t(x / 4)) *
                                                   blockBytes(PixelFormat::kBc3);
      const int a0 = std::to_integer<int>(block[0]), a1 = std::to_integer<int>(block[1]);
      const int index = static_cast<int>(alphaIndex(block, uint32_t((y % 4) * 4 + x % 4)));
      const int n = a0 > a1 ? 7 : 5, k = index - 1;
      if (k < 1 || k >= n) continue;  // an end point, or the five-value mode's 0 and 255
      const int v = unorm8Of(bc3Measured[size_t(y) * kDecodingProbeSide + size_t(x)][3]);
      if (v < 0) {
        ranges.hi[alphaWeightSlot(a0, a1, k)] = -1;  // not an 8-bit value
        continue;
      }
      ranges.add(a0, a1, k, v);
    }
  return ranges;
}

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

namespace {

// Every rule member against every texel, the alpha rules on BC3's alpha only: fit.colour,
// fit.alpha and the rules they choose.
void fitPaletteRules(DecodingFit& fit, std::span<const PixelFormat, 2> formats,
                     const std::vector<std::vector<glm::vec4>>& measured) {
  std::vector<MemberResult> colours, alphas;
  std::vector<PaletteRule> colourRules, alphaRules;  // the rule of each member, in order
  constexpr uint64_t kTexels = uint64_t{kDecodingProbeSide} * kDecodingProbeSide;
  const uint64_t colourProbes = 2 * kTexels * 3, alphaProbes = kTexels;
  for (const auto& [rule, name] : kPaletteRuleNames) {
    uint64_t colourMisses = 0, alphaMisses = 0;
    // The weights member has no weights of its own: fitted below.
    if (rule == PaletteRule::kWeights) continue;
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
    if (isColourRule(rule)) {
      colours.push_back({ruleName(rule), colourMisses});
      colourRules.push_back(rule);
    }
    if (isAlphaRule(rule)) {
      alphas.push_back({ruleName(rule), alphaMisses});
      alphaRules.push_back(rule);
    }
  }
  fit.colour = ParameterFit{"block_decoding",
                            "texelFetch of every texel of a 64 x 64 BC1 and a 64 x 64 BC3 texture "
                            "of random blocks: RGB",
                            colourProbes, colours};
  fit.alpha = ParameterFit{"block_decoding_alpha",
                           "texelFetch of every texel of a 64 x 64 BC3 texture of random blocks: "
                           "alpha",
                           alphaProbes, alphas};
  fit.decoding.colour = colourRules[fit.colour.choose()];
  fit.decoding.alpha = alphaRules[fit.alpha.choose()];
}

// No rule reproduces the alpha: the weights member, where the measured values allow one weight
// per step, taken when it reproduces the BC3 probe. Returns what the values allow, in words.
std::string fitAlphaWeights(DecodingFit& fit, const std::vector<glm::vec4>& measuredBc3) {
  const std::optional<std::vector<uint8_t>> table = denseAlphaTable();
  const WeightRanges ranges = alphaWeightRanges(measuredBc3, table);
  const std::string weightsFinding =
      std::string(table ? "the dense alpha table (every end-point pair, " +
                              std::to_string(ranges.samples) + " values)"
                        : "the probe's alpha") +
      " allows weights " + ranges.text();
  if (!ranges.consistent() || !ranges.unique()) return weightsFinding;
  BlockDecoding weights{PaletteRule::kNearest, PaletteRule::kWeights, {}};
  for (size_t i = 0; i < weights.alphaWeights.size(); ++i)
    weights.alphaWeights[i] = static_cast<uint16_t>(ranges.lo[i]);
  // The weights must reproduce the probe too (the table may come from another draw).
  const std::vector<BlockTexel> expected = decodeProbe(PixelFormat::kBc3, weights);
  uint64_t misses = 0;
  for (size_t i = 0; i < expected.size(); ++i)
    misses += unorm8Of(measuredBc3[i][3]) != expected[i][3];
  fit.alpha.members.push_back({"weights", misses});
  if (misses == 0) {
    fit.alpha.choose();
    fit.decoding.alpha = PaletteRule::kWeights;
    fit.decoding.alphaWeights = weights.alphaWeights;
  }
  return weightsFinding;
}

// Every channel against what any conforming decoder may return there: the channels outside.
uint64_t channelsOutsideRange(std::span<const PixelFormat, 2> formats,
                              const std::vector<std::vector<glm::vec4>>& measured) {
  uint64_t outside = 0;
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
          outside += k < range[0][size_t(c)] || k > range[1][size_t(c)];
        }
      }
  }
  return outside;
}

}  // namespace

DecodingFit fitBlockDecoding() {
  DecodingFit fit;
  const PixelFormat formats[] = {PixelFormat::kBc1, PixelFormat::kBc3};
  std::vector<std::vector<glm::vec4>> measured;
  for (const PixelFormat format : formats) measured.push_back(drawDecodingProbe(format));

  fitPaletteRules(fit, formats, measured);
  const std::string weightsFinding = fit.alpha.pinned ? "" : fitAlphaWeights(fit, measured[1]);
  fit.outsideRange = channelsOutsideRange(formats, measured);
  for (ParameterFit* part : {&fit.colour, &fit.alpha}) {
    part->unit = "channels beyond every known decoder and the specification's fraction";
    part->largestResidual = part->pinned ? 0 : static_cast<double>(fit.outsideRange);
    part->finding = part->pinned
                        ? part->chosen + ", every texel bit for bit (" + part->memberSummary() + ")"
                        : "no member reproduces every texel, closest " + part->chosen + " (" +
                              part->memberSummary() + ")";
  }
  if (!weightsFinding.empty()) fit.alpha.finding += "; " + weightsFinding;
  return fit;
}

}  // namespace vt::calibrate
